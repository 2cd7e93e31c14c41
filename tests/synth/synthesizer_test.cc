#include "bcot/synth/synthesizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/core/sequence.h"
#include "bcot/render/mesh.h"
#include "bcot/synth/synth_appearance.h"
#include "bcot/synth/synth_scene.h"
#include "test_util.h"

namespace bcot {
namespace {

constexpr double kDegToRad = kPi / 180.0;

// ---------------------------------------------------------------------------------------------
// Camera layout.

TEST(SynthSceneTest, ArcAndConeCamerasHaveTheRequestedIncludedAngles) {
  SynthOptions::Cameras options;
  options.arc_angles_deg = {5, 10, 30, 45, 90, 120};
  options.cone_angles_deg = {5, 10, 30, 45, 100};
  const std::vector<SynthCamera> cameras = MakeSynthCameras(options);
  ASSERT_EQ(cameras.size(), 12u);
  const Eigen::Isometry3d& cam0_from_world = cameras[0].cam_from_world;
  const Eigen::Vector3d c0 = cam0_from_world.inverse().translation();
  const Eigen::Vector3d arc_normal = -cam0_from_world.linear().row(1).transpose();  // up
  for (size_t i = 0; i < cameras.size(); ++i) {
    const Eigen::Isometry3d world_from_cam = cameras[i].cam_from_world.inverse();
    // Every camera sits at distance_mm and looks at the target (world origin).
    EXPECT_NEAR(world_from_cam.translation().norm(), options.distance_mm, 1e-9);
    const Eigen::Vector3d axis = world_from_cam.linear().col(2);
    EXPECT_NEAR(axis.dot(-world_from_cam.translation().normalized()), 1.0, 1e-12);
    EXPECT_EQ(cameras[i].camera.name, "cam" + std::to_string(i));
  }
  for (size_t i = 1; i <= options.arc_angles_deg.size(); ++i) {
    EXPECT_EQ(cameras[i].kind, "arc");
    EXPECT_NEAR(IncludedAngleDeg(cam0_from_world, cameras[i].cam_from_world),
                options.arc_angles_deg[i - 1], 1e-9);
    // In the arc plane (through C-0 and the target).
    EXPECT_NEAR(cameras[i].cam_from_world.inverse().translation().dot(arc_normal), 0.0, 1e-9);
  }
  SynthOptions::Cameras arc_only = options;
  arc_only.cone_angles_deg.clear();
  for (size_t k = 0; k < options.cone_angles_deg.size(); ++k) {
    const SynthCamera& cone = cameras[1 + options.arc_angles_deg.size() + k];
    const double alpha = options.cone_angles_deg[k];
    EXPECT_EQ(cone.kind, "cone");
    // The arc position at α (not necessarily one of the arc cameras).
    arc_only.arc_angles_deg = {alpha};
    const SynthCamera arc = MakeSynthCameras(arc_only)[1];
    EXPECT_NEAR(IncludedAngleDeg(cam0_from_world, cone.cam_from_world), alpha, 1e-9);
    EXPECT_NEAR(IncludedAngleDeg(arc.cam_from_world, cone.cam_from_world), alpha, 1e-9);
    // Out of the arc plane, on its upper side.
    EXPECT_GT(cone.cam_from_world.inverse().translation().dot(arc_normal), 1.0);
  }
  // Rig: C-0 is the rig frame.
  const Rig rig = MakeSynthRig(cameras);
  EXPECT_TRUE(rig[0].cam_from_rig.isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  EXPECT_TRUE(rig.Validate().ok());
  EXPECT_GT((c0 - cameras[5].cam_from_world.inverse().translation()).norm(), 1.0);
}

// ---------------------------------------------------------------------------------------------
// Trajectories.

Mesh TestMesh() { return MakeTrefoilKnotMesh(150.0); }

struct Speeds {
  double mean_deg = 0, max_deg = 0, mean_mm = 0, max_mm = 0;
};

Speeds MeasureObjectSpeeds(const SynthMotion& motion, const Mesh& mesh, int num_frames) {
  Speeds s;
  const Eigen::Vector3d centre = mesh.bbox_center();
  for (int f = 1; f < num_frames; ++f) {
    const Eigen::Isometry3d a = motion.WorldFromObject(f - 1), b = motion.WorldFromObject(f);
    const double deg = RotationDistanceDeg(a.linear(), b.linear());
    const double mm = (a * centre - b * centre).norm();
    s.mean_deg += deg / (num_frames - 1);
    s.mean_mm += mm / (num_frames - 1);
    s.max_deg = std::max(s.max_deg, deg);
    s.max_mm = std::max(s.max_mm, mm);
  }
  return s;
}

void ExpectInsideEveryView(const SynthMotion& motion, const std::vector<SynthCamera>& cameras,
                           const Mesh& mesh, int num_frames) {
  for (int f = 0; f < num_frames; ++f) {
    for (size_t c = 0; c < cameras.size(); ++c) {
      const Camera& camera = cameras[c].camera;
      const Eigen::Isometry3d cam_from_object =
          motion.CamFromWorld(static_cast<int>(c), f) * motion.WorldFromObject(f);
      for (const Eigen::Vector3f& v : mesh.vertices()) {
        const Eigen::Vector3d p = cam_from_object * v.cast<double>();
        ASSERT_GT(p.z(), 0.0);
        const Eigen::Vector2d pixel = camera.Project(p);
        ASSERT_TRUE(pixel.x() >= 0 && pixel.y() >= 0 && pixel.x() <= camera.width - 1 &&
                    pixel.y() <= camera.height - 1)
            << "view " << c << " frame " << f << " pixel " << pixel.transpose();
      }
    }
  }
}

TEST(SynthSceneTest, FreeMotionIsSmoothAtTheRequestedSpeedsAndStaysInView) {
  const Mesh mesh = TestMesh();
  for (int seed : {1, 2, 3}) {
    SynthOptions options;
    options.seed = seed;
    options.motion.num_frames = 120;
    options.motion.rotation_deg_per_frame = 3.0;
    options.motion.translation_mm_per_frame = 2.5;
    options.cameras.arc_angles_deg = {45, 90};
    options.cameras.cone_angles_deg = {30};
    options.cameras.distortion = {-0.05, 0.02, 0, 0, 0};
    const std::vector<SynthCamera> cameras = MakeSynthCameras(options.cameras);
    StatusOr<SynthMotion> motion = SynthMotion::Create(options, cameras, mesh);
    ASSERT_TRUE(motion.ok()) << motion.status().message();
    EXPECT_GT(motion->workspace_radius_mm(), 10.0);
    const Speeds s = MeasureObjectSpeeds(*motion, mesh, options.motion.num_frames);
    EXPECT_NEAR(s.mean_deg, 3.0, 0.3 * 3.0) << "seed " << seed;
    EXPECT_NEAR(s.mean_mm, 2.5, 0.3 * 2.5) << "seed " << seed;
    // Smooth: no frame moves more than twice the mean, and the speed changes gradually.
    EXPECT_LT(s.max_deg, 2.0 * 3.0);
    EXPECT_LT(s.max_mm, 2.0 * 2.5);
    for (int f = 2; f < options.motion.num_frames; ++f) {
      const Eigen::Vector3d p0 = motion->WorldFromObject(f - 2) * mesh.bbox_center();
      const Eigen::Vector3d p1 = motion->WorldFromObject(f - 1) * mesh.bbox_center();
      const Eigen::Vector3d p2 = motion->WorldFromObject(f) * mesh.bbox_center();
      EXPECT_LT((p2 - 2 * p1 + p0).norm(), 2.5) << "frame " << f;
    }
    // The object's centre stays in the workspace ball; every vertex stays in every view.
    for (int f = 0; f < options.motion.num_frames; ++f) {
      EXPECT_LE((motion->WorldFromObject(f) * mesh.bbox_center()).norm(),
                motion->workspace_radius_mm() + 1e-6);
    }
    ExpectInsideEveryView(*motion, cameras, mesh, options.motion.num_frames);
    EXPECT_TRUE(CheckObjectInViews(*motion, cameras, mesh, options.motion.num_frames,
                                   options.motion.frustum_margin_px)
                    .ok());
  }
}

TEST(SynthSceneTest, RotateModeOnlyRotatesAboutTheCentre) {
  const Mesh mesh = TestMesh();
  SynthOptions options;
  options.motion.mode = "rotate";
  options.motion.num_frames = 60;
  options.motion.rotation_deg_per_frame = 4.0;
  const std::vector<SynthCamera> cameras = MakeSynthCameras(options.cameras);
  StatusOr<SynthMotion> motion = SynthMotion::Create(options, cameras, mesh);
  ASSERT_TRUE(motion.ok()) << motion.status().message();
  const Speeds s = MeasureObjectSpeeds(*motion, mesh, options.motion.num_frames);
  EXPECT_NEAR(s.mean_deg, 4.0, 0.3 * 4.0);
  EXPECT_LT(s.max_mm, 1e-9);
  ExpectInsideEveryView(*motion, cameras, mesh, options.motion.num_frames);
}

TEST(SynthSceneTest, RigModeKeepsCamFromRigFixedWhileTheRigMoves) {
  const Mesh mesh = TestMesh();
  SynthOptions options;
  options.motion.mode = "rig";
  options.motion.num_frames = 80;
  options.motion.rotation_deg_per_frame = 1.0;
  options.motion.translation_mm_per_frame = 2.0;
  options.cameras.arc_angles_deg = {90};
  const std::vector<SynthCamera> cameras = MakeSynthCameras(options.cameras);
  const Rig rig = MakeSynthRig(cameras);
  StatusOr<SynthMotion> motion = SynthMotion::Create(options, cameras, mesh);
  ASSERT_TRUE(motion.ok()) << motion.status().message();
  double rig_deg = 0.0, rig_mm = 0.0;
  for (int f = 0; f < options.motion.num_frames; ++f) {
    for (int c = 0; c < rig.size(); ++c) {
      const Eigen::Isometry3d cam_from_rig = motion->CamFromWorld(c, f) * motion->WorldFromRig(f);
      EXPECT_TRUE(cam_from_rig.isApprox(rig[c].cam_from_rig, 1e-9)) << "frame " << f;
    }
    if (f > 0) {
      const Eigen::Isometry3d a = motion->WorldFromRig(f - 1), b = motion->WorldFromRig(f);
      rig_deg += RotationDistanceDeg(a.linear(), b.linear()) / (options.motion.num_frames - 1);
      rig_mm += (a.translation() - b.translation()).norm() / (options.motion.num_frames - 1);
    }
    // Ground truth composes: rig_from_object = world_from_rig⁻¹ · world_from_object.
    EXPECT_TRUE(motion->RigFromObject(f).isApprox(
        motion->WorldFromRig(f).inverse() * motion->WorldFromObject(f), 1e-12));
  }
  EXPECT_NEAR(rig_deg, 1.0, 0.3);  // the rig pans at the requested speed
  EXPECT_GT(rig_mm, 5.0);          // and its cameras travel (panning about the look-at point)
  const Speeds s = MeasureObjectSpeeds(*motion, mesh, options.motion.num_frames);
  EXPECT_NEAR(s.mean_deg, 0.2, 0.3 * 0.2);  // object_motion_scale 0.2
  ExpectInsideEveryView(*motion, cameras, mesh, options.motion.num_frames);
}

TEST(SynthSceneTest, ObjectTooLargeForTheViewIsAConfigError) {
  SynthOptions options;
  options.cameras.distance_mm = 150.0;
  const std::vector<SynthCamera> cameras = MakeSynthCameras(options.cameras);
  const StatusOr<SynthMotion> motion = SynthMotion::Create(options, cameras, TestMesh());
  ASSERT_FALSE(motion.ok());
  EXPECT_EQ(motion.status().code(), StatusCode::kInvalidConfig);
}

// ---------------------------------------------------------------------------------------------
// Rendering: the anti-aliased object coverage matches the exact GT silhouette.

// Bilinear sample of a coverage image at an image position (pixel centres at integers).
double SampleCoverage(const cv::Mat1f& image, const Eigen::Vector2d& p) {
  const double x = std::clamp(p.x(), 0.0, image.cols - 1.001);
  const double y = std::clamp(p.y(), 0.0, image.rows - 1.001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double wx = x - x0, wy = y - y0;
  return (1 - wy) * ((1 - wx) * image(y0, x0) + wx * image(y0, x0 + 1)) +
         wy * ((1 - wx) * image(y0 + 1, x0) + wx * image(y0 + 1, x0 + 1));
}

TEST(SynthesizerTest, CoverageEdgesMatchTheGroundTruthSilhouetteAt1280) {
  StatusOr<SynthOptions> read =
      ReadSynthOptions(test::SourcePath("configs/synth/binocular_90_1280.yaml"),
                       {"motion.num_frames=3", "sensor.noise_sigma=0", "sensor.shot_noise_gain=0",
                        "sensor.blur_sigma_px=0", "distractors.count=0"});
  ASSERT_TRUE(read.ok()) << read.status().message();
  StatusOr<std::unique_ptr<SynthWorld>> world = SynthWorld::Create(*read);
  ASSERT_TRUE(world.ok()) << world.status().message();
  const Rig& rig = (*world)->rig();
  ASSERT_EQ(rig.size(), 2);
  ASSERT_TRUE(rig[0].camera.HasDistortion());
  ContourOptions contour_options;
  contour_options.precision_px = 1.0 / 256.0;
  contour_options.sample_spacing_px = 2.0;
  for (int frame = 0; frame < 3; ++frame) {
    for (int view = 0; view < rig.size(); ++view) {
      const SynthViewRender render = (*world)->RenderView(view, frame);
      const Eigen::Isometry3d cam_from_object = (*world)->CamFromObject(view, frame);
      const std::vector<ContourPoint> contour = (*world)->object_caster().ExtractContour(
          rig[view].camera, cam_from_object, contour_options);
      ASSERT_GT(contour.size(), 200u);
      // Along each contour normal the integral of the coverage over [−L, L] is L + e, where
      // e is the coverage edge's offset from the GT contour (exact for a straight edge and
      // any symmetric pixel filter).
      constexpr double kHalf = 3.0, kStep = 0.05;
      std::vector<double> offsets;
      for (const ContourPoint& point : contour) {
        const Eigen::Vector2d inside = point.pixel - kHalf * point.normal;
        const Eigen::Vector2d outside = point.pixel + kHalf * point.normal;
        if (!rig[view].camera.InImage(inside, 2.0) || !rig[view].camera.InImage(outside, 2.0)) {
          continue;
        }
        // Clean profiles only: fully inside at −L and fully outside at +L (skips thin parts
        // and places where another edge is within L).
        if (SampleCoverage(render.coverage, inside) < 0.999 ||
            SampleCoverage(render.coverage, outside) > 0.001) {
          continue;
        }
        double integral = 0.0;
        for (double s = -kHalf + 0.5 * kStep; s < kHalf; s += kStep) {
          integral += kStep * SampleCoverage(render.coverage, point.pixel + s * point.normal);
        }
        offsets.push_back(integral - kHalf);
      }
      ASSERT_GT(offsets.size(), contour.size() / 2) << "view " << view << " frame " << frame;
      double mean_abs = 0.0, mean = 0.0;
      for (double e : offsets) {
        mean_abs += std::abs(e) / offsets.size();
        mean += e / offsets.size();
      }
      std::sort(offsets.begin(), offsets.end());
      EXPECT_LT(mean_abs, 0.1) << "view " << view << " frame " << frame;
      EXPECT_LT(std::abs(mean), 0.03) << "view " << view << " frame " << frame;
      EXPECT_LT(std::abs(offsets[offsets.size() / 2]), 0.05);
      std::printf("view %d frame %d: %zu edge samples, mean |offset| %.4f px, mean %.4f px\n", view,
                  frame, offsets.size(), mean_abs, mean);
    }
  }
}

TEST(SynthesizerTest, ObjectPixelsShowTheObjectColour) {
  SynthOptions options;
  options.cameras.width = 320;
  options.cameras.height = 256;
  options.motion.num_frames = 1;
  options.object.color_rgb = {20, 200, 40};
  options.object.specular = 0.0;
  options.sensor.noise_sigma = 0.0;
  options.sensor.shot_noise_gain = 0.0;
  StatusOr<std::unique_ptr<SynthWorld>> world = SynthWorld::Create(options);
  ASSERT_TRUE(world.ok()) << world.status().message();
  cv::Mat1f coverage;
  const cv::Mat3b image = (*world)->RenderFrame(0, 0, &coverage);
  int inside = 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      if (coverage(r, c) < 1.0f) continue;
      ++inside;
      const cv::Vec3b bgr = image(r, c);
      EXPECT_GT(bgr[1], bgr[0]);  // green object, diffuse only: green dominates
      EXPECT_GT(bgr[1], bgr[2]);
    }
  }
  EXPECT_GT(inside, 500);
}

TEST(SchlickFresnelTest, IsF0HeadOnAndOneAtGrazing) {
  EXPECT_FLOAT_EQ(SchlickFresnel(0.04f, 1.0f), 0.04f);
  EXPECT_FLOAT_EQ(SchlickFresnel(0.04f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(SchlickFresnel(0.04f, -0.3f), 1.0f);  // back-facing normals count as grazing
  float previous = 1.0f;
  for (float c = 0.1f; c <= 1.0f; c += 0.1f) {
    const float f = SchlickFresnel(0.04f, c);
    EXPECT_LT(f, previous);
    previous = f;
  }
  EXPECT_NEAR(SchlickFresnel(0.04f, 0.5f), 0.04f + 0.96f / 32.0f, 1e-6f);
}

// A clear coat mirrors the backdrop with a Fresnel weight that reaches 1 at the silhouette: the
// object's outermost pixels change much more than its interior (which takes F0 = 4 %).
TEST(SynthesizerTest, ClearCoatMirrorsTheBackdropAtTheRim) {
  SynthOptions options;
  options.cameras.width = 320;
  options.cameras.height = 256;
  options.motion.num_frames = 1;
  options.object.specular = 0.0;
  options.sensor.noise_sigma = 0.0;
  options.sensor.shot_noise_gain = 0.0;
  options.sensor.blur_sigma_px = 0.0;
  cv::Mat1f coverage;
  StatusOr<std::unique_ptr<SynthWorld>> plain_world = SynthWorld::Create(options);
  ASSERT_TRUE(plain_world.ok()) << plain_world.status().message();
  const cv::Mat3b plain = (*plain_world)->RenderFrame(0, 0, &coverage);
  options.object.reflectance = 0.04;
  StatusOr<std::unique_ptr<SynthWorld>> coated_world = SynthWorld::Create(options);
  ASSERT_TRUE(coated_world.ok()) << coated_world.status().message();
  const cv::Mat3b coated = (*coated_world)->RenderFrame(0, 0, nullptr);
  double rim_change = 0.0, interior_change = 0.0;
  int rim = 0, interior = 0;
  for (int r = 3; r < coverage.rows - 3; ++r) {
    for (int c = 3; c < coverage.cols - 3; ++c) {
      if (coverage(r, c) < 1.0f) continue;
      double nearest_uncovered = 1.0;  // smallest coverage within 3 px
      for (int dr = -3; dr <= 3; ++dr) {
        for (int dc = -3; dc <= 3; ++dc) {
          nearest_uncovered = std::min(nearest_uncovered, double(coverage(r + dr, c + dc)));
        }
      }
      const cv::Vec3b a = plain(r, c), b = coated(r, c);
      const double change = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
      const bool at_rim = coverage(r - 1, c) < 0.5f || coverage(r + 1, c) < 0.5f ||
                          coverage(r, c - 1) < 0.5f || coverage(r, c + 1) < 0.5f;
      if (at_rim) {
        rim_change += change;
        ++rim;
      } else if (nearest_uncovered == 1.0) {
        interior_change += change;
        ++interior;
      }
    }
  }
  ASSERT_GT(rim, 50);
  ASSERT_GT(interior, 500);
  rim_change /= rim;
  interior_change /= interior;
  std::printf("mean |change| of 8-bit RGB: rim %.1f, interior %.1f\n", rim_change, interior_change);
  // Measured: rim 41.1, interior 12.4 (summed over the channels).
  EXPECT_GT(rim_change, 2.5 * interior_change);
  EXPECT_GT(interior_change, 0.5);  // the coat shows everywhere, weakly
}

// ---------------------------------------------------------------------------------------------
// The written sequence.

SynthOptions TinyOptions(const std::string& mode) {
  SynthOptions options;
  options.seed = 9;
  options.cameras.width = 192;
  options.cameras.height = 160;
  options.cameras.arc_angles_deg = {90};
  options.cameras.cone_angles_deg = {45};
  options.motion.mode = mode;
  options.motion.num_frames = 4;
  options.render.object_samples_per_axis = 2;
  options.render.background_samples_per_axis = 1;
  options.background.kinds = {"cluttered", "plain"};
  options.background.clutter_shapes = 30;
  options.distractors.count = 2;
  options.init.rotation_deg = 4.0;
  options.init.translation_mm = 6.0;
  options.output.write_coverage = true;
  return options;
}

// init_pose.txt is off frame-0's ground truth by exactly `rotation_deg` and, at the object's
// bounding-box centre, `translation_mm`.
void ExpectInitPerturbation(const Sequence& sequence, const Eigen::Isometry3d& truth,
                            double rotation_deg, double translation_mm) {
  ASSERT_TRUE(sequence.init_rig_from_object.has_value());
  const StatusOr<Mesh> mesh = Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  const Eigen::Isometry3d template_from_objcentre = mesh->objcentre_from_template().inverse();
  EXPECT_NEAR(test::RotationErrorDeg(*sequence.init_rig_from_object, truth), rotation_deg, 1e-6);
  EXPECT_NEAR(test::TranslationErrorMm(*sequence.init_rig_from_object * template_from_objcentre,
                                       truth * template_from_objcentre),
              translation_mm, 1e-6);
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

TEST(SynthesizerTest, WritesAConsistentLoadableSequence) {
  test::TempDir dir;
  const std::string out = dir.File("seq");
  const SynthOptions options = TinyOptions("rig");
  int last_done = 0;
  ASSERT_TRUE(Synthesize(options, out, [&](int done, int total) {
                EXPECT_EQ(total, 4);
                last_done = done;
              }).ok());
  EXPECT_EQ(last_done, 4);

  const StatusOr<Sequence> sequence = LoadSequence(out);
  ASSERT_TRUE(sequence.ok()) << sequence.status().message();
  EXPECT_EQ(sequence->num_frames, 4);
  ASSERT_EQ(sequence->rig.size(), 3);
  EXPECT_EQ(sequence->object.name, "knot");
  EXPECT_TRUE(std::filesystem::exists(sequence->object.mesh_path));
  ASSERT_EQ(sequence->timestamps_ns.size(), 4u);
  EXPECT_EQ(sequence->timestamps_ns[3][2], std::llround(3 * 1e9 / options.motion.fps));

  const StatusOr<std::vector<Eigen::Isometry3d>> rig_from_object =
      ReadPoseFile(out + "/gt/rig_from_object.txt");
  ASSERT_TRUE(rig_from_object.ok());
  ASSERT_EQ(rig_from_object->size(), 4u);
  for (int view = 0; view < sequence->rig.size(); ++view) {
    const std::string name = sequence->rig[view].camera.name;
    const StatusOr<std::vector<Eigen::Isometry3d>> cam_from_object =
        ReadPoseFile(out + "/gt/" + name + "/pose.txt");
    ASSERT_TRUE(cam_from_object.ok());
    ASSERT_EQ(cam_from_object->size(), 4u);
    for (int f = 0; f < 4; ++f) {
      const Eigen::Isometry3d expected = sequence->rig[view].cam_from_rig * (*rig_from_object)[f];
      EXPECT_TRUE((*cam_from_object)[f].isApprox(expected, 1e-9)) << name << " frame " << f;
    }
    EXPECT_TRUE(std::filesystem::exists(out + "/gt/" + name + "/coverage_000003.png"));
  }
  // init_pose = GT frame 0 off by exactly the configured magnitudes.
  ExpectInitPerturbation(*sequence, (*rig_from_object)[0], 4.0, 6.0);
  // The resolved config reads back to the same options.
  const StatusOr<SynthOptions> resolved = ReadSynthOptions(out + "/synth.resolved.yaml");
  ASSERT_TRUE(resolved.ok()) << resolved.status().message();
  EXPECT_EQ(FormatSynthOptions(*resolved), FormatSynthOptions(options));

  // Refuses to write into a non-empty directory.
  EXPECT_EQ(Synthesize(options, out).code(), StatusCode::kInvalidConfig);
}

TEST(SynthesizerTest, SameSeedGivesIdenticalFilesAndAnotherSeedDoesNot) {
  test::TempDir dir;
  SynthOptions options = TinyOptions("free");
  options.motion.num_frames = 2;
  options.sensor.motion_blur_subframes = 2;
  ASSERT_TRUE(Synthesize(options, dir.File("a")).ok());
  options.render.threads = 1;  // thread count must not matter
  ASSERT_TRUE(Synthesize(options, dir.File("b")).ok());
  options.seed = 10;
  options.render.threads = 0;
  ASSERT_TRUE(Synthesize(options, dir.File("c")).ok());
  int compared = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.File("a"))) {
    if (!entry.is_regular_file()) continue;
    const std::string relative = std::filesystem::relative(entry.path(), dir.File("a")).string();
    if (relative == "synth.resolved.yaml") continue;  // records render.threads
    EXPECT_EQ(ReadBytes(entry.path().string()), ReadBytes(dir.File("b/" + relative))) << relative;
    ++compared;
  }
  EXPECT_GT(compared, 10);
  EXPECT_NE(ReadBytes(dir.File("a/cam0/000001.png")), ReadBytes(dir.File("c/cam0/000001.png")));
}

TEST(SynthesizerTest, RigMotionMovesTheBackgroundButNotTheRig) {
  SynthOptions options = TinyOptions("rig");
  options.motion.num_frames = 12;
  options.motion.rotation_deg_per_frame = 1.5;
  options.distractors.count = 0;
  StatusOr<std::unique_ptr<SynthWorld>> world = SynthWorld::Create(options);
  ASSERT_TRUE(world.ok()) << world.status().message();
  const SynthViewRender a = (*world)->RenderView(0, 0);
  const SynthViewRender b = (*world)->RenderView(0, 11);
  // Compare background pixels (no object in either render).
  double difference = 0.0;
  int count = 0;
  for (int r = 0; r < a.radiance.rows; ++r) {
    for (int c = 0; c < a.radiance.cols; ++c) {
      if (a.coverage(r, c) > 0 || b.coverage(r, c) > 0) continue;
      difference += cv::norm(a.radiance(r, c) - b.radiance(r, c), cv::NORM_L1);
      ++count;
    }
  }
  ASSERT_GT(count, 1000);
  const double moving = difference / count;
  EXPECT_GT(moving, 0.01);  // the background moved in the image

  // In free mode the background is static.
  options.motion.mode = "free";
  StatusOr<std::unique_ptr<SynthWorld>> fixed = SynthWorld::Create(options);
  ASSERT_TRUE(fixed.ok());
  const SynthViewRender c0 = (*fixed)->RenderView(0, 0);
  const SynthViewRender c1 = (*fixed)->RenderView(0, 11);
  double static_difference = 0.0;
  int static_count = 0;
  for (int r = 0; r < c0.radiance.rows; ++r) {
    for (int c = 0; c < c0.radiance.cols; ++c) {
      if (c0.coverage(r, c) > 0 || c1.coverage(r, c) > 0) continue;
      static_difference += cv::norm(c0.radiance(r, c) - c1.radiance(r, c), cv::NORM_L1);
      ++static_count;
    }
  }
  // Static up to the sampling rate of pixels inside either frame's object box.
  EXPECT_LT(static_difference / static_count, 0.1 * moving);
}

}  // namespace
TEST(SynthesizerTest, PerturbsTheInitPoseAboutTheObjectCentreOfAnOffCentreMesh) {
  // A 100 mm cube whose file origin lies 900 mm away: a rotation about the origin would move
  // the object by ~80 mm for 5°.
  test::TempDir dir;
  const std::string mesh_path = dir.File("far_cube.obj");
  std::string obj;
  for (int corner = 0; corner < 8; ++corner) {
    obj += "v " + std::to_string(900 + 100 * (corner & 1)) + " " +
           std::to_string(100 * ((corner >> 1) & 1)) + " " + std::to_string(100 * (corner >> 2)) +
           "\n";
  }
  obj += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  ASSERT_TRUE(WriteFileAtomic(mesh_path, obj).ok());
  SynthOptions options = TinyOptions("free");
  options.object.mesh = mesh_path;
  options.motion.num_frames = 1;
  options.cameras.cone_angles_deg = {};
  options.output.write_coverage = false;
  options.init.rotation_deg = 5.0;
  options.init.translation_mm = 2.0;
  const std::string out = dir.File("seq");
  ASSERT_TRUE(Synthesize(options, out).ok());
  const StatusOr<Sequence> sequence = LoadSequence(out);
  ASSERT_TRUE(sequence.ok()) << sequence.status().message();
  const StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(out + "/gt/rig_from_object.txt");
  ASSERT_TRUE(truth.ok());
  ExpectInitPerturbation(*sequence, (*truth)[0], 5.0, 2.0);
}

}  // namespace bcot

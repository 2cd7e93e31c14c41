// A small synthetic scene shared by the colour-model, region-template and region-cost tests:
// the spool mesh (150 mm, with its template frame O_t deliberately offset from the
// object-centred frame O_o), a 640×480 camera on a rig, and an image of a uniformly coloured,
// shaded object in front of a textured, noisy background (anti-aliased by 4×4 supersampling).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/se3.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "test_util.h"

namespace bcot::test {

inline Mesh TestSpoolMesh() {
  const StatusOr<Mesh> spool = Mesh::Load(SourcePath("data/meshes/spool.off"), 150.0);
  BCOT_CHECK(spool.ok());
  // Shift the file's frame so that objcentre_from_template is not the identity.
  Eigen::Isometry3d shifted_from_file = Eigen::Isometry3d::Identity();
  shifted_from_file.translation() = Eigen::Vector3d(12.0, -8.0, 5.0);
  return spool->Transformed(shifted_from_file);
}

inline Camera TestCamera() { return Camera("cam0", 640, 480, 550.0, 552.0, 319.5, 239.5); }

// A rig whose frame is not the camera's: cam_from_rig rotates 0.1 rad about y and shifts.
inline Eigen::Isometry3d TestCamFromRig() {
  Eigen::Isometry3d cam_from_rig = Eigen::Isometry3d::Identity();
  cam_from_rig.linear() = ExpSO3(Eigen::Vector3d(0.0, 0.1, 0.02));
  cam_from_rig.translation() = Eigen::Vector3d(20.0, -5.0, 10.0);
  return cam_from_rig;
}

// rig_from_objcentre placing the object at `cam_from_objcentre` in the test camera.
inline Eigen::Isometry3d RigFromObjcentre(const Eigen::Isometry3d& cam_from_objcentre) {
  return TestCamFromRig().inverse() * cam_from_objcentre;
}

inline Eigen::Isometry3d MakeCamFromObjcentre(const Eigen::Vector3d& rotation_vector,
                                              const Eigen::Vector3d& translation_mm) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = ExpSO3(rotation_vector);
  transform.translation() = translation_mm;
  return transform;
}

// A 5° / 10 mm perturbation (or `degrees` / `mm`) about a seeded random axis and direction.
inline Eigen::Isometry3d Perturb(const Eigen::Isometry3d& truth, unsigned seed,
                                 double degrees = 5.0, double mm = 10.0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  const Eigen::Vector3d direction =
      Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  Eigen::Isometry3d perturbed = truth;
  perturbed.linear() = truth.linear() * ExpSO3(axis * degrees * kPi / 180.0);
  perturbed.translation() += mm * direction;
  return perturbed;
}

inline cv::Vec3f BackgroundColor(double x, double y) {
  // Blue/green texture with stripes and blobs; the object is red.
  return cv::Vec3f(static_cast<float>(70 + 45 * std::sin(x / 13.0) * std::cos(y / 21.0)),
                   static_cast<float>(120 + 60 * std::sin(y / 17.0 + x / 29.0)),
                   static_cast<float>(150 + 50 * std::cos((x + y) / 11.0)));
}

// RGB image of the object at cam_from_objcentre; seeded noise (σ = noise_sigma grey levels).
inline cv::Mat3b RenderTestImage(const RayCaster& caster, const Camera& camera,
                                 const Eigen::Isometry3d& cam_from_objcentre, unsigned seed = 7,
                                 double noise_sigma = 4.0) {
  constexpr int kSamples = 4;
  RenderOptions options;
  options.roi = cv::Rect(0, 0, camera.width, camera.height);
  options.samples_per_axis = kSamples;
  const Eigen::Isometry3d cam_from_template =
      cam_from_objcentre * caster.mesh().objcentre_from_template();
  const RenderedView view = caster.Render(camera, cam_from_template, options);
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, static_cast<float>(noise_sigma));
  cv::Mat3b image(camera.height, camera.width);
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      cv::Vec3f object_sum(0, 0, 0);
      int hits = 0;
      for (int j = 0; j < kSamples; ++j) {
        for (int i = 0; i < kSamples; ++i) {
          const int r = y * kSamples + j;
          const int c = x * kSamples + i;
          if (view.mask(r, c) == 0) continue;
          const float shade = 0.55f + 0.45f * std::abs(view.normal_in_cam(r, c)[2]);
          object_sum += cv::Vec3f(200.0f, 45.0f, 35.0f) * shade;
          ++hits;
        }
      }
      const float coverage = static_cast<float>(hits) / (kSamples * kSamples);
      cv::Vec3f color = (1.0f - coverage) * BackgroundColor(x, y);
      if (hits > 0) color += object_sum * (coverage / hits);
      for (int k = 0; k < 3; ++k) {
        image(y, x)[k] = cv::saturate_cast<uchar>(color[k] + noise(rng));
      }
    }
  }
  return image;
}

// Poses of the Jacobian checks (STYLE.md "Cost functions"): identity-ish, near-π rotation,
// object at the image border (with lens distortion), grazing view. `cam_from_objcentre` is
// the truth of the test image.
struct Scenario {
  std::string name;
  Eigen::Isometry3d cam_from_objcentre;  // truth (the image)
  bool distortion = false;
};

inline std::vector<Scenario> GradientScenarios() {
  return {
      {"near_identity_rotation",
       test::MakeCamFromObjcentre(Eigen::Vector3d(1e-4, -2e-4, 5e-5), {5.0, -3.0, 450.0})},
      {"near_pi_rotation",
       test::MakeCamFromObjcentre((kPi - 1e-2) * Eigen::Vector3d(0.2, 0.9, 0.3).normalized(),
                                  {-10.0, 8.0, 480.0})},
      // The object's centre projects ~15 px from the right border: part of it is cut off.
      {"object_at_image_border",
       test::MakeCamFromObjcentre(Eigen::Vector3d(0.3, 0.5, 0.1), {250.0, 20.0, 450.0}), true},
      // The flanges' flat faces (normal = object x) are seen 3° from edge-on.
      {"grazing_view", test::MakeCamFromObjcentre(Eigen::Vector3d(0.0, 3.0 * kPi / 180.0, 0.0),
                                                  {30.0, -20.0, 420.0})},
  };
}

inline Camera ScenarioCamera(const Scenario& scenario) {
  Camera camera = test::TestCamera();
  if (scenario.distortion) camera.distortion = {-0.12, 0.05, 1e-3, -5e-4, 0.0};
  return camera;
}

inline Vector6d SeededTwist(std::mt19937& rng, double rotation_rad, double translation_mm) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Vector6d twist;
  for (int k = 0; k < 3; ++k) twist[k] = translation_mm * uniform(rng);
  for (int k = 3; k < 6; ++k) twist[k] = rotation_rad * uniform(rng);
  return twist;
}

// The bunny scaled to a 150 mm diameter: asymmetric, so every rotation is observable.
inline Mesh TestBunnyMesh() {
  const StatusOr<Mesh> bunny = Mesh::Load(SourcePath("data/meshes/bunny.obj"), 1.0);
  BCOT_CHECK(bunny.ok());
  return bunny->Transformed(Eigen::Isometry3d::Identity(), 150.0 / bunny->diameter());
}

// A test fixture sharing one mesh (made by `kMakeMesh`) and its ray caster across the suite's
// tests.
template <Mesh (*kMakeMesh)()>
class SharedCasterTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    mesh_ = new Mesh(kMakeMesh());
    caster_ = new RayCaster(*mesh_);
  }
  static void TearDownTestSuite() {
    delete caster_;
    delete mesh_;
    caster_ = nullptr;
    mesh_ = nullptr;
  }
  static inline Mesh* mesh_ = nullptr;
  static inline RayCaster* caster_ = nullptr;
};
using BunnyCasterTest = SharedCasterTest<&TestBunnyMesh>;
using SpoolCasterTest = SharedCasterTest<&TestSpoolMesh>;

// A test fixture with the spool in the test camera at a fixed pose and its rendered image.
class SpoolImageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    mesh_ = std::make_unique<Mesh>(TestSpoolMesh());
    caster_ = std::make_unique<RayCaster>(*mesh_);
    camera_ = TestCamera();
    cam_from_objcentre_ = MakeCamFromObjcentre(Eigen::Vector3d(0.3, 0.5, 0.1), {10.0, -5.0, 450.0});
    image_ = RenderTestImage(*caster_, camera_, cam_from_objcentre_);
  }

  std::unique_ptr<Mesh> mesh_;
  std::unique_ptr<RayCaster> caster_;
  Camera camera_;
  Eigen::Isometry3d cam_from_objcentre_ = Eigen::Isometry3d::Identity();
  cv::Mat3b image_;
};

// Two 640×480 cameras 90° apart looking at an object 450 mm away: the rig frame is camera 0's,
// camera 1 sits on the +x side of the object and looks along −x (rotation −90° about y).
struct BinocularScene {
  Camera camera0 = Camera("left", 640, 480, 550.0, 552.0, 319.5, 239.5);
  Camera camera1 = Camera("right", 640, 480, 548.0, 549.0, 321.0, 241.0);
  Eigen::Isometry3d cam0_from_rig = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d cam1_from_rig = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d rig_from_objcentre = Eigen::Isometry3d::Identity();

  BinocularScene() {
    const Eigen::Vector3d object_in_rig(8.0, -6.0, 450.0);
    Eigen::Isometry3d rig_from_cam1 = Eigen::Isometry3d::Identity();
    rig_from_cam1.linear() = ExpSO3(Eigen::Vector3d(0.0, -kPi / 2.0, 0.0));
    rig_from_cam1.translation() = object_in_rig + Eigen::Vector3d(450.0, 0.0, 0.0);
    cam1_from_rig = rig_from_cam1.inverse();
    rig_from_objcentre.linear() = ExpSO3(Eigen::Vector3d(0.4, -0.7, 0.25));
    rig_from_objcentre.translation() = object_in_rig;
  }
};

// The test images of the object at `rig_from_objcentre` in camera 0 and camera 1 of `scene`,
// with noise seeds `seed` and `seed + 1`.
inline std::vector<cv::Mat3b> RenderViews(const RayCaster& caster, const BinocularScene& scene,
                                          const Eigen::Isometry3d& rig_from_objcentre,
                                          unsigned seed) {
  return {
      RenderTestImage(caster, scene.camera0, scene.cam0_from_rig * rig_from_objcentre, seed),
      RenderTestImage(caster, scene.camera1, scene.cam1_from_rig * rig_from_objcentre, seed + 1)};
}

}  // namespace bcot::test

#include "bcot/export/exporter.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/eval/bcot_layout.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/synth/synthesizer.h"
#include "export/coverage_frames.h"
#include "synth_scenes.h"
#include "test_util.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

// A tiny binocular synthetic sequence (4 frames) with lens distortion. `precise`: 320×256 with
// 4×4 samples per pixel and the frames replaced by the object's exact anti-aliased coverage
// (0..255), so an exported frame is directly comparable with a coverage rendered at the exported
// K and pose; otherwise 160×128, one sample per pixel (for the tests of files and errors).
void SynthesizeSequence(const std::string& out, bool precise) {
  SynthOptions options =
      test::SmallBinocularSynthOptions(precise ? 320 : 160, precise ? 256 : 128, /*num_frames=*/4);
  options.seed = 3;
  // Wide lens, strong barrel distortion: the object's contour moves by pixels.
  options.cameras.hfov_deg = 70.0;
  options.cameras.distance_mm = 400.0;
  options.object.size_mm = 220.0;
  options.cameras.distortion = {-0.3, 0.1, 0.001, -0.001, 0.0};
  options.background.clutter_shapes = 10;
  options.render.object_samples_per_axis = precise ? 4 : 1;
  options.output.write_coverage = precise;
  ASSERT_TRUE(Synthesize(options, out).ok());
  if (!precise) return;
  test::ReplaceFramesWithCoverage(out, 4);
}

class ExporterTest : public ::testing::Test {
 protected:
  void SetUp() override { SynthesizeSequence(Sequence(), Precise()); }
  virtual bool Precise() const { return false; }
  std::string Sequence() const { return dir_.File("seq"); }
  std::string Annotation() const { return dir_.File("seq/gt"); }

  test::TempDir dir_;
};

class ExporterPreciseTest : public ExporterTest {
 protected:
  bool Precise() const override { return true; }
};

// Mean boundary offset (px) between an exported coverage image and the coverage rendered at
// `camera`/`cam_from_object`: Σ|c_exported − c_rendered| / contour length. A silhouette
// displaced by δ px along its normal gives about δ; it also catches scale and distortion
// errors, which displace the contour non-uniformly.
double MeanBoundaryOffsetPx(const cv::Mat1f& exported, const RayCaster& caster,
                            const Camera& camera, const Eigen::Isometry3d& cam_from_object) {
  RenderOptions render;
  render.roi = cv::Rect(0, 0, camera.width, camera.height);
  render.samples_per_axis = 8;
  const RenderedView view = caster.Render(camera, cam_from_object, render);
  cv::Mat mask;
  view.mask.convertTo(mask, CV_32F, 1.0 / 255.0);
  cv::Mat1f rendered;
  cv::resize(mask, rendered, exported.size(), 0, 0, cv::INTER_AREA);
  const double difference = cv::sum(cv::abs(exported - rendered))[0];
  std::vector<std::vector<cv::Point>> contours;
  cv::Mat1b binary = rendered > 0.5f;
  cv::findContours(binary, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
  double length = 0.0;
  for (const auto& contour : contours) length += cv::arcLength(contour, /*closed=*/true);
  EXPECT_GT(length, 50.0);
  return difference / length;
}

TEST_F(ExporterPreciseTest, ExportedFramesAlignWithTheMeshAtTheExportedIntrinsicsAndPoses) {
  test::TempDir out;
  ExportOptions options;
  options.frame_step = 2;
  options.image_scale = 0.5;
  options.cameras = {"cam0", "cam1"};
  options.scene = "outdoor 1";
  options.object = "Knot Part";
  const StatusOr<ExportSummary> summary =
      ExportToBcot(Sequence(), Annotation(), out.path(), options);
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_TRUE(summary->undistorted);
  EXPECT_EQ(summary->frames.size(), 2u);
  EXPECT_EQ(summary->width, 160);
  EXPECT_EQ(summary->height, 128);

  const StatusOr<Mesh> mesh = Mesh::Load(out.File("models/Knot Part.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  const StatusOr<::bcot::Sequence> sequence = LoadSequence(Sequence(), false);
  ASSERT_TRUE(sequence.ok());
  const StatusOr<Mesh> original =
      Mesh::Load(sequence->object.mesh_path, sequence->object.unit_to_mm);
  ASSERT_TRUE(original.ok());
  EXPECT_EQ(mesh->vertices().size(), original->vertices().size());
  EXPECT_NEAR(mesh->diameter(), original->diameter(), 1e-4);
  const RayCaster caster(*mesh);

  // The release reads back with the evaluator's reader.
  const StatusOr<std::vector<BenchmarkSequence>> release = LoadBcotDataset(out.path());
  ASSERT_TRUE(release.ok()) << release.status().message();
  ASSERT_EQ(release->size(), 2u);
  for (int view = 0; view < 2; ++view) {
    const BenchmarkSequence& exported = (*release)[view];
    EXPECT_EQ(exported.scene, fmt::format("outdoor 1_cam{}", view));
    EXPECT_EQ(exported.object, "Knot Part");
    ASSERT_EQ(exported.gt_cam_from_object.size(), 2u);
    const StatusOr<std::vector<Eigen::Isometry3d>> gt =
        ReadPoseFile(fmt::format("{}/cam{}/pose.txt", Annotation(), view));
    ASSERT_TRUE(gt.ok());
    Camera camera = exported.camera;
    camera.width = 160;
    camera.height = 128;
    const Camera expected = sequence->rig[view].camera.Scaled(0.5);
    EXPECT_DOUBLE_EQ(camera.fx, expected.fx);
    EXPECT_DOUBLE_EQ(camera.cx, expected.cx);
    EXPECT_DOUBLE_EQ(camera.cy, expected.cy);
    for (int i = 0; i < 2; ++i) {
      EXPECT_TRUE(exported.gt_cam_from_object[i].isApprox((*gt)[2 * i], 1e-12));
      const cv::Mat image = cv::imread(exported.image_paths[i], cv::IMREAD_COLOR);
      ASSERT_EQ(image.cols, 160);
      ASSERT_EQ(image.rows, 128);
      cv::Mat channel;
      cv::extractChannel(image, channel, 0);
      cv::Mat1f coverage;
      channel.convertTo(coverage, CV_32F, 1.0 / 255.0);
      const double offset =
          MeanBoundaryOffsetPx(coverage, caster, camera, exported.gt_cam_from_object[i]);
      EXPECT_LT(offset, 0.1) << "view " << view << " frame " << i;
      // The criterion has teeth: the same pose a quarter pixel off fails it.
      Camera shifted = camera;
      shifted.cx += 0.25;
      shifted.cy += 0.25;
      const double shifted_offset =
          MeanBoundaryOffsetPx(coverage, caster, shifted, exported.gt_cam_from_object[i]);
      EXPECT_GT(shifted_offset, 0.1);
      // Without undistortion the frame would not align either.
      Camera distorted = camera;
      distorted.distortion = sequence->rig[view].camera.distortion;
      const double distorted_offset =
          MeanBoundaryOffsetPx(coverage, caster, distorted, exported.gt_cam_from_object[i]);
      EXPECT_GT(distorted_offset, 0.1);
      std::printf(
          "view %d frame %d: mean boundary offset %.4f px (K off by 1/4 px: %.4f, "
          "not undistorted: %.4f)\n",
          view, i, offset, shifted_offset, distorted_offset);
    }
  }

  // A second export into the same scene folders needs overwrite.
  EXPECT_EQ(ExportToBcot(Sequence(), Annotation(), out.path(), options).status().code(),
            StatusCode::kInvalidConfig);
  options.overwrite = true;
  EXPECT_TRUE(ExportToBcot(Sequence(), Annotation(), out.path(), options).ok());
}

TEST_F(ExporterTest, UsesRigFromObjectWhenThereIsNoPerCameraPoseFile) {
  test::TempDir annotation;
  ASSERT_TRUE(
      fs::copy_file(Annotation() + "/rig_from_object.txt", annotation.File("rig_from_object.txt")));
  test::TempDir out;
  ExportOptions options;
  options.frame_step = 3;
  options.image_scale = 1.0;
  options.cameras = {"cam1"};
  const StatusOr<ExportSummary> summary =
      ExportToBcot(Sequence(), annotation.path(), out.path(), options);
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->frames, (std::vector<int>{0, 3}));
  // One camera: the scene is the sequence folder's name, the object object.yaml's.
  const StatusOr<std::vector<Eigen::Isometry3d>> exported =
      ReadPoseFile(out.File("seq/knot/pose.txt"));
  const StatusOr<std::vector<Eigen::Isometry3d>> gt = ReadPoseFile(Annotation() + "/cam1/pose.txt");
  ASSERT_TRUE(exported.ok()) << exported.status().message();
  ASSERT_TRUE(gt.ok());
  ASSERT_EQ(exported->size(), 2u);
  EXPECT_THAT((*exported)[1], test::PoseNear((*gt)[3], 1e-9, 1e-9));
  EXPECT_TRUE(fs::exists(out.File("seq/knot/0001.png")));
  EXPECT_FALSE(fs::exists(out.File("seq/knot/0002.png")));
}

TEST_F(ExporterTest, InputAndOptionErrors) {
  test::TempDir out;
  ExportOptions options;
  options.image_scale = 0.3;  // 160·0.3 = 48 but 128·0.3 = 38.4
  StatusOr<ExportSummary> summary = ExportToBcot(Sequence(), Annotation(), out.path(), options);
  EXPECT_EQ(summary.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(summary.status().message(), ::testing::HasSubstr("38.4"));

  options = ExportOptions();
  options.cameras = {"cam7"};
  summary = ExportToBcot(Sequence(), Annotation(), out.path(), options);
  EXPECT_EQ(summary.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(summary.status().message(), ::testing::HasSubstr("cam7"));

  test::TempDir annotation;  // three poses for four frames
  test::WriteText(annotation.File("rig_from_object.txt"),
                  "1 0 0 0 1 0 0 0 1 0 0 500\n1 0 0 0 1 0 0 0 1 0 0 500\n"
                  "1 0 0 0 1 0 0 0 1 0 0 500\n");
  summary = ExportToBcot(Sequence(), annotation.path(), out.path(), ExportOptions());
  EXPECT_EQ(summary.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(summary.status().message(), ::testing::HasSubstr("3 poses"));
  EXPECT_FALSE(fs::exists(out.File("models")));
}

TEST(ExportOptionsTest, ValidateListsEveryViolation) {
  ExportOptions options;
  options.frame_step = 0;
  options.image_scale = 1.5;
  options.cameras = {"cam0", "cam0"};
  options.object = "a/b";
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"frame_step = 0", "image_scale = 1.5", "cameras[1]", "object = 'a/b'"});
}

TEST(ExportOptionsTest, DefaultsAreFullRateAndResolutionThePresetIsTheRelease) {
  const ExportOptions defaults;
  EXPECT_EQ(defaults.format, ExportFormat::kBcot);
  EXPECT_EQ(defaults.frame_step, 1);
  EXPECT_EQ(defaults.image_scale, 1.0);
  EXPECT_TRUE(defaults.cameras.empty());
  EXPECT_TRUE(defaults.Validate().ok());
  StatusOr<ExportOptions> preset = ExportPreset("bcot-release");
  ASSERT_TRUE(preset.ok());
  EXPECT_EQ(preset->frame_step, 2);
  EXPECT_EQ(preset->image_scale, 0.5);
  // Keys set in a config or by --set override the preset; the others keep its values.
  const StatusOr<ExportOptions> read = ReadExportOptions("", {"frame_step=3"}, *preset);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->frame_step, 3);
  EXPECT_EQ(read->image_scale, 0.5);
  preset = ExportPreset("paper");
  EXPECT_EQ(preset.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(preset.status().message(), ::testing::HasSubstr("bcot-release"));
}

TEST(ExportOptionsTest, DescribeExportIsOneLineSayingWhatIsExported) {
  ExportSummary summary;
  summary.cameras = {"cam0"};
  summary.rig_cameras = 2;
  summary.frames = {0, 2, 4};
  summary.sequence_frames = 6;
  summary.frame_step = 2;
  summary.width = 640;
  summary.height = 512;
  summary.source_width = 1280;
  summary.source_height = 1024;
  summary.undistorted = true;
  summary.scene_dirs = {"out/scene"};
  const std::string line = DescribeExport(summary, ExportFormat::kBcot);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  for (const char* part : {"bcot format", "3 of 6 frames", "step 2", "camera cam0 (1 of 2)",
                           "640x512 (scaled from 1280x1024, undistorted)", "out/scene"}) {
    EXPECT_THAT(line, ::testing::HasSubstr(part)) << line;
  }
}

TEST(ExportOptionsTest, ReadsYamlWithOverridesAndRejectsUnknownKeys) {
  test::TempDir dir;
  test::WriteText(dir.File("export.yaml"),
                  "frame_step: 2\nimage_scale: 0.5\ncameras: [left, right]\n");
  StatusOr<ExportOptions> options = ReadExportOptions(dir.File("export.yaml"), {"frame_step=3"});
  ASSERT_TRUE(options.ok()) << options.status().message();
  EXPECT_EQ(options->frame_step, 3);
  EXPECT_EQ(options->cameras, (std::vector<std::string>{"left", "right"}));
  test::WriteText(dir.File("resolved.yaml"), FormatExportOptions(*options));
  const StatusOr<ExportOptions> again = ReadExportOptions(dir.File("resolved.yaml"));
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(FormatExportOptions(*again), FormatExportOptions(*options));

  test::WriteText(dir.File("bad.yaml"), "frame_step: 2\nscale: 0.5\n");
  options = ReadExportOptions(dir.File("bad.yaml"));
  EXPECT_EQ(options.status().code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(options.status().message(), ::testing::HasSubstr("bad.yaml:2"));
}

}  // namespace
}  // namespace bcot

// `bcot export` end to end: defaults and the preset, the BOP format, the summary line and
// --quiet, the quality verdict (exit code 3 unless --include-rejected), one-line errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "bcot/core/pose_io.h"
#include "bcot/core/status.h"
#include "bcot/synth/synthesizer.h"
#include "synth_scenes.h"
#include "test_util.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string Bcot(const std::string& arguments) { return test::BcotBinary() + " " + arguments; }
// A binocular synthetic sequence, 160×128, 3 frames; its gt/ is the annotation.
class ExportCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SynthOptions options = test::SmallBinocularSynthOptions(160, 128, 3);
    options.render.object_samples_per_axis = 1;
    ASSERT_TRUE(Synthesize(options, dir_.File("seq")).ok());
  }
  // `bcot export ANN --sequence seq --out OUT` and `extra`.
  std::string Export(const std::string& annotation, const std::string& out,
                     const std::string& extra = "") const {
    return Bcot("export " + annotation + " --sequence " + dir_.File("seq") + " --out " + out + " " +
                extra);
  }
  cv::Size ImageSize(const std::string& path) const { return cv::imread(path).size(); }

  test::TempDir dir_;
};

TEST_F(ExportCommandTest, DefaultsAreEveryFrameFullResolutionThePresetIsTheRelease) {
  std::string output;
  ASSERT_EQ(test::RunCommand(Export(dir_.File("seq/gt"), dir_.File("full")), &output), 0) << output;
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("bcot format: 3 of 3 frames"));
  EXPECT_THAT(output, HasSubstr("160x128 (full resolution)"));
  EXPECT_THAT(output, HasSubstr("cameras cam0,cam1 (2 of 2)"));
  EXPECT_TRUE(fs::exists(dir_.File("full/models/knot.obj")));
  EXPECT_TRUE(fs::exists(dir_.File("full/seq_cam0/knot/0002.png")));
  EXPECT_EQ(ImageSize(dir_.File("full/seq_cam0/knot/0000.png")), cv::Size(160, 128));
  EXPECT_TRUE(fs::exists(dir_.File("full/seq_cam1/knot/0002.png")));  // every camera

  ASSERT_EQ(test::RunCommand(
                Export(dir_.File("seq/gt"), dir_.File("release"), "--preset bcot-release --quiet"),
                &output),
            0)
      << output;
  EXPECT_EQ(output, "");
  EXPECT_TRUE(fs::exists(dir_.File("release/seq_cam0/knot/0001.png")));  // frames 0, 2
  EXPECT_FALSE(fs::exists(dir_.File("release/seq_cam0/knot/0002.png")));
  EXPECT_EQ(ImageSize(dir_.File("release/seq_cam0/knot/0000.png")), cv::Size(80, 64));
  const StatusOr<std::vector<Eigen::Isometry3d>> poses =
      ReadPoseFile(dir_.File("release/seq_cam0/knot/pose.txt"));
  ASSERT_TRUE(poses.ok());
  EXPECT_EQ(poses->size(), 2u);

  // --config and --set override the preset: configs/export.yaml holds the defaults.
  ASSERT_EQ(test::RunCommand(Export(dir_.File("seq/gt"), dir_.File("configured"),
                                    "--preset bcot-release --set frame_step=2 --config " +
                                        test::SourcePath("configs/export.yaml")),
                             &output),
            0)
      << output;
  EXPECT_THAT(output, HasSubstr("2 of 3 frames"));
  EXPECT_EQ(ImageSize(dir_.File("configured/seq_cam0/knot/0000.png")), cv::Size(160, 128));

  // Exporting again needs --overwrite; errors are one line with the usage exit code.
  EXPECT_EQ(test::RunCommand(Export(dir_.File("seq/gt"), dir_.File("full")), &output), 2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_EQ(
      test::RunCommand(Export(dir_.File("seq/gt"), dir_.File("full"), "--overwrite"), &output), 0)
      << output;
  EXPECT_EQ(test::RunCommand(Export(dir_.File("seq/gt"), dir_.File("x"), "--set image_scale=0.3"),
                             &output),
            2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("image_scale = 0.3"));
  EXPECT_EQ(
      test::RunCommand(Export(dir_.File("seq/gt"), dir_.File("x"), "--preset paper"), &output), 2);
  EXPECT_EQ(test::RunCommand(Export(dir_.File("seq/gt"), dir_.File("x"), "--frames 2:1"), &output),
            2);
  EXPECT_EQ(test::RunCommand(Export(dir_.File("nowhere"), dir_.File("x")), &output), 1);
  EXPECT_EQ(test::CountLines(output), 1) << output;
}

TEST_F(ExportCommandTest, BopSceneWithOneCameraTypePerView) {
  std::string output;
  ASSERT_EQ(test::RunCommand(Export(dir_.File("seq/gt"), dir_.File("bop"),
                                    "--format bop --frames 1:2 --frame-step 1"),
                             &output),
            0)
      << output;
  EXPECT_THAT(output, HasSubstr("bop format: 2 of 3 frames (1..2"));
  EXPECT_THAT(output, HasSubstr("cameras cam0,cam1 (2 of 2)"));
  const std::string scene = dir_.File("bop/test/000000/");
  for (const std::string cam : {"cam0", "cam1"}) {
    for (const std::string& file :
         {"rgb_" + cam + "/000001.png", "mask_" + cam + "/000001_000000.png",
          "mask_visib_" + cam + "/000000_000000.png", "scene_camera_" + cam + ".json",
          "scene_gt_" + cam + ".json", "scene_gt_info_" + cam + ".json"}) {
      EXPECT_TRUE(fs::exists(scene + file)) << file;
    }
    EXPECT_FALSE(fs::exists(scene + "rgb_" + cam + "/000002.png"));
  }
  EXPECT_TRUE(fs::exists(dir_.File("bop/models/obj_000001.ply")));
  EXPECT_TRUE(fs::exists(dir_.File("bop/models/models_info.json")));
}

TEST_F(ExportCommandTest, RejectedAnnotationNeedsIncludeRejected) {
  fs::copy(dir_.File("seq/gt"), dir_.File("ann"), fs::copy_options::recursive);
  test::WriteText(dir_.File("ann/quality.json"),
                  R"({"verdict": "rejected", "reasons": ["cam1: 3 of 3 frames above 2 px"]})");
  std::string output;
  EXPECT_EQ(test::RunCommand(Export(dir_.File("ann"), dir_.File("out"), "--format bop"), &output),
            kExitRejected);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr(dir_.File("ann")));
  EXPECT_THAT(output, HasSubstr("rejected"));
  EXPECT_THAT(output, HasSubstr("--include-rejected"));
  EXPECT_FALSE(fs::exists(dir_.File("out")));

  ASSERT_EQ(
      test::RunCommand(
          Export(dir_.File("ann"), dir_.File("out"), "--format bop --include-rejected"), &output),
      0)
      << output;
  EXPECT_THAT(output, HasSubstr("verdict is rejected"));
  EXPECT_TRUE(fs::exists(dir_.File("out/test/000000/scene_gt_cam0.json")));

  // An accepted verdict exports without the flag; an unreadable quality.json is an error.
  test::WriteText(dir_.File("ann/quality.json"), R"({"verdict": "accepted", "reasons": []})");
  EXPECT_EQ(test::RunCommand(Export(dir_.File("ann"), dir_.File("out2"), "--quiet"), &output), 0)
      << output;
  test::WriteText(dir_.File("ann/quality.json"), "{not json");
  EXPECT_EQ(test::RunCommand(Export(dir_.File("ann"), dir_.File("out3")), &output), 1);
  EXPECT_THAT(output, HasSubstr("quality.json"));
}

}  // namespace
}  // namespace bcot

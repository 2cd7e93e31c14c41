// The parts of bcot init that need no search: --click parsing, the request checks, the output
// file names and the refusal to overwrite, the options' rules. The search itself is tested end
// to end in tests/tools/init_command_test.cc.
#include "bcot/annotate/initializer.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

Sequence TwoCameraSequence() {
  Sequence sequence;
  sequence.rig.Add({Camera("left", 640, 512, 800, 800, 319.5, 255.5), {}});
  sequence.rig.Add({Camera("right", 320, 256, 400, 400, 159.5, 127.5), {}});
  sequence.num_frames = 5;
  return sequence;
}

TEST(InitializerTest, ParsesClicks) {
  const StatusOr<ImageClick> click = ParseImageClick("cam0:312.5,240");
  ASSERT_TRUE(click.ok()) << click.status().message();
  EXPECT_EQ(click->camera, "cam0");
  EXPECT_DOUBLE_EQ(click->pixel.x(), 312.5);
  EXPECT_DOUBLE_EQ(click->pixel.y(), 240.0);
  // A camera name may itself hold a colon; the last one separates the pixel.
  const StatusOr<ImageClick> odd = ParseImageClick("rig:a:-0.25,+7");
  ASSERT_TRUE(odd.ok()) << odd.status().message();
  EXPECT_EQ(odd->camera, "rig:a");
  EXPECT_DOUBLE_EQ(odd->pixel.x(), -0.25);
}

TEST(InitializerTest, MalformedClicksNameTheFlagAndTheText) {
  for (const std::string text : {"cam0", "cam0:", ":1,2", "cam0:1", "cam0:1,2,3", "cam0:1,,2",
                                 "cam0:a,2", "cam0:1;2", "cam0:nan,2", "cam0:inf,2"}) {
    const StatusOr<ImageClick> click = ParseImageClick(text);
    ASSERT_FALSE(click.ok()) << text;
    test::ExpectErrorNaming(click.status(), StatusCode::kInvalidConfig,
                            {"--click '" + text + "'", "expected CAM:X,Y"});
  }
}

TEST(InitializerTest, RequestChecksNameTheFlag) {
  const Sequence sequence = TwoCameraSequence();
  InitRequest request;
  request.clicks = {{"left", {10, 10}}, {"right", {330, 10}}};
  EXPECT_THAT(CheckInitRequest(sequence, request).message(),
              HasSubstr("outside right's 320x256 image"));
  request.clicks = {{"left", {639.5, 511.5}}, {"right", {-0.5, 0}}};  // the image's edges
  EXPECT_TRUE(CheckInitRequest(sequence, request).ok());
  request.clicks = {{"middle", {1, 1}}};
  EXPECT_THAT(CheckInitRequest(sequence, request).message(),
              HasSubstr("no camera 'middle' in the rig (cameras: left, right)"));
  request.clicks = {{"left", {1, 1}}, {"left", {2, 2}}};
  EXPECT_THAT(CheckInitRequest(sequence, request).message(), HasSubstr("clicked twice"));
  request.clicks = {};
  EXPECT_THAT(CheckInitRequest(sequence, request).message(), HasSubstr("give --click"));
  request.clicks = {{"left", {1, 1}}};
  request.frame = 5;
  EXPECT_THAT(CheckInitRequest(sequence, request).message(),
              HasSubstr("--frame 5: the sequence has frames 0..4"));
  request.frame = 0;
  request.distance_mm = 0.0;
  EXPECT_THAT(CheckInitRequest(sequence, request).message(), HasSubstr("--distance-mm 0"));
  request.distance_mm = 600.0;
  EXPECT_TRUE(CheckInitRequest(sequence, request).ok());
  request.clicks.push_back({"right", {1, 1}});
  EXPECT_THAT(CheckInitRequest(sequence, request).message(),
              HasSubstr("--distance-mm applies to a single --click"));
  EXPECT_EQ(CheckInitRequest(sequence, request).code(), StatusCode::kInvalidConfig);
}

TEST(InitializerTest, CandidateFilesSitBesideThePoseFile) {
  InitOutputs outputs;
  outputs.pose_path = "/data/seq/init_pose.txt";
  outputs.num_candidates = 2;
  EXPECT_THAT(InitPosePaths(outputs),
              ElementsAre("/data/seq/init_pose.txt", "/data/seq/init_pose.cand1.txt",
                          "/data/seq/init_pose.cand2.txt"));
}

TEST(InitializerTest, ExistingPoseFilesAreRefusedUnlessOverwrite) {
  test::TempDir dir;
  InitOutputs outputs;
  outputs.pose_path = dir.File("init_pose.txt");
  outputs.num_candidates = 1;
  EXPECT_TRUE(CheckInitOutputs(outputs).ok());
  test::WriteText(dir.File("init_pose.cand1.txt"), "x\n");
  test::ExpectErrorNaming(CheckInitOutputs(outputs), StatusCode::kInvalidConfig,
                          {dir.File("init_pose.cand1.txt") + " exists", "--overwrite"});
  outputs.overwrite = true;
  EXPECT_TRUE(CheckInitOutputs(outputs).ok());
}

TEST(InitializerTest, OptionsRulesNameTheKey) {
  EXPECT_TRUE(InitOptions().Validate().ok());
  InitOptions options;
  options.search.grid_rotations = 10;
  options.search.same_iou = 0.0;
  options.search.max_extent_fraction = 0.01;
  test::ExpectErrorNaming(
      options.Validate(), StatusCode::kInvalidConfig,
      {"init.grid_rotations = 10", "init.same_iou = 0", "init.max_extent_fraction = 0.01"});
  EXPECT_FALSE(options.search.Validate().ok());

  const StatusOr<InitOptions> read = ReadInitOptions(
      test::SourcePath("configs/annotate.yaml"), {"init.grid_rotations=2000", "frame.rounds=3"});
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->search.grid_rotations, 2000);
  EXPECT_EQ(read->annotate.tracker.frame.rounds, 3);
  const StatusOr<InitOptions> bad = ReadInitOptions("", {"init.band_px=-1"});
  ASSERT_FALSE(bad.ok());
  EXPECT_THAT(bad.status().message(), HasSubstr("--set init.band_px = -1"));
}

}  // namespace
}  // namespace bcot

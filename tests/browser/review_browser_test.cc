// The page of `bcot review` in headless Chromium (Debian `chromium`), driven over the DevTools
// protocol by tests/browser/review_page.py (Python's standard library only): on a tiny annotated
// `bcot synth` sequence, clicking the timeline at a chosen frame shows that frame with every
// view's image loaded, → steps on, a listed bad frame (if any) is shown when clicked, and on an
// annotation the trajectory, the mask, a nudge set as a keyframe, the re-annotation around it
// and a drag and the wheel as edits work; on a sequence without init_pose.txt, two clicks give
// an initial pose saved by the page.
// Skipped without Chromium or Python. Screenshots are kept in the test's temporary directory
// while it runs; set BCOT_TEST_ARTIFACTS to a directory to keep them. CTest label: browser.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/review/review_annotation.h"
#include "bcot/review/review_server.h"
#include "bcot/review/review_session.h"
#include "synth_truth.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

const char* kChromium = "/usr/bin/chromium";
constexpr int kFrames = 8;

class ReviewBrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kChromium)) {
      GTEST_SKIP() << kChromium << " not installed (scripts/setup.sh installs it)";
    }
    if (test::RunCommand("python3 --version") != 0) GTEST_SKIP() << "python3 not found";
  }

  // Serves the sequence (and annotation) of `dir`, runs the page driver clicking `frame` and
  // returns what it printed. `clicks` ("cam0:X,Y;cam1:X,Y"): the initialisation flow on frame 0
  // as well.
  static std::string RunPage(const test::TempDir& dir, const std::string& annotation, int frame,
                             const std::string& address_suffix = "",
                             const std::string& clicks = "") {
    const StatusOr<std::unique_ptr<ReviewSession>> session =
        ReviewSession::Load(dir.File("seq"), annotation);
    EXPECT_TRUE(session.ok()) << session.status().message();
    if (!session.ok()) return "";
    ReviewOptions options;
    options.port = 0;
    ReviewServer server(**session, options);
    EXPECT_TRUE(server.Bind().ok());
    server.Start();
    const char* artifacts = std::getenv("BCOT_TEST_ARTIFACTS");
    const std::string shots = artifacts != nullptr ? artifacts : dir.path();
    std::string output;
    const int code = test::RunCommand(
        "timeout 900 python3 " + test::SourcePath("tests/browser/review_page.py") + " " +
            kChromium + " '" + server.Url() + address_suffix + "' " + std::to_string(frame) + " " +
            shots + (clicks.empty() ? "" : " '" + clicks + "'"),
        &output);
    EXPECT_EQ(code, 0) << output;
    EXPECT_THAT(output, HasSubstr("ok: no console messages")) << output;
    return output;
  }

  // The page's edits on the annotation in `annotation` of the `num_frames` frames in dir/seq:
  // nudge, keyframe 0, re-annotation, drag; the files they leave.
  static void ExpectEditsWorked(const test::TempDir& dir, const std::string& annotation,
                                int num_frames, const std::string& output) {
    EXPECT_THAT(output, HasSubstr("ok: nudged frame 0 and set it as keyframe 0")) << output;
    EXPECT_THAT(output, HasSubstr("ok: re-annotated frames 0:")) << output;
    EXPECT_THAT(output, HasSubstr("ok: a drag and the wheel on a view moved the pose")) << output;
    EXPECT_THAT(output, HasSubstr("ok: the edit keys nudge and undo")) << output;
    // The re-annotation finished its files: DONE again, poses for every frame, and the page's
    // timeline shows the new quality.json's errors.
    EXPECT_TRUE(std::filesystem::exists(annotation + "/DONE"));
    const StatusOr<std::string> quality_text = ReadTextFile(annotation + "/quality.json");
    ASSERT_TRUE(quality_text.ok()) << quality_text.status().message();
    const StatusOr<QualityTimeline> quality =
        ParseQualityTimeline(*quality_text, "quality.json", num_frames);
    ASSERT_TRUE(quality.ok()) << quality.status().message();
    std::string shown;
    for (size_t v = 0; v < quality->view_names.size(); ++v) {
      shown += (v > 0 ? " " : "") + quality->view_names[v] + "=" +
               fmt::format("{}", quality->error_px[v][0]);
    }
    EXPECT_THAT(output, HasSubstr("timeline frame 0 after re-annotation: " + shown)) << output;
    const StatusOr<std::vector<Eigen::Isometry3d>> poses =
        ReadPoseFile(annotation + "/rig_from_object.txt");
    ASSERT_TRUE(poses.ok()) << poses.status().message();
    EXPECT_EQ(static_cast<int>(poses->size()), num_frames);
    const StatusOr<std::string> keyframes = ReadTextFile(dir.File("seq/keyframes.txt"));
    ASSERT_TRUE(keyframes.ok()) << keyframes.status().message();
    EXPECT_EQ(keyframes->substr(0, 2), "0 ");
  }

  static void ExpectPageWorks(const test::TempDir& dir, const std::string& annotation, int frame,
                              const std::string& address_suffix = "") {
    const std::string output = RunPage(dir, annotation, frame, address_suffix);
    if (!annotation.empty()) ExpectEditsWorked(dir, annotation, kFrames, output);
  }
};

TEST_F(ReviewBrowserTest, TimelineClickShowsTheFrameOfAnAnnotation) {
  test::TempDir dir;
  test::MakeTinyAnnotatedSequence(dir.File("seq"), kFrames, dir.File("ann"));
  ExpectPageWorks(dir, dir.File("ann"), 5);
}

// A threshold no frame meets: every frame is bad, the list's first entry is clicked too.
TEST_F(ReviewBrowserTest, BadFramesAreListedAndShown) {
  test::TempDir dir;
  test::MakeTinyAnnotatedSequence(dir.File("seq"), kFrames, dir.File("ann"),
                                  "--set quality.threshold_px=0.001");
  ExpectPageWorks(dir, dir.File("ann"), 3);
}

// `bcot review --frame 6` prints the address with #frame=6: the page opens there.
TEST_F(ReviewBrowserTest, AddressNamesTheFirstFrameShown) {
  test::TempDir dir;
  test::MakeTinyAnnotatedSequence(dir.File("seq"), kFrames, dir.File("ann"));
  ExpectPageWorks(dir, dir.File("ann"), 2, "#frame=6");
}

TEST_F(ReviewBrowserTest, SequenceWithoutAnnotation) {
  test::TempDir dir;
  test::MakeTinyAnnotatedSequence(dir.File("seq"), kFrames, "");
  ExpectPageWorks(dir, "", 2);
}

// No init_pose.txt: clicks 2 px off the object's true centre in both views of frame 0, "find
// pose", the best candidate saved as init_pose.txt near the truth.
TEST_F(ReviewBrowserTest, InitialPoseFromTwoClicks) {
  test::TempDir dir;
  const std::string seq = dir.File("seq");
  test::Synthesize(seq,
                   "--set cameras.width=320 --set cameras.height=256 --set motion.num_frames=3"
                   " --set distractors.count=1 --set render.object_samples_per_axis=2");
  std::filesystem::remove(seq + "/init_pose.txt");
  std::string clicks;
  for (int camera = 0; camera < 2; ++camera) {
    const Eigen::Vector2d pixel =
        test::TrueCentrePixel(seq, camera, 0) + Eigen::Vector2d(2.0, -2.0);
    clicks += fmt::format("{}cam{}:{:.2f},{:.2f}", camera ? ";" : "", camera, pixel.x(), pixel.y());
  }
  // --annotation names a directory that does not exist yet: the page annotates into it, then
  // shows it (and the driver goes on with the edits on it).
  const std::string annotation = dir.File("ann");
  const std::string output = RunPage(dir, annotation, 1, "", clicks);
  const StatusOr<std::vector<Eigen::Isometry3d>> saved = ReadPoseFile(seq + "/init_pose.txt");
  ASSERT_TRUE(saved.ok()) << saved.status().message();
  ASSERT_EQ(saved->size(), 1u);
  EXPECT_THAT(saved->front(), test::PoseNear(test::TruePose(seq, 0), 5.0, 10.0));
  EXPECT_THAT(output, HasSubstr("ok: annotated from the page into " + annotation)) << output;
  EXPECT_TRUE(std::filesystem::exists(annotation + "/DONE"));
  const StatusOr<std::vector<Eigen::Isometry3d>> poses =
      ReadPoseFile(annotation + "/rig_from_object.txt");
  ASSERT_TRUE(poses.ok()) << poses.status().message();
  ASSERT_EQ(poses->size(), 3u);
  EXPECT_THAT(poses->back(), test::PoseNear(test::TruePose(seq, 2), 1.0, 2.0));
  ExpectEditsWorked(dir, annotation, 3, output);
}

}  // namespace
}  // namespace bcot

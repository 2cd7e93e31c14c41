// The page of `bcot review` in headless Chromium (Debian `chromium`), driven over the DevTools
// protocol by tests/browser/review_page.py (Python's standard library only): on a tiny annotated
// `bcot synth` sequence, clicking the timeline at a chosen frame shows that frame with every
// view's image loaded, → steps on, a listed bad frame (if any) is shown when clicked, and on an
// annotation the trajectory, the mask and a nudge set as a keyframe work.
// Skipped without Chromium or Python. Screenshots are kept in the test's temporary directory
// while it runs; set BCOT_TEST_ARTIFACTS to a directory to keep them. CTest label: browser.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "bcot/core/file_util.h"
#include "bcot/review/review_server.h"
#include "bcot/review/review_session.h"
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

  // Serves the sequence (and annotation) of `dir` and runs the page driver clicking `frame`.
  static void ExpectPageWorks(const test::TempDir& dir, const std::string& annotation, int frame,
                              const std::string& address_suffix = "") {
    const StatusOr<std::unique_ptr<ReviewSession>> session =
        ReviewSession::Load(dir.File("seq"), annotation);
    ASSERT_TRUE(session.ok()) << session.status().message();
    ReviewOptions options;
    options.port = 0;
    ReviewServer server(**session, options);
    ASSERT_TRUE(server.Bind().ok());
    server.Start();
    const char* artifacts = std::getenv("BCOT_TEST_ARTIFACTS");
    const std::string shots = artifacts != nullptr ? artifacts : dir.path();
    std::string output;
    const int code =
        test::RunCommand("timeout 300 python3 " + test::SourcePath("tests/browser/review_page.py") +
                             " " + kChromium + " '" + server.Url() + address_suffix + "' " +
                             std::to_string(frame) + " " + shots,
                         &output);
    EXPECT_EQ(code, 0) << output;
    EXPECT_THAT(output, HasSubstr("ok: no console messages")) << output;
    if (!annotation.empty()) {
      EXPECT_THAT(output, HasSubstr("ok: nudged frame 0 and set it as keyframe 0")) << output;
      const StatusOr<std::string> keyframes = ReadTextFile(dir.File("seq/keyframes.txt"));
      ASSERT_TRUE(keyframes.ok()) << keyframes.status().message();
      EXPECT_EQ(keyframes->substr(0, 2), "0 ");
    }
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

}  // namespace
}  // namespace bcot

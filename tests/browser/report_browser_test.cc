// Renders report.html and summary.html of a real `bcot batch` run in headless Chromium
// (Debian `chromium`, installed by scripts/setup.sh): the pages load without console messages
// (our pages log nothing, so any console line is an error), their script ran (it sets
// data-report-ready on <body>), and a screenshot is not blank. CTest label: browser.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/status.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const char* kChromium = "/usr/bin/chromium";

class ReportBrowserTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    if (!std::filesystem::exists(kChromium)) return;
    std::string output;
    test::Synthesize(dir_->File("root/seq"),
                     "--set cameras.width=160 --set cameras.height=128"
                     " --set motion.num_frames=4 --set render.object_samples_per_axis=2");
    BCOT_CHECK(test::RunCommand(test::BcotBinary() + " batch --quiet " + dir_->File("root") +
                                    " --out " + dir_->File("out") + " --set frame.rounds=1",
                                &output) == 0);
  }
  static void TearDownTestSuite() { delete dir_; }

  void SetUp() override {
    if (!std::filesystem::exists(kChromium)) {
      GTEST_SKIP() << kChromium << " not installed (scripts/setup.sh installs it)";
    }
  }

  // Runs headless Chromium with a fresh profile; `mode` is --dump-dom or --screenshot=...
  static int Chromium(const std::string& page, const std::string& mode, std::string* dom,
                      std::string* log) {
    test::TempDir profile;
    const std::string command = fmt::format(
        "timeout 120 {} --headless --no-sandbox --disable-gpu --disable-quic "
        "--no-first-run --disable-background-networking --disable-component-update "
        "--disable-sync --user-data-dir={} --enable-logging=stderr --v=0 "
        "--window-size=1000,900 {} file://{} > {} 2> {}",
        kChromium, profile.File("profile"), mode, page, profile.File("stdout"),
        profile.File("stderr"));
    const int code = test::RunCommand(command);
    const StatusOr<std::string> out = ReadTextFile(profile.File("stdout"));
    const StatusOr<std::string> err = ReadTextFile(profile.File("stderr"));
    *dom = out.ok() ? *out : "";
    *log = err.ok() ? *err : "";
    return code;
  }

  static void ExpectRendersCleanly(const std::string& page) {
    ASSERT_TRUE(std::filesystem::exists(page)) << page;
    std::string dom, log;
    ASSERT_EQ(Chromium(page, "--dump-dom", &dom, &log), 0) << log;
    EXPECT_THAT(dom, HasSubstr("data-report-ready=\"yes\"")) << "the page's script did not run";
    EXPECT_THAT(log, Not(HasSubstr(":CONSOLE"))) << log;

    test::TempDir shots;
    const std::string png = shots.File("shot.png");
    ASSERT_EQ(Chromium(page, "--screenshot=" + png, &dom, &log), 0) << log;
    EXPECT_THAT(log, Not(HasSubstr(":CONSOLE"))) << log;
    const cv::Mat shot = cv::imread(png, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(shot.empty()) << "no screenshot";
    cv::Scalar mean, stddev;
    cv::meanStdDev(shot, mean, stddev);
    EXPECT_GT(stddev[0], 10.0) << "blank screenshot (mean " << mean[0] << ")";
    EXPECT_GT(cv::countNonZero(shot < 128), 500) << "hardly any dark pixels (text, plots)";
  }

  static test::TempDir* dir_;
};
test::TempDir* ReportBrowserTest::dir_ = nullptr;

TEST_F(ReportBrowserTest, ReportHtmlLoadsWithoutConsoleErrorsAndIsNotBlank) {
  ExpectRendersCleanly(dir_->File("out/seq/report.html"));
}

TEST_F(ReportBrowserTest, SummaryHtmlLoadsWithoutConsoleErrorsAndIsNotBlank) {
  ExpectRendersCleanly(dir_->File("out/summary.html"));
}

}  // namespace
}  // namespace bcot

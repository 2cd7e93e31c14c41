// `bcot batch` and `bcot report` end to end, including a batch killed with SIGKILL mid-way.
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/status.h"
#include "test_util.h"

extern char** environ;

namespace bcot {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kSequences = 3;
constexpr int kFrames = 4;

class BatchCommandTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    for (int i = 0; i < kSequences; ++i) {
      test::Synthesize(
          dir_->File(fmt::format("root/group{}/seq{}", i % 2, i)),
          "--set cameras.width=160 --set cameras.height=128 --set distractors.count=0" +
              fmt::format(" --set motion.num_frames={} --set seed={}", kFrames, i + 1) +
              " --set render.object_samples_per_axis=2");
    }
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string Batch(const std::string& arguments) {
    return test::BcotBinary() + " batch " + dir_->File("root") + " " + arguments;
  }
  static test::TempDir* dir_;
};
test::TempDir* BatchCommandTest::dir_ = nullptr;

std::vector<std::string> AnnotationDirs(const std::string& out) {
  std::vector<std::string> dirs;
  for (int i = 0; i < kSequences; ++i)
    dirs.push_back(out + fmt::format("/group{}/seq{}", i % 2, i));
  return dirs;
}

int CountDone(const std::string& out) {
  int done = 0;
  for (const std::string& dir : AnnotationDirs(out)) done += fs::exists(dir + "/DONE") ? 1 : 0;
  return done;
}

// Every file under `out` with its final name is complete: poses parse and have one line per
// frame, JSON parses, and a directory holding DONE has every output.
void ExpectNothingHalfWritten(const std::string& out) {
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    if (!entry.is_regular_file()) continue;
    const std::string path = entry.path().string();
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp.") != std::string::npos) continue;  // checked by the caller
    if (name == "pose.txt" || name == "rig_from_object.txt") {
      const StatusOr<std::vector<Eigen::Isometry3d>> poses = ReadPoseFile(path);
      ASSERT_TRUE(poses.ok()) << poses.status().message();
      EXPECT_EQ(poses->size(), static_cast<size_t>(kFrames)) << path;
    } else if (name.size() > 5 && name.substr(name.size() - 5) == ".json") {
      EXPECT_FALSE(nlohmann::json::parse(*ReadTextFile(path), nullptr, false).is_discarded())
          << path;
    } else if (name == "report.html" || name == "summary.html") {
      EXPECT_THAT(*ReadTextFile(path), HasSubstr("</html>")) << path;
    }
  }
  for (const std::string& dir : AnnotationDirs(out)) {
    if (!fs::exists(dir + "/DONE")) continue;
    for (const char* file :
         {"rig_from_object.txt", "cam0/pose.txt", "cam1/pose.txt", "frames.csv", "quality.json",
          "quality.csv", "report.html", "config.resolved.yaml"}) {
      EXPECT_TRUE(fs::exists(dir + "/" + file)) << dir << "/" << file;
    }
  }
}

int CountTempFiles(const std::string& out) {
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    count += entry.path().filename().string().find(".tmp.") != std::string::npos ? 1 : 0;
  }
  return count;
}

TEST_F(BatchCommandTest, KilledMidWayRerunFinishesWithoutRedoingFinishedSequences) {
  test::TempDir work;
  const std::string out = work.File("out");
  const std::string binary = test::BcotBinary();
  const std::string root = dir_->File("root");
  // The annotation setting (edge stage, window) on one job, so sequences finish one after another.
  std::vector<std::string> args = {
      binary,   "batch", root,      "--out",    out,
      "--jobs", "1",     "--quiet", "--config", test::SourcePath("configs/annotate.yaml")};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Kill as soon as the first sequence is complete: the next one is then being written.
  bool exited = false;
  for (int i = 0; i < 6000 && CountDone(out) == 0; ++i) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_FALSE(exited) << "the batch ended before it could be killed";
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  const int done_at_kill = CountDone(out);
  ASSERT_GE(done_at_kill, 1);
  ASSERT_LT(done_at_kill, kSequences) << "nothing was left to resume";
  ExpectNothingHalfWritten(out);

  std::map<std::string, std::pair<std::string, fs::file_time_type>> finished;
  for (const std::string& dir : AnnotationDirs(out)) {
    if (fs::exists(dir + "/DONE")) {
      finished[dir] = {*ReadTextFile(dir + "/DONE"), fs::last_write_time(dir + "/DONE")};
    }
  }
  std::string output;
  const int code = test::RunCommand(Batch("--out " + out + " --jobs 2 --quiet --config " +
                                          test::SourcePath("configs/annotate.yaml")),
                                    &output);
  EXPECT_TRUE(code == 0 || code == 1) << output;
  EXPECT_EQ(code, 0) << output;
  EXPECT_EQ(CountDone(out), kSequences);
  ExpectNothingHalfWritten(out);
  EXPECT_EQ(CountTempFiles(out), 0);
  for (const auto& [dir, done] : finished) {
    EXPECT_EQ(*ReadTextFile(dir + "/DONE"), done.first);
    EXPECT_EQ(fs::last_write_time(dir + "/DONE"), done.second) << dir << " was redone";
  }
  const nlohmann::json summary = nlohmann::json::parse(*ReadTextFile(out + "/summary.json"));
  int skipped = 0;
  for (const auto& entry : summary["sequences"]) skipped += entry["outcome"] == "skipped";
  EXPECT_EQ(skipped, done_at_kill);
  EXPECT_THAT(output, HasSubstr("summary: " + out + "/summary.html"));
}

TEST_F(BatchCommandTest, ShardsConfigErrorsAndReport) {
  test::TempDir work;
  const std::string out = work.File("out");
  std::string output;
  EXPECT_EQ(test::RunCommand(Batch("--out " + out + " --shard 4/4"), &output), 2);
  EXPECT_THAT(output, HasSubstr("--shard 4/4"));
  EXPECT_EQ(test::RunCommand(Batch("--out " + out + " --set frame.roundz=1"), &output), 2);
  EXPECT_THAT(output, HasSubstr("roundz"));
  EXPECT_EQ(test::RunCommand(Batch("--out " + out + " --image-cache-mb -1"), &output), 2);
  EXPECT_THAT(output, HasSubstr("--image-cache-mb"));
  // Shard 1 of 2 of the sorted corpus (group0/seq0, group0/seq2, group1/seq1); the child
  // processes take the image cache's size.
  ASSERT_EQ(
      test::RunCommand(
          Batch("--out " + out + " --shard 1/2 --set frame.rounds=1 --image-cache-mb 0"), &output),
      0)
      << output;
  EXPECT_TRUE(fs::exists(out + "/group0/seq2/DONE"));
  EXPECT_FALSE(fs::exists(out + "/group0/seq0/DONE"));
  EXPECT_FALSE(fs::exists(out + "/group1/seq1/DONE"));
  EXPECT_TRUE(fs::exists(out + "/summary.shard1of2.html"));
  EXPECT_FALSE(fs::exists(out + "/summary.html"));
  // The report of one annotation directory, regenerated with a stricter threshold.
  fs::remove(out + "/group0/seq2/report.html");
  EXPECT_EQ(test::RunCommand(test::BcotBinary() + " report " + out +
                                 "/group0/seq2 --set quality.threshold_px=0.000001",
                             &output),
            kExitRejected)
      << output;
  EXPECT_THAT(output, HasSubstr("rejected"));
  EXPECT_TRUE(fs::exists(out + "/group0/seq2/report.html"));
  // The whole output root: every report and the summary.
  EXPECT_EQ(test::RunCommand(test::BcotBinary() + " report " + out, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("summary.html"));
}

}  // namespace
}  // namespace bcot

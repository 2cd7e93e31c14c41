#include "bcot/annotate/batch.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "bcot/annotate/annotator.h"
#include "bcot/annotate/child_process_runner.h"
#include "bcot/core/file_util.h"
#include "bcot/core/version.h"
#include "test_util.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(BatchTest, FindSequencesMirrorsTheTreeAndStopsAtASequence) {
  test::TempDir root;
  for (const char* dir : {"lab1/a", "lab1/b", "lab2/day3/c", "a/nested"}) {
    test::WriteText(root.File(dir) + "/rig.yaml", "cameras: []\n");
  }
  test::WriteText(root.File("a/nested/inner/rig.yaml"), "cameras: []\n");  // inside a sequence
  test::WriteText(root.File("empty/readme.txt"), "no rig here\n");
  const StatusOr<std::vector<std::string>> found = FindSequences(root.path());
  ASSERT_TRUE(found.ok()) << found.status().message();
  EXPECT_THAT(*found, ElementsAre("a/nested", "lab1/a", "lab1/b", "lab2/day3/c"));
  std::vector<std::string> nested;
  ASSERT_TRUE(FindSequences(root.path(), &nested).ok());
  EXPECT_THAT(nested, ElementsAre("a/nested/inner"));
  EXPECT_EQ(FindSequences(root.File("missing")).status().code(), StatusCode::kNotFound);
}

// Linked sequences and linked folders are found under the links' names (so their outputs are
// written under --out, never through the link into the source data); a link cycle ends.
TEST(BatchTest, FindSequencesFollowsLinksUnderTheirOwnNames) {
  test::TempDir data;
  test::WriteText(data.File("store/seqA/rig.yaml"), "cameras: []\n");
  test::WriteText(data.File("store/group/seqB/rig.yaml"), "cameras: []\n");
  test::TempDir root;
  fs::create_symlink(data.File("store/seqA"), root.File("linked_seq"));
  fs::create_symlink(data.File("store/group"), root.File("linked_group"));
  fs::create_directories(root.File("loop"));
  fs::create_directory_symlink(root.path(), root.File("loop/back"));
  const StatusOr<std::vector<std::string>> found = FindSequences(root.path());
  ASSERT_TRUE(found.ok()) << found.status().message();
  EXPECT_THAT(*found, ElementsAre("linked_group/seqB", "linked_seq"));
}

TEST(BatchTest, OutputInsideTheInputSequencesIsRefused) {
  test::TempDir root;
  test::WriteText(root.File("lab/s1/rig.yaml"), "cameras: []\n");
  const std::vector<std::string> sequences = {"lab/s1"};
  EXPECT_TRUE(CheckOutputOutsideSequences(root.path(), root.File("out"), sequences).ok());
  EXPECT_TRUE(CheckOutputOutsideSequences(root.path(), root.File("lab/ann"), sequences).ok());
  const Status same = CheckOutputOutsideSequences(root.path(), root.path(), sequences);
  EXPECT_EQ(same.code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(same.message(), HasSubstr("inside the sequence folder"));
  EXPECT_FALSE(CheckOutputOutsideSequences(root.path(), root.File("lab/s1/ann"), sequences).ok());
}

TEST(BatchTest, ShardsAreDisjointCompleteAndDeterministic) {
  std::vector<std::string> all;
  for (int i = 0; i < 23; ++i) all.push_back(fmt::format("seq{:02d}", i));
  for (int count : {1, 2, 3, 5, 30}) {
    std::multiset<std::string> seen;
    for (int index = 0; index < count; ++index) {
      const std::vector<std::string> shard = SelectShard(all, index, count);
      EXPECT_EQ(shard, SelectShard(all, index, count));
      EXPECT_LE(shard.size(), all.size() / count + 1);
      seen.insert(shard.begin(), shard.end());
    }
    EXPECT_EQ(seen, std::multiset<std::string>(all.begin(), all.end())) << count;
  }
}

TEST(BatchTest, ParseShardAcceptsKOverNOnly) {
  BatchOptions options;
  ASSERT_TRUE(ParseShard("2/5", &options).ok());
  EXPECT_EQ(options.shard_index, 2);
  EXPECT_EQ(options.shard_count, 5);
  for (const char* bad : {"5/5", "-1/3", "1", "a/b", "1/0", "1/2/3"}) {
    const Status status = ParseShard(bad, &options);
    EXPECT_EQ(status.code(), StatusCode::kInvalidConfig) << bad;
    EXPECT_THAT(status.message(), HasSubstr(bad));
  }
}

TEST(BatchResultTest, ExitCodeIsFailureThenRejectionThenSuccess) {
  BatchResult result;
  result.sequences.resize(2);
  for (BatchSequenceResult& sequence : result.sequences) {
    sequence.outcome = BatchOutcome::kAnnotated;
    sequence.accepted = true;
  }
  EXPECT_EQ(result.ExitCode(), 0);
  result.sequences[1].outcome = BatchOutcome::kSkipped;
  result.sequences[1].accepted = false;
  EXPECT_EQ(result.ExitCode(), kExitRejected);
  result.sequences[0].outcome = BatchOutcome::kFailed;
  EXPECT_EQ(result.ExitCode(), 1);
}

// Two tiny sequences in a tree plus a broken one.
class BatchRunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    for (const char* name : {"lab/s1", "lab/s2"}) {
      test::Synthesize(dir_->File(name),
                       "--set cameras.width=160 --set cameras.height=128 --set motion.num_frames=3"
                       " --set distractors.count=0 --set render.object_samples_per_axis=2");
    }
  }
  static void TearDownTestSuite() { delete dir_; }

  // A private copy of the corpus, with `broken/` (an init pose line of 11 numbers).
  static std::string CopyCorpus(const test::TempDir& into, bool with_broken) {
    fs::create_directories(into.File("root"));
    fs::copy(dir_->File("lab"), into.File("root/lab"), fs::copy_options::recursive);
    if (with_broken) {
      fs::copy(dir_->File("lab/s1"), into.File("root/broken"), fs::copy_options::recursive);
      test::WriteText(into.File("root/broken/init_pose.txt"), "1 0 0 0 1 0 0 0 1 0 0\n");
    }
    return into.File("root");
  }
  static BatchOptions TrackOptions() {
    BatchOptions options;
    options.annotate.tracker.frame.rounds = 1;
    options.jobs = 2;
    return options;
  }
  static test::TempDir* dir_;
};
test::TempDir* BatchRunTest::dir_ = nullptr;

TEST_F(BatchRunTest, FailureIsRecordedAndOthersFinishThenRerunSkipsOrRedoes) {
  test::TempDir work;
  const std::string root = CopyCorpus(work, /*with_broken=*/true);
  const std::string out = work.File("out");
  const StatusOr<BatchResult> first = RunBatch(root, out, TrackOptions());
  ASSERT_TRUE(first.ok()) << first.status().message();
  ASSERT_EQ(first->sequences.size(), 3u);
  EXPECT_EQ(first->sequences[0].relative_path, "broken");
  EXPECT_EQ(first->sequences[0].outcome, BatchOutcome::kFailed);
  EXPECT_THAT(first->sequences[0].error, HasSubstr("init_pose.txt"));
  EXPECT_FALSE(first->all_succeeded());
  for (int i : {1, 2}) {
    EXPECT_EQ(first->sequences[i].outcome, BatchOutcome::kAnnotated);
    EXPECT_TRUE(fs::exists(out + "/" + first->sequences[i].relative_path + "/DONE"));
    EXPECT_TRUE(fs::exists(out + "/" + first->sequences[i].relative_path + "/report.html"));
    EXPECT_TRUE(fs::exists(out + "/" + first->sequences[i].relative_path + "/batch.log"));
  }
  EXPECT_FALSE(fs::exists(out + "/broken/DONE"));
  const nlohmann::json summary = nlohmann::json::parse(*ReadTextFile(out + "/summary.json"));
  EXPECT_EQ(summary["failed"], 1);
  EXPECT_EQ(summary["bcot_version"], BcotVersion());
  EXPECT_EQ(summary["config_hash"], AnnotateConfigHash(TrackOptions().annotate));
  EXPECT_THAT(*ReadTextFile(out + "/summary.html"),
              HasSubstr("bcot " + std::string(BcotVersion())));
  EXPECT_EQ(summary["sequences"][0]["verdict"], "failed");
  EXPECT_TRUE(fs::exists(out + "/summary.html"));

  // Same config: skipped (the broken one is tried again and fails again).
  const StatusOr<BatchResult> second = RunBatch(root, out, TrackOptions());
  ASSERT_TRUE(second.ok());
  EXPECT_EQ(second->sequences[1].outcome, BatchOutcome::kSkipped);
  EXPECT_EQ(second->sequences[2].outcome, BatchOutcome::kSkipped);
  EXPECT_EQ(second->sequences[1].accepted, first->sequences[1].accepted);

  // Changed config: redone. --force: redone even though DONE matches.
  BatchOptions changed = TrackOptions();
  changed.annotate.tracker.frame.iterations = 5;
  const StatusOr<BatchResult> third = RunBatch(root, out, changed);
  EXPECT_EQ(third->sequences[1].outcome, BatchOutcome::kAnnotated);
  EXPECT_EQ(third->sequences[2].outcome, BatchOutcome::kAnnotated);
  changed.force = true;
  EXPECT_EQ(RunBatch(root, out, changed)->sequences[2].outcome, BatchOutcome::kAnnotated);
  changed.force = false;
  EXPECT_EQ(RunBatch(root, out, changed)->sequences[2].outcome, BatchOutcome::kSkipped);

  // Changed input: redone.
  std::string init_pose = *ReadTextFile(root + "/lab/s2/init_pose.txt");
  ASSERT_NE(init_pose.find('\t'), std::string::npos);
  init_pose[init_pose.find('\t')] = ' ';  // same pose, different bytes
  test::WriteText(root + "/lab/s2/init_pose.txt", init_pose);
  const StatusOr<BatchResult> fourth = RunBatch(root, out, changed);
  EXPECT_EQ(fourth->sequences[1].outcome, BatchOutcome::kSkipped);
  EXPECT_EQ(fourth->sequences[2].outcome, BatchOutcome::kAnnotated);
}

// One process per sequence: a sequence whose process crashes (here a stand-in executable that
// kills itself with SIGSEGV for it and runs bcot for the others) is recorded as failed with the
// signal, a bad input with bcot's own message, and the rest is annotated as in-process, with
// the same DONE so that a rerun in either mode skips them.
TEST_F(BatchRunTest, ChildProcessesIsolateACrashingSequence) {
  test::TempDir work;
  const std::string root = CopyCorpus(work, /*with_broken=*/true);
  fs::copy(dir_->File("lab/s1"), root + "/poison", fs::copy_options::recursive);
  const std::string wrapper = work.File("bcot_or_crash.sh");
  test::WriteText(wrapper,
                  "#!/bin/sh\ncase \"$2\" in\n  */poison) echo 'bcot annotate: frame 1/3'; "
                  "kill -SEGV $$ ;;\n  */lab/s1) echo 'bcot annotate: note: cam0: a note' >&2 ;;"
                  "\nesac\nexec " +
                      test::BcotBinary() + " \"$@\"\n");
  fs::permissions(wrapper, fs::perms::owner_all);
  BatchOptions options = TrackOptions();
  options.runner = MakeChildProcessRunner(wrapper);
  const std::string out = work.File("out");
  const StatusOr<BatchResult> result = RunBatch(root, out, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  ASSERT_EQ(result->sequences.size(), 4u);  // broken, lab/s1, lab/s2, poison
  EXPECT_EQ(result->sequences[0].outcome, BatchOutcome::kFailed);
  EXPECT_THAT(result->sequences[0].error, HasSubstr("init_pose.txt"));
  EXPECT_EQ(result->sequences[0].error.find("bcot annotate: error"), std::string::npos);
  for (int i : {1, 2}) {
    EXPECT_EQ(result->sequences[i].outcome, BatchOutcome::kAnnotated) << result->sequences[i].error;
    EXPECT_EQ(result->sequences[i].frames, 3);
    EXPECT_TRUE(fs::exists(out + "/" + result->sequences[i].relative_path + "/DONE"));
    EXPECT_FALSE(
        fs::exists(out + "/" + result->sequences[i].relative_path + "/.batch_config.yaml"));
  }
  EXPECT_EQ(result->sequences[3].relative_path, "poison");
  EXPECT_EQ(result->sequences[3].outcome, BatchOutcome::kFailed);
  EXPECT_THAT(result->sequences[3].error, HasSubstr("killed by signal 11"));
  // A note of the child (AnnotationOutcome::notes) reaches the sequence's batch log.
  EXPECT_THAT(*ReadTextFile(out + "/lab/s1/batch.log"), HasSubstr("note: cam0: a note"));
  EXPECT_FALSE(fs::exists(out + "/poison/DONE"));
  const nlohmann::json summary = nlohmann::json::parse(*ReadTextFile(out + "/summary.json"));
  EXPECT_EQ(summary["failed"], 2);

  // The children wrote the DONE this process would have: an in-process rerun skips them.
  const StatusOr<BatchResult> again = RunBatch(root, out, TrackOptions());
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->sequences[1].outcome, BatchOutcome::kSkipped);
  EXPECT_EQ(again->sequences[2].outcome, BatchOutcome::kSkipped);
}

TEST_F(BatchRunTest, ShardsOfARunCoverTheCorpusOnce) {
  test::TempDir work;
  const std::string root = CopyCorpus(work, /*with_broken=*/false);
  std::set<std::string> done;
  for (int index = 0; index < 2; ++index) {
    BatchOptions options = TrackOptions();
    options.shard_index = index;
    options.shard_count = 2;
    const StatusOr<BatchResult> result = RunBatch(root, work.File("out"), options);
    ASSERT_TRUE(result.ok());
    ASSERT_EQ(result->sequences.size(), 1u);
    EXPECT_EQ(result->sequences[0].outcome, BatchOutcome::kAnnotated);
    EXPECT_TRUE(done.insert(result->sequences[0].relative_path).second);
  }
  EXPECT_EQ(done, (std::set<std::string>{"lab/s1", "lab/s2"}));
}

TEST_F(BatchRunTest, ReportsRegenerateWithoutSolving) {
  test::TempDir work;
  const std::string root = CopyCorpus(work, /*with_broken=*/false);
  const std::string out = work.File("out");
  ASSERT_TRUE(RunBatch(root, out, TrackOptions()).ok());
  const std::string poses = *ReadTextFile(out + "/lab/s1/rig_from_object.txt");
  const std::string done = *ReadTextFile(out + "/lab/s1/DONE");
  fs::remove(out + "/lab/s1/report.html");
  // A threshold no annotation meets: every sequence is rejected now.
  const StatusOr<BatchResult> result =
      RegenerateBatchReports(out, "", {"quality.threshold_px=0.000001"});
  ASSERT_TRUE(result.ok()) << result.status().message();
  ASSERT_EQ(result->sequences.size(), 2u);
  for (const BatchSequenceResult& s : result->sequences) {
    EXPECT_EQ(s.outcome, BatchOutcome::kReported);
    EXPECT_FALSE(s.accepted);
  }
  EXPECT_TRUE(fs::exists(out + "/lab/s1/report.html"));
  EXPECT_EQ(*ReadTextFile(out + "/lab/s1/rig_from_object.txt"), poses);
  EXPECT_EQ(*ReadTextFile(out + "/lab/s1/DONE"), done);
}

}  // namespace
}  // namespace bcot

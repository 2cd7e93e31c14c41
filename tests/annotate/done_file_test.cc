#include "bcot/annotate/done_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "bcot/annotate/batch.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

TEST(DoneFileTest, WrittenRecordReadsBack) {
  test::TempDir dir;
  DoneRecord record;
  record.config_hash = "0123456789abcdef";
  record.input_hash = "fedcba9876543210";
  record.sequence_dir = "/data/captures/lab 1/seq3";  // spaces survive
  record.frames = 120;
  record.failed_frames = 2;
  ASSERT_TRUE(WriteDoneFile(dir.path(), record).ok());
  const StatusOr<DoneRecord> read = ReadDoneFile(dir.path());
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->config_hash, record.config_hash);
  EXPECT_EQ(read->input_hash, record.input_hash);
  EXPECT_EQ(read->sequence_dir, record.sequence_dir);
  EXPECT_EQ(read->frames, 120);
  EXPECT_EQ(read->failed_frames, 2);
  ASSERT_TRUE(RemoveDoneFile(dir.path()).ok());
  EXPECT_FALSE(std::filesystem::exists(dir.File("DONE")));
  EXPECT_TRUE(RemoveDoneFile(dir.path()).ok());  // absent: nothing to do
}

TEST(DoneFileTest, MissingAndMalformedFilesAreNamedErrors) {
  test::TempDir dir;
  const StatusOr<DoneRecord> missing = ReadDoneFile(dir.path());
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(missing.status().message(), HasSubstr("not a finished annotation"));

  test::WriteText(dir.File("DONE"), "config_hash: a\ninput_hash b\n");
  const StatusOr<DoneRecord> no_colon = ReadDoneFile(dir.path());
  EXPECT_EQ(no_colon.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(no_colon.status().message(), HasSubstr("DONE:2:"));

  test::WriteText(dir.File("DONE"), "config_hash: a\ninput_hash: b\nframes: many\n");
  const StatusOr<DoneRecord> bad_count = ReadDoneFile(dir.path());
  EXPECT_THAT(bad_count.status().message(), HasSubstr("DONE:3: frames = 'many'"));

  test::WriteText(dir.File("DONE"), "frames: 3\n");
  EXPECT_THAT(ReadDoneFile(dir.path()).status().message(),
              HasSubstr("needs config_hash and input_hash"));
}

// `bcot report` on a folder holding no finished annotation writes nothing there.
TEST(DoneFileTest, ReportsNeedAFinishedAnnotation) {
  test::TempDir dir;
  test::WriteText(dir.File("lab/notes.txt"), "not an annotation\n");
  const StatusOr<BatchResult> result = RegenerateBatchReports(dir.path(), "", {});
  EXPECT_EQ(result.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(result.status().message(), HasSubstr("no finished annotation"));
  EXPECT_FALSE(std::filesystem::exists(dir.File("summary.json")));
  EXPECT_FALSE(std::filesystem::exists(dir.File("summary.html")));
}

}  // namespace
}  // namespace bcot

#include "bcot/core/file_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "test_util.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

// Names of every entry in `dir`, to prove that no temporary file is left behind.
std::vector<std::string> ListNames(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(ReadTextFileTest, ReturnsBytesUnchanged) {
  test::TempDir dir;
  const std::string content = std::string("line 1\r\nline 2\t\n\0binary", 22) + "\xff";
  test::WriteText(dir.File("a.txt"), content);
  const StatusOr<std::string> read = ReadTextFile(dir.File("a.txt"));
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(*read, content);
}

TEST(ReadTextFileTest, EmptyFileIsEmptyString) {
  test::TempDir dir;
  test::WriteText(dir.File("empty.txt"), "");
  const StatusOr<std::string> read = ReadTextFile(dir.File("empty.txt"));
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(*read, "");
}

TEST(ReadTextFileTest, MissingFileIsNotFoundNamingThePath) {
  test::TempDir dir;
  const StatusOr<std::string> read = ReadTextFile(dir.File("missing.txt"));
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(read.status().message(), HasSubstr(dir.File("missing.txt")));
}

TEST(ReadTextFileTest, DirectoryIsIoError) {
  test::TempDir dir;
  const StatusOr<std::string> read = ReadTextFile(dir.path());
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().code(), StatusCode::kIoError);
  EXPECT_THAT(read.status().message(), HasSubstr("directory"));
}

TEST(WriteFileAtomicTest, CreatesParentsAndWritesExactBytes) {
  test::TempDir dir;
  const std::string path = dir.File("a/b/c/out.txt");
  const std::string content = std::string("x\0y\r\n", 5);
  ASSERT_TRUE(WriteFileAtomic(path, content).ok());
  const StatusOr<std::string> read = ReadTextFile(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(*read, content);
  EXPECT_THAT(ListNames(dir.File("a/b/c")), ElementsAre("out.txt"));
}

TEST(WriteFileAtomicTest, ReplacesExistingFileAndLeavesNoTemporaryFile) {
  test::TempDir dir;
  const std::string path = dir.File("out.txt");
  test::WriteText(path, "a much longer old content that must disappear entirely");
  ASSERT_TRUE(WriteFileAtomic(path, "new").ok());
  EXPECT_EQ(*ReadTextFile(path), "new");
  EXPECT_THAT(ListNames(dir.path()), ElementsAre("out.txt"));
}

TEST(WriteFileAtomicTest, WritesLargeContent) {
  test::TempDir dir;
  std::string content;
  for (int i = 0; i < 200000; ++i) content += static_cast<char>('a' + i % 26);
  ASSERT_TRUE(WriteFileAtomic(dir.File("big.txt"), content).ok());
  EXPECT_EQ(*ReadTextFile(dir.File("big.txt")), content);
}

TEST(WriteFileAtomicTest, TargetIsADirectoryFailsWithoutLeftovers) {
  test::TempDir dir;
  fs::create_directory(dir.File("taken"));
  test::WriteText(dir.File("taken/inside.txt"), "keep");
  const Status status = WriteFileAtomic(dir.File("taken"), "content");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_THAT(status.message(), HasSubstr(dir.File("taken")));
  EXPECT_THAT(ListNames(dir.path()), ElementsAre("taken"));
  EXPECT_EQ(*ReadTextFile(dir.File("taken/inside.txt")), "keep");
}

TEST(WriteFileAtomicTest, ParentIsAFileIsIoError) {
  test::TempDir dir;
  test::WriteText(dir.File("file"), "x");
  const Status status = WriteFileAtomic(dir.File("file/out.txt"), "content");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_THAT(status.message(), HasSubstr(dir.File("file")));
}

TEST(CheckWritableDirectoryTest, CreatesTheDirectoryAndLeavesNothingBehind) {
  test::TempDir dir;
  ASSERT_TRUE(CheckWritableDirectory(dir.File("a/b")).ok());
  EXPECT_TRUE(fs::is_directory(dir.File("a/b")));
  EXPECT_THAT(ListNames(dir.File("a/b")), IsEmpty());
}

TEST(CheckWritableDirectoryTest, UnwritableOrInvalidDirectoryIsIoErrorNamingIt) {
  test::TempDir dir;
  test::WriteText(dir.File("file"), "x");
  const Status under_file = CheckWritableDirectory(dir.File("file/out"));
  EXPECT_EQ(under_file.code(), StatusCode::kIoError);
  EXPECT_THAT(under_file.message(), HasSubstr(dir.File("file")));
  if (fs::is_directory("/proc/self")) {  // /proc accepts no new files, even from root
    const Status proc = CheckWritableDirectory("/proc/self");
    EXPECT_EQ(proc.code(), StatusCode::kIoError);
    EXPECT_THAT(proc.message(), HasSubstr("/proc/self: not writable"));
  }
}

TEST(WriteFileAtomicTest, ReadOnlyDirectoryIsIoError) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  test::TempDir dir;
  fs::create_directory(dir.File("ro"));
  fs::permissions(dir.File("ro"), fs::perms::owner_read | fs::perms::owner_exec);
  const Status status = WriteFileAtomic(dir.File("ro/out.txt"), "content");
  fs::permissions(dir.File("ro"), fs::perms::owner_all);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_THAT(ListNames(dir.File("ro")), IsEmpty());
}

TEST(WriteFileAtomicTest, UncreatableTemporaryFileIsIoError) {
  // /proc accepts no new files, even from root.
  if (!fs::is_directory("/proc/self")) GTEST_SKIP() << "no /proc";
  const Status status = WriteFileAtomic("/proc/self/bcot_out.txt", "content");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_THAT(status.message(), HasSubstr("/proc/self/"));
}

TEST(WriteFileAtomicTest, FilePermissionsFollowUmaskNotPrivateTempMode) {
  test::TempDir dir;
  ASSERT_TRUE(WriteFileAtomic(dir.File("out.txt"), "x").ok());
  struct stat info;
  ASSERT_EQ(::stat(dir.File("out.txt").c_str(), &info), 0);
  // A mkstemp-style temp file would be 0600; outputs must be readable like any other file
  // the user creates (umask permitting, owner read/write at least).
  EXPECT_EQ(info.st_mode & 0600, 0600);
  // Read the umask without changing it (umask() would set it process-wide).
  const StatusOr<std::string> proc_status = ReadTextFile("/proc/self/status");
  ASSERT_TRUE(proc_status.ok());
  const size_t at = proc_status->find("Umask:");
  if (at == std::string::npos) GTEST_SKIP() << "kernel does not report Umask";
  const unsigned mask = std::stoul(proc_status->substr(at + 6), nullptr, 8);
  EXPECT_EQ(info.st_mode & 0777, 0666 & ~mask);
}

TEST(CreateDirectoriesTest, CreatesNestedAndAcceptsExisting) {
  test::TempDir dir;
  ASSERT_TRUE(CreateDirectories(dir.File("x/y/z")).ok());
  EXPECT_TRUE(fs::is_directory(dir.File("x/y/z")));
  EXPECT_TRUE(CreateDirectories(dir.File("x/y/z")).ok());
  EXPECT_TRUE(CreateDirectories("").ok());
}

TEST(CreateDirectoriesTest, FileInTheWayIsIoError) {
  test::TempDir dir;
  test::WriteText(dir.File("x"), "");
  const Status status = CreateDirectories(dir.File("x"));
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_THAT(status.message(), HasSubstr(dir.File("x")));
  EXPECT_FALSE(CreateDirectories(dir.File("x/y")).ok());
}

TEST(ResolveRelativeToTest, ResolvesAgainstTheFilesDirectory) {
  EXPECT_EQ(ResolveRelativeTo("/data/seq/object.yaml", "../models/cat.obj"),
            "/data/seq/../models/cat.obj");
  EXPECT_EQ(ResolveRelativeTo("seq/object.yaml", "cat.obj"), "seq/cat.obj");
  EXPECT_EQ(ResolveRelativeTo("object.yaml", "cat.obj"), "cat.obj");
  EXPECT_EQ(ResolveRelativeTo("/data/seq/object.yaml", "/abs/cat.obj"), "/abs/cat.obj");
  EXPECT_EQ(ResolveRelativeTo("/data/seq/object.yaml", ""), "");
}

TEST(SplitLinesTest, HandlesLfCrlfAndMissingFinalNewline) {
  EXPECT_THAT(SplitLines("a\nb\n"), ElementsAre("a", "b"));
  EXPECT_THAT(SplitLines("a\nb"), ElementsAre("a", "b"));
  EXPECT_THAT(SplitLines("a\r\nb\t\r\n\r\n"), ElementsAre("a", "b\t", ""));
  EXPECT_THAT(SplitLines("\n\n"), ElementsAre("", ""));
  EXPECT_THAT(SplitLines(""), IsEmpty());
  EXPECT_THAT(SplitLines("\xEF\xBB\xBF"
                         "a\r\nb"),
              ElementsAre("a", "b"));
}

TEST(SplitTokensTest, SkipsRunsOfSeparators) {
  EXPECT_THAT(SplitTokens("\t1  2\t\t3\t", " \t"), ElementsAre("1", "2", "3"));
  EXPECT_THAT(SplitTokens("   ", " \t"), IsEmpty());
  EXPECT_THAT(SplitTokens("one", " "), ElementsAre("one"));
}

TEST(TrimWhitespaceTest, TrimsSpacesTabsAndCarriageReturns) {
  EXPECT_EQ(TrimWhitespace(" \t a b \r"), "a b");
  EXPECT_EQ(TrimWhitespace(" \t\r"), "");
  EXPECT_EQ(TrimWhitespace("x"), "x");
}

TEST(ParseDoubleTest, AcceptsDecimalForms) {
  double value = 0.0;
  ASSERT_TRUE(ParseDouble("-0.5", &value));
  EXPECT_EQ(value, -0.5);
  ASSERT_TRUE(ParseDouble("+2.5e-3", &value));
  EXPECT_EQ(value, 2.5e-3);
  ASSERT_TRUE(ParseDouble("1E3", &value));
  EXPECT_EQ(value, 1000.0);
  ASSERT_TRUE(ParseDouble(".25", &value));
  EXPECT_EQ(value, 0.25);
  ASSERT_TRUE(ParseDouble("0.30000000000000004", &value));
  EXPECT_EQ(value, 0.1 + 0.2);
  ASSERT_TRUE(ParseDouble("nan", &value));
  EXPECT_TRUE(std::isnan(value));
}

TEST(ParseDoubleTest, RejectsPartialAndNonNumbers) {
  double value = 7.0;
  for (const char* text :
       {"", "+", "abc", "1.5x", " 1.5", "1.5 ", "1,5", "0x10", "++1", "+-1", "1e999"}) {
    EXPECT_FALSE(ParseDouble(text, &value)) << text;
  }
  EXPECT_EQ(value, 7.0);  // untouched on failure
}

TEST(ParseInt64Test, AcceptsFullRangeAndRejectsOthers) {
  int64_t value = 0;
  ASSERT_TRUE(ParseInt64("9223372036854775807", &value));
  EXPECT_EQ(value, std::numeric_limits<int64_t>::max());
  ASSERT_TRUE(ParseInt64("-42", &value));
  EXPECT_EQ(value, -42);
  ASSERT_TRUE(ParseInt64("+7", &value));
  EXPECT_EQ(value, 7);
  for (const char* text : {"", "1.0", "1e3", "9223372036854775808", "12a", " 1"}) {
    EXPECT_FALSE(ParseInt64(text, &value)) << text;
  }
  EXPECT_EQ(value, 7);
}

}  // namespace
}  // namespace bcot

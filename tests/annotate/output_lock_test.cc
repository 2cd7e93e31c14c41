#include "bcot/annotate/output_lock.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

// flock locks belong to an open file description, so two Acquire calls conflict even within
// one process, as two processes do.
TEST(OutputLockTest, OneHolderAtATime) {
  test::TempDir dir;
  {
    StatusOr<OutputLock> first = OutputLock::Acquire(dir.path());
    ASSERT_TRUE(first.ok()) << first.status().message();
    const StatusOr<OutputLock> second = OutputLock::Acquire(dir.path());
    ASSERT_FALSE(second.ok());
    EXPECT_EQ(second.status().code(), StatusCode::kInvalidInput);
    EXPECT_THAT(second.status().message(), HasSubstr(dir.path()));
    EXPECT_THAT(second.status().message(), HasSubstr("another bcot run is writing"));
    // A moved lock is still held; the moved-from one releases nothing.
    OutputLock moved = std::move(*first);
    EXPECT_FALSE(OutputLock::Acquire(dir.path()).ok());
  }
  EXPECT_TRUE(OutputLock::Acquire(dir.path()).ok());
  EXPECT_TRUE(std::filesystem::exists(dir.File(kOutputLockFileName)));
}

TEST(OutputLockTest, MissingDirectoryIsAnIoErrorNamingTheFile) {
  test::TempDir dir;
  const StatusOr<OutputLock> lock = OutputLock::Acquire(dir.File("missing"));
  ASSERT_FALSE(lock.ok());
  EXPECT_EQ(lock.status().code(), StatusCode::kIoError);
  EXPECT_THAT(lock.status().message(), HasSubstr(dir.File("missing/.bcot.lock")));
}

}  // namespace
}  // namespace bcot

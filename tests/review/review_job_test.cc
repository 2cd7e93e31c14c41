#include "bcot/review/review_job.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <nlohmann/json.hpp>
#include <thread>

namespace bcot {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

// The job's JSON once its state is no longer "running" (at most 30 s).
json WaitForEnd(const ReviewJob& job) {
  for (int attempt = 0; attempt < 3000 && job.Running(); ++attempt) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return json::parse(job.Json());
}

TEST(ReviewJobTest, RunsOneJobAtATimeAndReportsProgress) {
  ReviewJob job;
  EXPECT_EQ(json::parse(job.Json())["state"], "idle");
  std::promise<void> release;
  std::promise<void> reported;
  std::shared_future<void> released = release.get_future().share();
  ASSERT_TRUE(job.Start("first",
                        [&](const ReviewJob::Progress& progress) -> StatusOr<std::string> {
                          progress(2, 5);
                          reported.set_value();
                          released.wait();
                          return std::string("all done");
                        })
                  .ok());
  reported.get_future().wait();
  const json running = json::parse(job.Json());
  EXPECT_EQ(running["name"], "first");
  EXPECT_EQ(running["state"], "running");
  EXPECT_EQ(running["done"], 2);
  EXPECT_EQ(running["total"], 5);
  EXPECT_EQ(running["run"], 1);

  const Status second = job.Start("second", [](const ReviewJob::Progress&) {
    return StatusOr<std::string>(std::string("never"));
  });
  EXPECT_FALSE(second.ok());
  EXPECT_THAT(second.message(), HasSubstr("'first' is still running"));

  release.set_value();
  const json done = WaitForEnd(job);
  EXPECT_EQ(done["state"], "done");
  EXPECT_EQ(done["message"], "all done");

  // After the end, the next job starts; its error ends it as "failed".
  ASSERT_TRUE(job.Start("third",
                        [](const ReviewJob::Progress&) -> StatusOr<std::string> {
                          return Status::InvalidInput("no frames");
                        })
                  .ok());
  const json failed = WaitForEnd(job);
  EXPECT_EQ(failed["name"], "third");
  EXPECT_EQ(failed["state"], "failed");
  EXPECT_EQ(failed["message"], "no frames");
  EXPECT_EQ(failed["run"], 2);
  EXPECT_EQ(failed["done"], 0);
}

// A job still running when the ReviewJob goes away is waited for, not cut off.
TEST(ReviewJobTest, DestructionWaitsForTheRunningJob) {
  bool finished = false;
  {
    ReviewJob job;
    ASSERT_TRUE(job.Start("slow",
                          [&](const ReviewJob::Progress&) -> StatusOr<std::string> {
                            std::this_thread::sleep_for(std::chrono::milliseconds(100));
                            finished = true;
                            return std::string();
                          })
                    .ok());
  }
  EXPECT_TRUE(finished);
}

}  // namespace
}  // namespace bcot

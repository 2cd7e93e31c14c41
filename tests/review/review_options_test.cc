#include "bcot/review/review_options.h"

#include <gtest/gtest.h>

#include "test_util.h"

namespace bcot {
namespace {

TEST(ReviewOptionsTest, DefaultsAreValidAndLoopbackOnly) {
  const ReviewOptions options;
  EXPECT_TRUE(options.Validate().ok());
  EXPECT_TRUE(options.LoopbackOnly());
}

TEST(ReviewOptionsTest, ValidateListsEveryViolation) {
  ReviewOptions options;
  options.host = "";
  options.port = 70000;
  options.jpeg_quality = 0;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"review.host", "review.port = 70000", "review.jpeg_quality = 0"});
}

TEST(ReviewOptionsTest, OnlyLoopbackAddressesAreLoopback) {
  for (const char* address : {"127.0.0.1", "127.1.2.3", "::1", "::ffff:127.0.0.1", "localhost"}) {
    EXPECT_TRUE(IsLoopbackAddress(address)) << address;
  }
  for (const char* address :
       {"0.0.0.0", "192.168.1.2", "10.0.0.1", "::", "128.0.0.1", "127.0.0.1.5", "127.0.0.256",
        "127.0.0", "", "::ffff:10.0.0.1", "example.org"}) {
    EXPECT_FALSE(IsLoopbackAddress(address)) << address;
  }
  ReviewOptions options;
  options.host = "0.0.0.0";
  EXPECT_FALSE(options.LoopbackOnly());
}

}  // namespace
}  // namespace bcot

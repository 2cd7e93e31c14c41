// Test data of the export tests: a synthetic sequence whose frames show the object's exact
// coverage, so an exported image tells where the object is in the exported camera.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

namespace bcot::test {

// Replaces frames 0 … num_frames−1 of cam0 and cam1 in the sequence `dir` (synthesized with
// output.write_coverage) by gt/<camera>/coverage_XXXXXX.png as BGR (0..255).
inline void ReplaceFramesWithCoverage(const std::string& dir, int num_frames) {
  for (const char* camera : {"cam0", "cam1"}) {
    for (int f = 0; f < num_frames; ++f) {
      const cv::Mat gray = cv::imread(fmt::format("{}/gt/{}/coverage_{:06d}.png", dir, camera, f),
                                      cv::IMREAD_GRAYSCALE);
      ASSERT_FALSE(gray.empty()) << dir << " " << camera << " " << f;
      cv::Mat bgr;
      cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
      ASSERT_TRUE(cv::imwrite(fmt::format("{}/{}/{:06d}.png", dir, camera, f), bgr));
    }
  }
}

}  // namespace bcot::test

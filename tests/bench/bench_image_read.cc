// Reading one 960×768 JPEG frame (scripts/bench_image_read.sh runs this and tabulates it):
// bcot's ReadColorImage (the file read in one call, libjpeg-turbo decoding straight into BGR)
// against OpenCV's cv::imread and cv::imdecode of the same file, which decode to RGB and then
// swap the channels. The frame is a smooth shaded gradient with sensor-like noise, written with
// OpenCV at quality 90 (4:2:0), as `bcot synth` and `bcot capture` write frames. One thread.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "bcot/core/file_util.h"
#include "bcot/core/image_io.h"

namespace bcot {
namespace {

// Writes the frame once per process into the temporary directory and returns its path.
const std::string& FramePath() {
  static const std::string path = [] {
    cv::Mat3b image(768, 960);
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        image(y, x) = cv::Vec3b(static_cast<uchar>(60 + x / 8), static_cast<uchar>(40 + y / 6),
                                static_cast<uchar>(90 + (x + y) / 16));
      }
    }
    cv::Mat noise(image.size(), CV_8UC3);
    cv::randn(noise, cv::Scalar::all(0), cv::Scalar::all(6));
    image += noise;
    const std::string file =
        (std::filesystem::temp_directory_path() / "bcot_bench_image_read.jpg").string();
    if (!cv::imwrite(file, image, {cv::IMWRITE_JPEG_QUALITY, 90})) {
      std::fprintf(stderr, "cannot write %s\n", file.c_str());
      std::abort();
    }
    return file;
  }();
  return path;
}

void BM_ReadColorImage(benchmark::State& state) {
  for (auto _ : state) {
    StatusOr<cv::Mat3b> image = ReadColorImage(FramePath());
    if (!image.ok()) state.SkipWithError(image.status().message().c_str());
    benchmark::DoNotOptimize(image);
  }
}
BENCHMARK(BM_ReadColorImage)->Unit(benchmark::kMillisecond);

void BM_OpenCvImread(benchmark::State& state) {
  for (auto _ : state) {
    cv::Mat image = cv::imread(FramePath(), cv::IMREAD_COLOR);
    benchmark::DoNotOptimize(image);
  }
}
BENCHMARK(BM_OpenCvImread)->Unit(benchmark::kMillisecond);

void BM_OpenCvImdecode(benchmark::State& state) {
  const StatusOr<std::string> file = ReadTextFile(FramePath());
  if (!file.ok()) {
    state.SkipWithError(file.status().message().c_str());
    return;
  }
  const std::vector<unsigned char> bytes(file->begin(), file->end());
  for (auto _ : state) {
    cv::Mat image = cv::imdecode(bytes, cv::IMREAD_COLOR);
    benchmark::DoNotOptimize(image);
  }
}
BENCHMARK(BM_OpenCvImdecode)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace bcot

BENCHMARK_MAIN();

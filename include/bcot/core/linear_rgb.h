// Linear (radiance-proportional) RGB from 8-bit images. Optical blur acts on radiance, so the
// centre of a blurred step is found on linear values; decoded with the wrong response it moves
// towards one side of the step (towards the bright side when a linear camera's codes are decoded
// as sRGB: docs/notes/issue12_response.md). The response is the camera's: sRGB for most
// consumer cameras and renderers, a power law (often γ = 1, i.e. linear) for machine-vision
// cameras, a logarithm for log-encoding cameras and film-like view transforms (Blender's
// Filmic is close to log over its middle range).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "bcot/core/status.h"

namespace bcot {

// How an image's 8-bit codes c map to linear values in [0, 1].
struct ImageResponse {
  enum class Kind {
    kSrgb,   // IEC 61966-2-1 decoding
    kGamma,  // (c / 255)^gamma; gamma = 1: a linear camera
    kAuto,   // not known: estimated from the images (optim/response_estimation.h)
    kTable,  // measured: `table` (from `table_file`, ReadResponseTable)
    kLog,    // 2^(log_stops·(c / 255 − 1)) for c > 0, 0 for c = 0: log_stops stops below white
  };
  static constexpr double kMinGamma = 0.2;
  static constexpr double kMaxGamma = 5.0;
  static constexpr double kMinLogStops = 4.0;
  static constexpr double kMaxLogStops = 20.0;
  Kind kind = Kind::kSrgb;
  // Exponent of kGamma; in [kMinGamma, kMaxGamma]. Unused by the other kinds.
  double gamma = 2.2;
  // Stops (factors of 2) the codes 1..255 of kLog span; in [kMinLogStops, kMaxLogStops].
  double log_stops = 10.0;
  // kTable: the linear value of each code 0..255 (non-decreasing, finite, >= 0, last > 0; any
  // scale: LinearTable divides by the last), read from table_file.
  std::string table_file;
  std::vector<float> table;

  static ImageResponse Gamma(double exponent) {
    ImageResponse response;
    response.kind = Kind::kGamma;
    response.gamma = exponent;
    return response;
  }
  static ImageResponse Log(double stops) {
    ImageResponse response;
    response.kind = Kind::kLog;
    response.log_stops = stops;
    return response;
  }
  static ImageResponse Auto() {
    ImageResponse response;
    response.kind = Kind::kAuto;
    return response;
  }

  bool IsValid() const;
  // A response codes can be decoded with (not kAuto).
  bool IsResolved() const { return kind != Kind::kAuto; }
  // "srgb", "gamma 1.8", "log 10", "table <file>" or "auto".
  std::string Name() const;
  // Same kind and, for kGamma, the same exponent, for kLog the same stops, for kTable the same
  // values.
  bool operator==(const ImageResponse& other) const {
    return kind == other.kind && (kind != Kind::kGamma || gamma == other.gamma) &&
           (kind != Kind::kLog || log_stops == other.log_stops) &&
           (kind != Kind::kTable || table == other.table);
  }
  bool operator!=(const ImageResponse& other) const { return !(*this == other); }
};

// A measured response: 256 numbers, the linear value of codes 0, 1, ..., 255 in order, separated
// by white space or line breaks; `#` starts a comment. E.g. the inverse of a camera's response
// curve recovered from an exposure series (OpenCV's CalibrateDebevec), or of a renderer's view
// transform (scripts/response_table.py). Errors name the file and line.
StatusOr<std::vector<float>> ReadResponseTable(const std::string& path);

// The linear value of every 8-bit code under one response. Building it costs 256 powers: build
// once per image or per set of lines, not per sample.
class LinearTable {
 public:
  // `response` must be valid and resolved.
  explicit LinearTable(const ImageResponse& response = ImageResponse());
  float operator[](int code) const { return table_[code]; }

  // The table as a continuous curve (linear between consecutive codes), for codes that are not
  // integers (an image's codes as a codec model predicts them): the linear value of a code in
  // [0, 255] (clamped), and the inverse, the code of a linear value (clamped to [0, 255]), so
  // that Decode(Encode(v)) = v for v in [table[0], 1].
  // Inline: the codec's simulations call them for every drawn node and sampled pixel.
  double Decode(double code) const {
    const double c = std::clamp(code, 0.0, 255.0);
    const int k = std::min(static_cast<int>(c), 254);
    return table_[k] + (c - k) * (table_[k + 1] - table_[k]);
  }
  double Encode(double linear) const {
    if (!(linear > table_[0])) return 0.0;
    if (linear >= table_[255]) return 255.0;
    // table_[k] <= linear < table_[k + 1] (table_[255] = 1, so the bucket exists).
    int k = bucket_code_[std::clamp(static_cast<int>(linear * kBuckets), 0, kBuckets - 1)];
    while (table_[k + 1] <= linear) ++k;
    return k + (linear - table_[k]) / (table_[k + 1] - table_[k]);
  }

 private:
  // Encode's index: for each of kBuckets equal parts [b, b + 1) / kBuckets of [0, 1], the
  // largest code whose value is at most b / kBuckets.
  static constexpr int kBuckets = 1024;
  std::array<float, 256> table_;
  std::array<unsigned char, kBuckets> bucket_code_;
};

// True when bilinear sampling at `p` stays inside an image of `size` (p and its 2×2
// neighbours: 0 <= x < width − 1, 0 <= y < height − 1).
inline bool CanSampleBilinear(const cv::Size& size, const Eigen::Vector2d& p) {
  return p.x() >= 0.0 && p.y() >= 0.0 && p.x() < size.width - 1.0 && p.y() < size.height - 1.0;
}

// Bilinear linear-RGB colour (R, G, B order) of the BGR image at `p`, codes decoded by `table`;
// requires CanSampleBilinear(image.size(), p).
Eigen::Vector3d SampleLinearRgb(const cv::Mat3b& image, const LinearTable& table,
                                const Eigen::Vector2d& p);

// Per channel (R, G, B), the largest linear value among the pixels SampleLinearRgb mixes at `p`
// (those with a non-zero weight): tells whether a sample rests on a clipped pixel. Same
// requirement as SampleLinearRgb.
Eigen::Vector3d PeakLinearRgb(const cv::Mat3b& image, const LinearTable& table,
                              const Eigen::Vector2d& p);

}  // namespace bcot

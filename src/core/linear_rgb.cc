#include "bcot/core/linear_rgb.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "bcot/core/file_util.h"

namespace bcot {

bool ImageResponse::IsValid() const {
  switch (kind) {
    case Kind::kGamma:
      return gamma >= kMinGamma && gamma <= kMaxGamma;
    case Kind::kLog:
      return log_stops >= kMinLogStops && log_stops <= kMaxLogStops;
    case Kind::kTable:
      if (table.size() != 256 || !(table.back() > 0.0f)) return false;
      for (size_t i = 0; i < table.size(); ++i) {
        if (!std::isfinite(table[i]) || table[i] < 0.0f) return false;
        if (i > 0 && table[i] < table[i - 1]) return false;
      }
      return true;
    case Kind::kSrgb:
    case Kind::kAuto:
      break;
  }
  return true;
}

std::string ImageResponse::Name() const {
  switch (kind) {
    case Kind::kSrgb:
      return "srgb";
    case Kind::kGamma:
      return fmt::format("gamma {}", gamma);
    case Kind::kLog:
      return fmt::format("log {}", log_stops);
    case Kind::kTable:
      return "table " + table_file;
    case Kind::kAuto:
      break;
  }
  return "auto";
}

StatusOr<std::vector<float>> ReadResponseTable(const std::string& path) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  std::vector<float> table;
  int line_number = 0;
  for (const std::string& line : SplitLines(text)) {
    ++line_number;
    std::istringstream fields(line.substr(0, line.find('#')));
    std::string field;
    while (fields >> field) {
      char* end = nullptr;
      const double value = std::strtod(field.c_str(), &end);
      if (end == field.c_str() || *end != '\0' || !std::isfinite(value) || value < 0.0) {
        return Status::InvalidInput(fmt::format(
            "{}:{}: '{}' is not a linear value (a finite number >= 0)", path, line_number, field));
      }
      if (!table.empty() && value < table.back()) {
        return Status::InvalidInput(fmt::format(
            "{}:{}: {} is below the value of the code before it: a response must not decrease",
            path, line_number, field));
      }
      table.push_back(static_cast<float>(value));
    }
  }
  if (table.size() != 256 || !(table.back() > 0.0f)) {
    return Status::InvalidInput(fmt::format(
        "{}: {} values, expected 256 (codes 0..255) with the last > 0", path, table.size()));
  }
  return table;
}

LinearTable::LinearTable(const ImageResponse& response) {
  BCOT_CHECK(response.IsValid() && response.IsResolved());
  for (int i = 0; i < 256; ++i) {
    const double v = i / 255.0;
    double linear;
    if (response.kind == ImageResponse::Kind::kTable) {
      linear = response.table[i] / static_cast<double>(response.table.back());
    } else if (response.kind == ImageResponse::Kind::kGamma) {
      linear = std::pow(v, response.gamma);
    } else if (response.kind == ImageResponse::Kind::kLog) {
      linear = i == 0 ? 0.0 : std::exp2(response.log_stops * (v - 1.0));
    } else {
      linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    }
    table_[i] = static_cast<float>(linear);
  }
  int code = 0;
  for (int b = 0; b < kBuckets; ++b) {
    const double lower = static_cast<double>(b) / kBuckets;
    while (code < 255 && table_[code + 1] <= lower) ++code;
    bucket_code_[b] = static_cast<unsigned char>(code);
  }
}

Eigen::Vector3d SampleLinearRgb(const cv::Mat3b& image, const LinearTable& lut,
                                const Eigen::Vector2d& p) {
  const int x0 = static_cast<int>(std::floor(p.x()));
  const int y0 = static_cast<int>(std::floor(p.y()));
  const double fx = p.x() - x0, fy = p.y() - y0;
  const double weights[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  const int dx[4] = {0, 1, 0, 1}, dy[4] = {0, 0, 1, 1};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    const cv::Vec3b& px = image(y0 + dy[k], x0 + dx[k]);
    sum += weights[k] * Eigen::Vector3d(lut[px[2]], lut[px[1]], lut[px[0]]);
  }
  return sum;
}

Eigen::Vector3d PeakLinearRgb(const cv::Mat3b& image, const LinearTable& lut,
                              const Eigen::Vector2d& p) {
  const int x0 = static_cast<int>(std::floor(p.x()));
  const int y0 = static_cast<int>(std::floor(p.y()));
  const int x1 = p.x() > x0 ? x0 + 1 : x0;
  const int y1 = p.y() > y0 ? y0 + 1 : y0;
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const cv::Vec3b& px = image(y, x);
      peak = peak.cwiseMax(Eigen::Vector3d(lut[px[2]], lut[px[1]], lut[px[0]]));
    }
  }
  return peak;
}

}  // namespace bcot

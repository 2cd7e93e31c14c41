#include "bcot/core/pose_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "bcot/core/file_util.h"
#include "bcot/core/se3.h"

namespace bcot {
namespace {

// Below this deviation a rotation is orthonormal up to rounding; re-orthonormalising it would
// only flip last bits and break bit-exact write/read round trips.
constexpr double kAlreadyOrthonormal = 1e-12;
constexpr int kPoseNumbers = 12;

bool IsBlank(const std::string& line) { return TrimWhitespace(line).empty(); }

}  // namespace

bool OrthonormalizeReadRotation(Eigen::Matrix3d* rotation, std::string* why) {
  const double deviation =
      (rotation->transpose() * *rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!IsRotationMatrix(*rotation, kRotationReadTolerance, why)) {
    if (why != nullptr && std::isfinite(deviation) && deviation > kRotationReadTolerance) {
      *why += fmt::format(", more than the tolerance {:g}", kRotationReadTolerance);
    }
    return false;
  }
  if (deviation > kAlreadyOrthonormal) *rotation = NearestRotation(*rotation);
  return true;
}

StatusOr<Eigen::Isometry3d> ParsePoseLine(const std::string& line, const std::string& context) {
  const std::vector<std::string> tokens = SplitTokens(line, " \t\r");
  if (tokens.size() != kPoseNumbers) {
    return Status::InvalidInput(fmt::format(
        "{}: expected {} numbers (r11 r12 r13 r21 r22 r23 r31 r32 r33 tx ty tz), got {}", context,
        kPoseNumbers, tokens.size()));
  }
  double values[kPoseNumbers];
  for (int i = 0; i < kPoseNumbers; ++i) {
    if (!ParseDouble(tokens[i], &values[i])) {
      return Status::InvalidInput(fmt::format(
          "{}: number {} of 12 is '{}', expected a decimal number", context, i + 1, tokens[i]));
    }
    if (!std::isfinite(values[i])) {
      return Status::InvalidInput(fmt::format(
          "{}: number {} of 12 is '{}', expected a finite number", context, i + 1, tokens[i]));
    }
  }
  Eigen::Matrix3d rotation;
  rotation << values[0], values[1], values[2], values[3], values[4], values[5], values[6],
      values[7], values[8];
  std::string why;
  if (!OrthonormalizeReadRotation(&rotation, &why)) {
    return Status::InvalidInput(fmt::format("{}: {}", context, why));
  }
  Eigen::Isometry3d target_from_source = Eigen::Isometry3d::Identity();
  target_from_source.linear() = rotation;
  target_from_source.translation() = Eigen::Vector3d(values[9], values[10], values[11]);
  return target_from_source;
}

std::string FormatPoseLine(const Eigen::Isometry3d& target_from_source) {
  const Eigen::Matrix3d& r = target_from_source.linear();
  const Eigen::Vector3d& t = target_from_source.translation();
  // fmt's "{}" prints the shortest representation that parses back to the same double.
  return fmt::format("{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}", r(0, 0), r(0, 1), r(0, 2),
                     r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2), t.x(), t.y(), t.z());
}

StatusOr<std::vector<Eigen::Isometry3d>> ReadPoseFile(const std::string& path) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  return ParsePoseLines(SplitLines(text), 0, path);
}

StatusOr<std::vector<Eigen::Isometry3d>> ParsePoseLines(const std::vector<std::string>& lines,
                                                        size_t first, const std::string& path) {
  size_t num_lines = lines.size();
  while (num_lines > first && IsBlank(lines[num_lines - 1])) --num_lines;

  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(num_lines - std::min(first, num_lines));
  for (size_t i = first; i < num_lines; ++i) {
    const std::string context = fmt::format("{}:{}", path, i + 1);
    if (IsBlank(lines[i])) {
      return Status::InvalidInput(fmt::format(
          "{}: blank line before the last pose; line i must hold pose i (one per frame)", context));
    }
    BCOT_ASSIGN_OR_RETURN(Eigen::Isometry3d pose, ParsePoseLine(lines[i], context));
    poses.push_back(pose);
  }
  return poses;
}

Status WritePoseFile(const std::string& path, const std::vector<Eigen::Isometry3d>& poses) {
  std::string content;
  for (const Eigen::Isometry3d& pose : poses) {
    content += FormatPoseLine(pose);
    content += '\n';
  }
  return WriteFileAtomic(path, content);
}

}  // namespace bcot

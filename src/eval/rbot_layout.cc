#include "bcot/eval/rbot_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

bool StartsWithNumber(const std::string& line) {
  const std::vector<std::string> tokens = SplitTokens(line, " \t\r,");
  double value = 0.0;
  return !tokens.empty() && ParseDouble(tokens[0], &value);
}

// Index of the first data line: 0, or 1 when line 0 is a header (does not start with a
// number). Blank leading lines are not allowed.
size_t FirstDataLine(const std::vector<std::string>& lines) {
  return !lines.empty() && !StartsWithNumber(lines[0]) ? 1 : 0;
}

bool IsBlank(const std::string& line) { return TrimWhitespace(line).empty(); }

}  // namespace

StatusOr<Camera> ReadRbotCalibration(const std::string& path) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  const std::vector<std::string> lines = SplitLines(text);
  const size_t first = FirstDataLine(lines);
  if (first >= lines.size() || IsBlank(lines[first])) {
    return Status::InvalidInput(
        fmt::format("{}:{}: expected a line 'fx fy cx cy ...' of numbers", path, first + 1));
  }
  const std::vector<std::string> tokens = SplitTokens(lines[first], " \t\r,");
  const std::string where = fmt::format("{}:{}", path, first + 1);
  if (tokens.size() < 4) {
    return Status::InvalidInput(
        fmt::format("{}: expected at least 4 numbers (fx fy cx cy), got {}", where, tokens.size()));
  }
  double values[4];
  for (int i = 0; i < 4; ++i) {
    if (!ParseDouble(tokens[i], &values[i]) || !std::isfinite(values[i])) {
      return Status::InvalidInput(
          fmt::format("{}: number {} is '{}', expected a finite number", where, i + 1, tokens[i]));
    }
  }
  if (!(values[0] > 0.0) || !(values[1] > 0.0)) {
    return Status::InvalidInput(
        fmt::format("{}: fx = {}, fy = {}; both must be > 0", where, values[0], values[1]));
  }
  // Further numbers (distortion, RBOT writes zeros) must be zero: RBOT images are undistorted.
  for (size_t i = 4; i < tokens.size(); ++i) {
    double value = 0.0;
    if (!ParseDouble(tokens[i], &value) || value != 0.0) {
      return Status::InvalidInput(fmt::format(
          "{}: number {} is '{}'; only zero distortion is supported", where, i + 1, tokens[i]));
    }
  }
  return Camera(/*name=*/"", /*width=*/0, /*height=*/0, /*fx=*/values[0], /*fy=*/values[1],
                /*cx=*/values[2], /*cy=*/values[3]);
}

StatusOr<std::vector<Eigen::Isometry3d>> ReadRbotPoses(const std::string& path) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  const std::vector<std::string> lines = SplitLines(text);
  BCOT_ASSIGN_OR_RETURN(std::vector<Eigen::Isometry3d> poses,
                        ParsePoseLines(lines, FirstDataLine(lines), path));
  if (poses.empty()) return Status::InvalidInput(fmt::format("{}: no poses", path));
  return poses;
}

StatusOr<std::vector<BenchmarkSequence>> LoadRbotDataset(const std::string& root,
                                                         const std::string& variant,
                                                         const std::string& poses_file) {
  std::error_code error;
  if (!fs::is_directory(root, error)) {
    return Status::NotFound(fmt::format("{}: RBOT dataset folder not found", root));
  }
  const std::string calibration_path = (fs::path(root) / "camera_calibration.txt").string();
  if (!fs::exists(calibration_path, error)) {
    return Status::NotFound(fmt::format("{}: missing (RBOT camera calibration)", calibration_path));
  }
  BCOT_ASSIGN_OR_RETURN(Camera camera, ReadRbotCalibration(calibration_path));
  camera.name = variant;
  const std::string poses_path = (fs::path(root) / poses_file).string();
  if (!fs::exists(poses_path, error)) {
    return Status::NotFound(fmt::format("{}: missing (RBOT ground truth)", poses_path));
  }
  BCOT_ASSIGN_OR_RETURN(const std::vector<Eigen::Isometry3d> poses, ReadRbotPoses(poses_path));

  std::vector<std::string> bodies;
  fs::directory_iterator it(root, error);
  for (; !error && it != fs::directory_iterator(); it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    if (fs::exists(it->path() / "frames" / (variant + "0000.png"))) bodies.push_back(name);
  }
  if (error) {
    return Status::IoError(fmt::format("{}: cannot list folder: {}", root, error.message()));
  }
  std::sort(bodies.begin(), bodies.end());
  if (bodies.empty()) {
    return Status::InvalidInput(
        fmt::format("{}: no body folder with frames/{}0000.png", root, variant));
  }
  std::vector<BenchmarkSequence> sequences;
  for (const std::string& body : bodies) {
    BenchmarkSequence sequence;
    sequence.scene = variant;
    sequence.object = body;
    sequence.camera = camera;
    sequence.mesh_path = (fs::path(root) / body / (body + ".obj")).string();
    if (!fs::exists(sequence.mesh_path, error)) {
      return Status::NotFound(
          fmt::format("{}: model of body '{}' not found", sequence.mesh_path, body));
    }
    sequence.gt_path = poses_path;
    sequence.gt_cam_from_object = poses;
    for (size_t i = 0; i < poses.size(); ++i) {
      const fs::path image =
          fs::path(root) / body / "frames" / fmt::format("{}{:04d}.png", variant, i);
      if (!fs::exists(image, error)) {
        return Status::InvalidInput(
            fmt::format("{}: missing; {} has {} poses", image.string(), poses_path, poses.size()));
      }
      sequence.image_paths.push_back(image.string());
    }
    sequences.push_back(std::move(sequence));
  }
  return sequences;
}

}  // namespace bcot

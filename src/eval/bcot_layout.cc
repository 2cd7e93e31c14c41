#include "bcot/eval/bcot_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "bcot/core/config_file.h"
#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

struct Token {
  std::string text;
  int line = 1;  // 1-based
};

// Splits text[begin, end) at separators, remembering each token's line.
std::vector<Token> Tokenize(const std::string& text, size_t begin, size_t end) {
  std::vector<Token> tokens;
  int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + begin, '\n'));
  std::string current;
  int current_line = line;
  for (size_t i = begin; i < end; ++i) {
    const char c = text[i];
    if (c == ',' || c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ';') {
      if (!current.empty()) tokens.push_back({current, current_line});
      current.clear();
      if (c == '\n') ++line;
      continue;
    }
    if (current.empty()) current_line = line;
    current += c;
  }
  if (!current.empty()) tokens.push_back({current, current_line});
  return tokens;
}

int LineOf(const std::string& text, size_t offset) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + offset, '\n'));
}

bool IsDirectory(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error);
}

// Sorted names of the sub-folders of `dir` (hidden ones skipped).
StatusOr<std::vector<std::string>> SubFolders(const fs::path& dir) {
  std::error_code error;
  std::vector<std::string> names;
  fs::directory_iterator it(dir, error);
  for (; !error && it != fs::directory_iterator(); it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    if (IsDirectory(it->path())) names.push_back(name);
  }
  if (error) {
    return Status::IoError(
        fmt::format("{}: cannot list folder: {}", dir.string(), error.message()));
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

StatusOr<Camera> ParseBcotIntrinsics(const std::string& text, const std::string& source) {
  size_t begin = 0;
  size_t end = text.size();
  const size_t open = text.rfind('(');
  if (open != std::string::npos) {
    const size_t close = text.find(')', open);
    if (close == std::string::npos) {
      return Status::InvalidInput(fmt::format("{}:{}: '(' of the Matx33f literal is never closed",
                                              source, LineOf(text, open)));
    }
    begin = open + 1;
    end = close;
  }
  const std::vector<Token> tokens = Tokenize(text, begin, end);
  if (tokens.size() != 9) {
    return Status::InvalidInput(fmt::format(
        "{}:{}: expected 9 numbers (fx 0 cx 0 fy cy 0 0 1, as Matx33f(...) or plain), got {}",
        source, tokens.empty() ? LineOf(text, begin) : tokens.back().line, tokens.size()));
  }
  double k[9];
  for (int i = 0; i < 9; ++i) {
    std::string_view number = tokens[i].text;
    if (!number.empty() && (number.back() == 'f' || number.back() == 'F') &&
        number.find_first_of("0123456789") != std::string_view::npos) {
      number.remove_suffix(1);  // C++ float literal "481.3f"
    }
    if (!ParseDouble(number, &k[i]) || !std::isfinite(k[i])) {
      return Status::InvalidInput(
          fmt::format("{}:{}: number {} of 9 is '{}', expected a finite number", source,
                      tokens[i].line, i + 1, tokens[i].text));
    }
  }
  const int line = tokens[0].line;
  std::vector<std::string> problems;
  if (!(k[0] > 0.0)) problems.push_back(fmt::format("fx = {} must be > 0", k[0]));
  if (!(k[4] > 0.0)) problems.push_back(fmt::format("fy = {} must be > 0", k[4]));
  for (int i : {1, 3, 6, 7}) {
    if (k[i] != 0.0) problems.push_back(fmt::format("entry {} = {} must be 0", i + 1, k[i]));
  }
  if (k[8] != 1.0) problems.push_back(fmt::format("entry 9 = {} must be 1", k[8]));
  if (!problems.empty()) {
    return Status::InvalidInput(
        fmt::format("{}:{}: not a pinhole matrix [[fx,0,cx],[0,fy,cy],[0,0,1]]: {}", source, line,
                    JoinMessages(problems)));
  }
  return Camera(/*name=*/"", /*width=*/0, /*height=*/0, /*fx=*/k[0], /*fy=*/k[4], /*cx=*/k[2],
                /*cy=*/k[5]);
}

StatusOr<Camera> ReadBcotIntrinsics(const std::string& path) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  return ParseBcotIntrinsics(text, path);
}

std::string FormatBcotIntrinsics(const Camera& camera) {
  return fmt::format("Matx33f K = Matx33f({}, 0.0, {}, 0.0, {}, {}, 0.0, 0.0, 1.0);\n", camera.fx,
                     camera.cx, camera.fy, camera.cy);
}

std::string BcotModelPath(const std::string& root, const std::string& object) {
  return (fs::path(root) / "models" / (object + ".obj")).string();
}

StatusOr<std::vector<BenchmarkSequence>> LoadBcotDataset(const std::string& root) {
  if (!IsDirectory(root)) {
    return Status::NotFound(fmt::format("{}: BCOT dataset folder not found", root));
  }
  BCOT_ASSIGN_OR_RETURN(const std::vector<std::string> scenes, SubFolders(root));
  std::vector<BenchmarkSequence> sequences;
  for (const std::string& scene : scenes) {
    if (scene == "models") continue;
    const fs::path scene_dir = fs::path(root) / scene;
    BCOT_ASSIGN_OR_RETURN(const std::vector<std::string> objects, SubFolders(scene_dir));
    std::optional<Camera> camera;
    for (const std::string& object : objects) {
      const fs::path object_dir = scene_dir / object;
      const std::string pose_path = (object_dir / "pose.txt").string();
      std::error_code error;
      if (!fs::exists(pose_path, error)) continue;
      if (!camera.has_value()) {
        const std::string k_path = (scene_dir / "K.txt").string();
        if (!fs::exists(k_path, error)) {
          return Status::NotFound(
              fmt::format("{}: missing (scene '{}' holds {})", k_path, scene, pose_path));
        }
        BCOT_ASSIGN_OR_RETURN(camera, ReadBcotIntrinsics(k_path));
        camera->name = scene;
      }
      BenchmarkSequence sequence;
      sequence.scene = scene;
      sequence.object = object;
      sequence.camera = *camera;
      sequence.mesh_path = BcotModelPath(root, object);
      if (!fs::exists(sequence.mesh_path, error)) {
        return Status::NotFound(fmt::format("{}: model of object '{}' ({}) not found",
                                            sequence.mesh_path, object, pose_path));
      }
      sequence.gt_path = pose_path;
      BCOT_ASSIGN_OR_RETURN(sequence.gt_cam_from_object, ReadPoseFile(pose_path));
      BCOT_ASSIGN_OR_RETURN(sequence.image_paths, ListFrameImages(object_dir.string()));
      if (sequence.gt_cam_from_object.size() != sequence.image_paths.size()) {
        return Status::InvalidInput(fmt::format("{}: {} poses for {} frames in {}", pose_path,
                                                sequence.gt_cam_from_object.size(),
                                                sequence.image_paths.size(), object_dir.string()));
      }
      sequences.push_back(std::move(sequence));
    }
  }
  if (sequences.empty()) {
    return Status::InvalidInput(
        fmt::format("{}: no BCOT sequence (<scene>/<Object>/pose.txt) found", root));
  }
  return sequences;
}

}  // namespace bcot

#include "bcot/core/sequence.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/rig_io.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

// Longest frame index we accept (10⁹ frames is far beyond any capture).
constexpr size_t kMaxIndexDigits = 9;

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return text;
}

bool IsImageExtension(const std::string& extension) {
  const std::string lower = Lower(extension);
  return lower == ".png" || lower == ".jpg" || lower == ".jpeg";
}

bool AllDigits(const std::string& text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); });
}

struct FrameFile {
  int64_t index;
  std::string name;
};

// Reads timestamps.csv: optional header row, then rows `frame, stamp_cam0, stamp_cam1, ...`
// for frames 0..num_frames-1 in order.
StatusOr<std::vector<std::vector<int64_t>>> ReadTimestamps(const std::string& path, const Rig& rig,
                                                           int num_frames) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  std::vector<std::string> lines = SplitLines(text);
  while (!lines.empty() && TrimWhitespace(lines.back()).empty()) lines.pop_back();

  const size_t num_fields = static_cast<size_t>(rig.size()) + 1;
  std::vector<std::string> camera_names;
  for (const RigCamera& camera : rig.cameras()) camera_names.push_back(camera.camera.name);
  const std::string layout =
      fmt::format("frame, then one nanosecond stamp per camera: {}", fmt::join(camera_names, ", "));

  const auto split = [](const std::string& line) {
    std::vector<std::string> fields;
    size_t start = 0;
    while (true) {
      const size_t comma = line.find(',', start);
      fields.emplace_back(TrimWhitespace(std::string_view(line).substr(
          start, comma == std::string::npos ? comma : comma - start)));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    return fields;
  };

  std::vector<std::vector<int64_t>> timestamps;
  size_t first_row = 0;
  if (!lines.empty()) {
    const std::vector<std::string> header = split(lines[0]);
    int64_t ignored = 0;
    if (!ParseInt64(header[0], &ignored)) {
      // A header row. When it names the rig's cameras, they must be in rig order, else the
      // stamps would be silently assigned to the wrong cameras.
      if (header.size() != num_fields) {
        return Status::InvalidInput(fmt::format("{}:1: header has {} columns, expected {} ({})",
                                                path, header.size(), num_fields, layout));
      }
      for (size_t i = 1; i < header.size(); ++i) {
        if (rig.Find(header[i]) >= 0 && header[i] != camera_names[i - 1]) {
          return Status::InvalidInput(
              fmt::format("{}:1: column {} is camera '{}', but rig.yaml lists '{}' there ({})",
                          path, i + 1, header[i], camera_names[i - 1], layout));
        }
      }
      first_row = 1;
    }
  }

  for (size_t line_index = first_row; line_index < lines.size(); ++line_index) {
    const std::string where = fmt::format("{}:{}", path, line_index + 1);
    const int64_t expected_frame = static_cast<int64_t>(timestamps.size());
    if (TrimWhitespace(lines[line_index]).empty()) {
      return Status::InvalidInput(
          fmt::format("{}: blank line; expected the row of frame {}", where, expected_frame));
    }
    const std::vector<std::string> fields = split(lines[line_index]);
    if (fields.size() != num_fields) {
      return Status::InvalidInput(fmt::format("{}: expected {} comma-separated fields ({}), got {}",
                                              where, num_fields, layout, fields.size()));
    }
    int64_t frame = 0;
    if (!ParseInt64(fields[0], &frame)) {
      return Status::InvalidInput(
          fmt::format("{}: frame index '{}' is not an integer", where, fields[0]));
    }
    if (frame != expected_frame) {
      return Status::InvalidInput(
          fmt::format("{}: frame index {}, expected {} (rows list frames 0, 1, 2, ... in order)",
                      where, frame, expected_frame));
    }
    if (frame >= num_frames) {
      return Status::InvalidInput(
          fmt::format("{}: row for frame {}, but the camera folders hold only {} frames", where,
                      frame, num_frames));
    }
    std::vector<int64_t> row(rig.size());
    for (int camera = 0; camera < rig.size(); ++camera) {
      const std::string& field = fields[camera + 1];
      if (!ParseInt64(field, &row[camera])) {
        return Status::InvalidInput(
            fmt::format("{}: stamp of camera '{}' is '{}', expected an integer (nanoseconds)",
                        where, camera_names[camera], field));
      }
    }
    timestamps.push_back(std::move(row));
  }
  if (static_cast<int>(timestamps.size()) != num_frames) {
    const std::string where =
        lines.empty() ? path : fmt::format("{}:{}", path, lines.size());  // the last row
    return Status::InvalidInput(
        fmt::format("{}: {} timestamp rows, expected {} (one per frame in the camera folders)",
                    where, timestamps.size(), num_frames));
  }
  return timestamps;
}

}  // namespace

StatusOr<std::vector<std::string>> ListFrameImages(const std::string& folder,
                                                   int64_t* first_index) {
  std::error_code error;
  if (!fs::exists(folder, error)) {
    return Status::NotFound(fmt::format("{}: frame folder not found", folder));
  }
  if (!fs::is_directory(folder, error)) {
    return Status::InvalidInput(fmt::format("{}: expected a folder of frame images", folder));
  }

  std::vector<FrameFile> frames;
  std::string extension;  // of the first image, as written
  std::string extension_example;
  fs::directory_iterator it(folder, error);
  if (error) {
    return Status::IoError(fmt::format("{}: cannot list folder: {}", folder, error.message()));
  }
  for (; it != fs::directory_iterator(); it.increment(error)) {
    if (error) break;
    const fs::path& path = it->path();
    const std::string name = path.filename().string();
    // Other files (pose.txt, .DS_Store, thumbnails) may live beside the frames.
    if (name.empty() || name[0] == '.' || !IsImageExtension(path.extension().string())) continue;
    if (!it->is_regular_file(error)) continue;
    const std::string stem = path.stem().string();
    if (!AllDigits(stem)) {
      return Status::InvalidInput(fmt::format(
          "{}: image '{}' is not named by its frame index (expected 000000{}, 000001{}, ...)",
          folder, name, path.extension().string(), path.extension().string()));
    }
    if (stem.size() > kMaxIndexDigits) {
      return Status::InvalidInput(
          fmt::format("{}: image '{}' has a frame index of more than {} "
                      "digits",
                      folder, name, kMaxIndexDigits));
    }
    if (extension.empty()) {
      extension = path.extension().string();
      extension_example = name;
    } else if (path.extension().string() != extension) {
      return Status::InvalidInput(fmt::format(
          "{}: images with different extensions ('{}' and '{}'); use one extension per camera",
          folder, extension_example, name));
    }
    frames.push_back({std::stoll(stem), name});
  }
  if (error) {
    return Status::IoError(fmt::format("{}: cannot list folder: {}", folder, error.message()));
  }
  if (frames.empty()) {
    return Status::InvalidInput(
        fmt::format("{}: no frame images (000000.png or .jpg/.jpeg, numbered from 0)", folder));
  }

  std::sort(frames.begin(), frames.end(), [](const FrameFile& a, const FrameFile& b) {
    return a.index != b.index ? a.index < b.index : a.name < b.name;
  });
  for (size_t i = 1; i < frames.size(); ++i) {
    if (frames[i - 1].index == frames[i].index) {
      return Status::InvalidInput(fmt::format("{}: '{}' and '{}' are both frame {}", folder,
                                              frames[i - 1].name, frames[i].name, frames[i].index));
    }
  }
  if (first_index != nullptr) {
    *first_index = frames.front().index;
  } else if (frames.front().index != 0) {
    return Status::InvalidInput(
        fmt::format("{}: frame 0 is missing (numbering starts at 0; the first image is '{}')",
                    folder, frames.front().name));
  }
  // The first frame sets the zero padding; a wider name is fine only once the index needs the
  // digits.
  const size_t width = frames.front().name.size() - extension.size();
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameFile& frame = frames[i];
    const std::string expected_name = fmt::format("{:0{}}{}", frame.index, width, extension);
    if (frame.name != expected_name) {
      return Status::InvalidInput(
          fmt::format("{}: '{}' is not padded like frame {} '{}' (expected '{}')", folder,
                      frame.name, frames.front().index, frames.front().name, expected_name));
    }
    const int64_t expected_index = frames.front().index + static_cast<int64_t>(i);
    if (frame.index != expected_index) {
      return Status::InvalidInput(fmt::format("{}: frame {} is missing ('{}' is followed by '{}')",
                                              folder, expected_index, frames[i - 1].name,
                                              frame.name));
    }
  }

  std::vector<std::string> paths;
  paths.reserve(frames.size());
  for (const FrameFile& frame : frames) paths.push_back((fs::path(folder) / frame.name).string());
  return paths;
}

StatusOr<Sequence> LoadSequence(const std::string& dir, bool require_init_pose) {
  std::error_code error;
  if (!fs::is_directory(dir, error)) {
    return fs::exists(dir, error)
               ? Status::InvalidInput(fmt::format("{}: not a sequence directory", dir))
               : Status::NotFound(fmt::format("{}: sequence directory not found", dir));
  }
  const fs::path root(dir);
  Sequence sequence;
  sequence.dir = dir;

  BCOT_ASSIGN_OR_RETURN(sequence.rig, ReadRigYaml((root / "rig.yaml").string()));
  BCOT_ASSIGN_OR_RETURN(sequence.object,
                        ReadObjectYamlAndCheckMesh((root / "object.yaml").string()));

  for (int camera = 0; camera < sequence.rig.size(); ++camera) {
    const std::string& name = sequence.rig[camera].camera.name;
    const std::string folder = (root / name).string();
    if (!fs::exists(folder, error)) {
      return Status::NotFound(fmt::format(
          "{}: folder of camera '{}' (cameras[{}] in rig.yaml) not found", folder, name, camera));
    }
    int64_t first_index = 0;
    BCOT_ASSIGN_OR_RETURN(std::vector<std::string> images, ListFrameImages(folder, &first_index));
    if (camera > 0 && first_index != sequence.first_image_index) {
      return Status::InvalidInput(fmt::format(
          "{}: camera '{}' starts at image {} but camera '{}' at image {}; every camera's "
          "numbering must start at the same index",
          dir, name, first_index, sequence.rig[0].camera.name, sequence.first_image_index));
    }
    sequence.first_image_index = first_index;
    if (camera > 0 && static_cast<int>(images.size()) != sequence.num_frames) {
      return Status::InvalidInput(fmt::format(
          "{}: camera '{}' has {} frames but camera '{}' has {}; every camera needs the same "
          "frame count",
          dir, name, images.size(), sequence.rig[0].camera.name, sequence.num_frames));
    }
    sequence.num_frames = static_cast<int>(images.size());
    sequence.image_paths.push_back(std::move(images));
  }

  const std::string init_path = (root / "init_pose.txt").string();
  if (fs::exists(init_path, error)) {
    BCOT_ASSIGN_OR_RETURN(const std::vector<Eigen::Isometry3d> poses, ReadPoseFile(init_path));
    if (poses.size() != 1) {
      return Status::InvalidInput(
          fmt::format("{}{}: expected exactly one pose line (rig_from_object of frame 0), got {}",
                      init_path, poses.empty() ? "" : ":2", poses.size()));
    }
    sequence.init_rig_from_object = poses[0];
  } else if (require_init_pose) {
    return Status::NotFound(fmt::format(
        "{}: not found; it holds one pose line, the rough rig_from_object of frame 0", init_path));
  }

  const std::string keyframes_path = (root / "keyframes.txt").string();
  if (fs::exists(keyframes_path, error)) {
    BCOT_RETURN_IF_ERROR(LoadKeyframes(keyframes_path, &sequence));
  }

  const std::string timestamps_path = (root / "timestamps.csv").string();
  if (fs::exists(timestamps_path, error)) {
    BCOT_ASSIGN_OR_RETURN(sequence.timestamps_ns,
                          ReadTimestamps(timestamps_path, sequence.rig, sequence.num_frames));
  }
  return sequence;
}

Status LoadKeyframes(const std::string& path, Sequence* sequence) {
  BCOT_ASSIGN_OR_RETURN(sequence->keyframes, ReadKeyframeFile(path, sequence->num_frames));
  sequence->keyframes_path = path;
  return Status::Ok();
}

}  // namespace bcot

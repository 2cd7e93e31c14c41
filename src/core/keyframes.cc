#include "bcot/core/keyframes.h"

#include <fmt/format.h>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"

namespace bcot {

StatusOr<KeyframePoses> ParseKeyframeLines(const std::vector<std::string>& lines,
                                           const std::string& path, int num_frames) {
  KeyframePoses keyframes;
  std::map<int, size_t> line_of_frame;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string_view line = TrimWhitespace(lines[i]);
    if (line.empty()) continue;
    const std::string context = fmt::format("{}:{}", path, i + 1);
    const size_t split = line.find_first_of(" \t");
    const std::string index_text(line.substr(0, split));
    int64_t frame = 0;
    if (!ParseInt64(index_text, &frame)) {
      return Status::InvalidInput(fmt::format(
          "{}: frame index '{}' is not an integer (expected: frame r11 r12 r13 r21 r22 r23 r31 "
          "r32 r33 tx ty tz)",
          context, index_text));
    }
    if (frame < 0 || frame >= num_frames) {
      return Status::InvalidInput(fmt::format("{}: frame {} is outside the sequence's frames 0..{}",
                                              context, frame, num_frames - 1));
    }
    const int index = static_cast<int>(frame);
    if (line_of_frame.count(index) > 0) {
      return Status::InvalidInput(fmt::format("{}: frame {} already has a keyframe on line {}",
                                              context, index, line_of_frame[index]));
    }
    const std::string pose_text =
        split == std::string_view::npos ? std::string() : std::string(line.substr(split));
    BCOT_ASSIGN_OR_RETURN(const Eigen::Isometry3d rig_from_object,
                          ParsePoseLine(pose_text, context));
    keyframes[index] = rig_from_object;
    line_of_frame[index] = i + 1;
  }
  return keyframes;
}

StatusOr<KeyframePoses> ReadKeyframeFile(const std::string& path, int num_frames) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  return ParseKeyframeLines(SplitLines(text), path, num_frames);
}

}  // namespace bcot

// Keyframes: hand-set poses at chosen frames (`<seq>/keyframes.txt` or
// `bcot annotate --keyframes FILE`). One keyframe per line:
//   frame r11 r12 r13 r21 r22 r23 r31 r32 r33 tx ty tz
// the frame index (0-based, counted from the sequence's first image) followed by a pose line of
// pose_io.h (rig_from_object, R row-major, t in mm), parsed by the same ParsePoseLine. Lines may
// come in any order; blank lines are skipped (the frame index is explicit, so a blank line
// cannot shift a pose). Errors name the file and the 1-based line: a malformed pose, a frame
// index that is not an integer, outside [0, num_frames) or given twice.
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

#include "bcot/core/status.h"

namespace bcot {

// rig_from_object (mm) by frame index.
using KeyframePoses = std::map<int, Eigen::Isometry3d>;

// Parses the lines of a keyframes file; `path` names it in error messages.
StatusOr<KeyframePoses> ParseKeyframeLines(const std::vector<std::string>& lines,
                                           const std::string& path, int num_frames);

// Reads and parses `path` (see the header comment).
StatusOr<KeyframePoses> ReadKeyframeFile(const std::string& path, int num_frames);

}  // namespace bcot

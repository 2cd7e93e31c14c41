// A sequence directory (DESIGN.md, input contract):
//   <seq>/rig.yaml, <seq>/object.yaml, <seq>/<camera name>/000000.png|jpg ...,
//   <seq>/init_pose.txt (one pose line: rig_from_object of frame 0),
//   <seq>/timestamps.csv (optional: frame, then one nanosecond stamp per camera).
// LoadSequence validates all of it up front, so a job fails before any work is done.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bcot/core/object_io.h"
#include "bcot/core/rig.h"
#include "bcot/core/status.h"

namespace bcot {

struct Sequence {
  std::string dir;
  Rig rig;
  ObjectSpec object;
  // image_paths[camera][frame], cameras in rig order; every camera has num_frames images.
  std::vector<std::vector<std::string>> image_paths;
  int num_frames = 0;
  std::optional<Eigen::Isometry3d> init_rig_from_object;   // from init_pose.txt
  std::vector<std::vector<int64_t>> timestamps_ns;          // [frame][camera]; may be empty
};

// Frame images in `folder`: files named by a zero-padded index starting at 0 with one
// extension (.png or .jpg/.jpeg), contiguous. Errors name the folder and the first gap.
StatusOr<std::vector<std::string>> ListFrameImages(const std::string& folder);

// Loads and validates a sequence. `require_init_pose`: init_pose.txt must exist.
StatusOr<Sequence> LoadSequence(const std::string& dir, bool require_init_pose = true);

}  // namespace bcot

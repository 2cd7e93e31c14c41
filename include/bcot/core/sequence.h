// A sequence directory (DESIGN.md, input contract):
//   <seq>/rig.yaml, <seq>/object.yaml, <seq>/<camera name>/000000.png|jpg ...,
//   <seq>/init_pose.txt (one pose line: rig_from_object of frame 0),
//   <seq>/timestamps.csv (optional: frame, then one nanosecond stamp per camera),
//   <seq>/keyframes.txt (optional: hand-set poses at chosen frames, keyframes.h).
// LoadSequence validates all of it up front, so a job fails before any work is done.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bcot/core/keyframes.h"
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
  // The number in the name of every camera's first image (e.g. 000120.png → 120). Frame
  // indices everywhere else (pose files, keyframes, frames.csv, --frames, timestamps.csv) count
  // from that image: frame f is image first_image_index + f.
  int64_t first_image_index = 0;
  std::optional<Eigen::Isometry3d> init_rig_from_object;  // from init_pose.txt
  std::vector<std::vector<int64_t>> timestamps_ns;        // [frame][camera]; may be empty
  // Hand-set rig_from_object by frame (keyframes.h); empty without a keyframes file.
  KeyframePoses keyframes;
  std::string keyframes_path;  // the file they came from; empty when none
};

// Frame images in `folder`: files named by a zero-padded index with one extension (.png or
// .jpg/.jpeg), contiguous. `first_index` null: numbering must start at 0; otherwise it may
// start anywhere and receives the first image's index (a sequence cut from a longer capture).
// Errors name the folder and the first gap.
StatusOr<std::vector<std::string>> ListFrameImages(const std::string& folder,
                                                   int64_t* first_index = nullptr);

// Loads and validates a sequence, with <dir>/keyframes.txt when it exists.
// `require_init_pose`: init_pose.txt must exist.
StatusOr<Sequence> LoadSequence(const std::string& dir, bool require_init_pose = true);

// Replaces the sequence's keyframes by those of `path` (bcot annotate --keyframes FILE).
Status LoadKeyframes(const std::string& path, Sequence* sequence);

}  // namespace bcot

// Hand edits of an annotation's poses in `bcot review`: nudges in one view's image, an undo
// stack per frame, and setting a keyframe from the edited pose (written to the sequence's
// keyframes.txt, which `bcot annotate` then tracks from; docs/keyframes.md).
//
// A nudge moves the object in the frame of one camera, about the object's bounding-box centre
// c (its position c_cam = cam_from_rig · rig_from_object · c, depth z = c_cam.z > 0):
//   translation  Δ = (dx_px · z / fx, dy_px · z / fy, dz_mm): the centre's projection moves by
//                (dx_px, dy_px) pixels (exactly without lens distortion) and its depth by dz_mm;
//   rotation     R_Δ = Exp((rx, ry, rz) in rad) about the camera's axes through c
// so cam_from_object' = T(c_cam + Δ) · R_Δ · T(−c_cam) · cam_from_object.
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "bcot/core/keyframes.h"
#include "bcot/core/rig.h"
#include "bcot/core/status.h"

namespace bcot {

struct PoseNudge {
  double dx_px = 0.0;  // image column
  double dy_px = 0.0;  // image row
  double dz_mm = 0.0;  // along the camera's viewing axis (away from the camera > 0)
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();  // about the camera's x, y, z axes
};

// The nudged rig_from_object (see the header comment). kInvalidInput when the centre is not in
// front of the camera or a value is not finite.
StatusOr<Eigen::Isometry3d> NudgePose(const Eigen::Isometry3d& rig_from_object,
                                      const Eigen::Vector3d& centre_in_object,
                                      const RigCamera& camera, const PoseNudge& nudge);

// Per-frame edit stacks over a fixed list of poses. Thread-safe.
class PoseEdits {
 public:
  explicit PoseEdits(std::vector<Eigen::Isometry3d> rig_from_object);

  int num_frames() const { return static_cast<int>(original_.size()); }
  // The frame's pose: its last edit, else the original. `frame` in range (CHECKed).
  Eigen::Isometry3d Pose(int frame) const;
  // Edits of the frame on its stack (0 = the original pose).
  int Depth(int frame) const;
  void Push(int frame, const Eigen::Isometry3d& rig_from_object);
  // Drops the frame's last edit; false when it has none.
  bool Undo(int frame);
  // New original poses (a re-annotation; same frame count, CHECKed); the edits of frames
  // first..last are dropped, the others stay on top of their new originals.
  void Rebase(std::vector<Eigen::Isometry3d> rig_from_object, int first, int last);

 private:
  mutable std::mutex mutex_;
  std::vector<Eigen::Isometry3d> original_;
  std::map<int, std::vector<Eigen::Isometry3d>> edits_;
};

// Sets `frame`'s keyframe in the keyframes file at `path` to `rig_from_object` (replacing a line
// of that frame, keeping the others), written atomically in frame order. The existing file must
// parse (its errors name it and the line); the new file is written whole, so two writers never
// interleave lines (the last one wins).
Status SetKeyframe(const std::string& path, int frame, const Eigen::Isometry3d& rig_from_object,
                   int num_frames);

}  // namespace bcot

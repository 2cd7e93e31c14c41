#include "bcot/review/review_edits.h"

#include <fmt/format.h>

#include <filesystem>
#include <utility>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"

namespace bcot {

StatusOr<Eigen::Isometry3d> NudgePose(const Eigen::Isometry3d& rig_from_object,
                                      const Eigen::Vector3d& centre_in_object,
                                      const RigCamera& camera, const PoseNudge& nudge) {
  if (!std::isfinite(nudge.dx_px) || !std::isfinite(nudge.dy_px) || !std::isfinite(nudge.dz_mm) ||
      !nudge.rotation_deg.allFinite()) {
    return Status::InvalidInput("a nudge must be finite");
  }
  const Eigen::Isometry3d cam_from_object = camera.cam_from_rig * rig_from_object;
  const Eigen::Vector3d centre = cam_from_object * centre_in_object;
  if (!(centre.z() > 0.0)) {
    return Status::InvalidInput(fmt::format(
        "the object's centre is not in front of {} (depth {} mm)", camera.camera.name, centre.z()));
  }
  const Eigen::Vector3d shift(nudge.dx_px * centre.z() / camera.camera.fx,
                              nudge.dy_px * centre.z() / camera.camera.fy, nudge.dz_mm);
  Eigen::Isometry3d move = Eigen::Isometry3d::Identity();
  move.linear() = ExpSO3(nudge.rotation_deg * kPi / 180.0);
  move.translation() = centre + shift - move.linear() * centre;
  return Eigen::Isometry3d(camera.cam_from_rig.inverse() * move * cam_from_object);
}

PoseEdits::PoseEdits(std::vector<Eigen::Isometry3d> rig_from_object)
    : original_(std::move(rig_from_object)) {}

Eigen::Isometry3d PoseEdits::Pose(int frame) const {
  BCOT_CHECK(frame >= 0 && frame < num_frames());
  std::lock_guard<std::mutex> lock(mutex_);
  const auto stack = edits_.find(frame);
  return stack == edits_.end() || stack->second.empty() ? original_[frame] : stack->second.back();
}

int PoseEdits::Depth(int frame) const {
  BCOT_CHECK(frame >= 0 && frame < num_frames());
  std::lock_guard<std::mutex> lock(mutex_);
  const auto stack = edits_.find(frame);
  return stack == edits_.end() ? 0 : static_cast<int>(stack->second.size());
}

void PoseEdits::Push(int frame, const Eigen::Isometry3d& rig_from_object) {
  BCOT_CHECK(frame >= 0 && frame < num_frames());
  std::lock_guard<std::mutex> lock(mutex_);
  edits_[frame].push_back(rig_from_object);
}

bool PoseEdits::Undo(int frame) {
  BCOT_CHECK(frame >= 0 && frame < num_frames());
  std::lock_guard<std::mutex> lock(mutex_);
  const auto stack = edits_.find(frame);
  if (stack == edits_.end() || stack->second.empty()) return false;
  stack->second.pop_back();
  return true;
}

void PoseEdits::Rebase(std::vector<Eigen::Isometry3d> rig_from_object, int first, int last) {
  std::lock_guard<std::mutex> lock(mutex_);
  BCOT_CHECK(rig_from_object.size() == original_.size());
  original_ = std::move(rig_from_object);
  edits_.erase(edits_.lower_bound(first), edits_.upper_bound(last));
}

Status SetKeyframe(const std::string& path, int frame, const Eigen::Isometry3d& rig_from_object,
                   int num_frames) {
  if (frame < 0 || frame >= num_frames) {
    return Status::InvalidInput(
        fmt::format("keyframe {}: the sequence has frames 0..{}", frame, num_frames - 1));
  }
  KeyframePoses keyframes;
  std::error_code error;
  if (std::filesystem::exists(path, error)) {
    BCOT_ASSIGN_OR_RETURN(keyframes, ReadKeyframeFile(path, num_frames));
  }
  keyframes[frame] = rig_from_object;
  std::string text;
  for (const auto& [index, pose] : keyframes) {
    text += std::to_string(index) + " " + FormatPoseLine(pose) + "\n";
  }
  return WriteFileAtomic(path, text);
}

}  // namespace bcot

// A rig: named, synchronized cameras with their extrinsics `cam_from_rig` (mm).
// The rig frame is arbitrary (usually the first camera's frame). The annotation is
// `rig_from_object`; a view's pose is cam_from_object = cam_from_rig · rig_from_object.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"

namespace bcot {

struct RigCamera {
  Camera camera;
  Eigen::Isometry3d cam_from_rig = Eigen::Isometry3d::Identity();
};

class Rig {
 public:
  Rig() = default;
  explicit Rig(std::vector<RigCamera> cameras) : cameras_(std::move(cameras)) {}

  void Add(RigCamera camera) { cameras_.push_back(std::move(camera)); }
  int size() const { return static_cast<int>(cameras_.size()); }
  bool empty() const { return cameras_.empty(); }
  const RigCamera& operator[](int index) const { return cameras_.at(index); }
  const std::vector<RigCamera>& cameras() const { return cameras_; }

  // Index of the camera called `name`, or −1.
  int Find(const std::string& name) const;

  // Non-empty, unique non-empty names, valid intrinsics, rotations orthonormal.
  Status Validate() const;

 private:
  std::vector<RigCamera> cameras_;
};

}  // namespace bcot

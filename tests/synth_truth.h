// The truth of a `bcot synth` sequence (its gt/ folder) as tests use it. Header-only: the layer
// test binaries that include it link render.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/render/mesh.h"

namespace bcot::test {

// gt/rig_from_object.txt of the sequence in `sequence_dir`, at `frame`.
inline Eigen::Isometry3d TruePose(const std::string& sequence_dir, int frame) {
  StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(sequence_dir + "/gt/rig_from_object.txt");
  BCOT_CHECK(truth.ok() && frame < static_cast<int>(truth->size()));
  return (*truth)[frame];
}

// Where the object's centre (its mesh's bounding-box centre) truly projects in camera
// `camera_index` at `frame`: a perfect click on it.
inline Eigen::Vector2d TrueCentrePixel(const std::string& sequence_dir, int camera_index,
                                       int frame) {
  StatusOr<Sequence> sequence = LoadSequence(sequence_dir, /*require_init_pose=*/false);
  BCOT_CHECK(sequence.ok());
  StatusOr<Mesh> mesh = Mesh::Load(sequence->object.mesh_path, sequence->object.unit_to_mm);
  BCOT_CHECK(mesh.ok());
  const RigCamera& camera = sequence->rig[camera_index];
  return camera.camera.Project(camera.cam_from_rig * TruePose(sequence_dir, frame) *
                               mesh->bbox_center());
}

}  // namespace bcot::test

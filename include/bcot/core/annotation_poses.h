// The poses of an annotation directory (output contract). `rig_from_object.txt` is the
// annotation, the one source of truth: one pose line per frame (pose_io.h). The per-camera
// files `<camera>/pose.txt` (cam_from_object = cam_from_rig · rig_from_object) are derived from
// it and rig.yaml for convenience and are never read back by bcot. Every reader of an
// annotation (bcot report, bcot export, tests) calls ReadAnnotationPoses, so a hand edit of
// rig_from_object.txt is what the next `bcot report` or `bcot export` sees.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/rig.h"
#include "bcot/core/status.h"

namespace bcot {

inline constexpr char kRigFromObjectFileName[] = "rig_from_object.txt";

// <annotation_dir>/rig_from_object.txt: rig_from_object per frame (mm).
StatusOr<std::vector<Eigen::Isometry3d>> ReadAnnotationPoses(const std::string& annotation_dir);

// cam_from_object per frame for one camera: cam_from_rig · rig_from_object[t].
std::vector<Eigen::Isometry3d> CamFromObjectPoses(
    const Eigen::Isometry3d& cam_from_rig, const std::vector<Eigen::Isometry3d>& rig_from_object);

// Writes, for every camera of `rig`, <camera>/pose.txt derived from `rig_from_object`,
// atomically. `bcot report` calls it, so per-camera files follow a hand edit.
Status WriteDerivedCameraPoses(const std::string& annotation_dir, const Rig& rig,
                               const std::vector<Eigen::Isometry3d>& rig_from_object);

// Writes rig_from_object.txt and, for every camera of `rig`, the derived <camera>/pose.txt,
// each atomically (temp + rename).
Status WriteAnnotationPoses(const std::string& annotation_dir, const Rig& rig,
                            const std::vector<Eigen::Isometry3d>& rig_from_object);

}  // namespace bcot

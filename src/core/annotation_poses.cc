#include "bcot/core/annotation_poses.h"

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"

namespace bcot {

StatusOr<std::vector<Eigen::Isometry3d>> ReadAnnotationPoses(const std::string& annotation_dir) {
  return ReadPoseFile(annotation_dir + "/" + kRigFromObjectFileName);
}

std::vector<Eigen::Isometry3d> CamFromObjectPoses(
    const Eigen::Isometry3d& cam_from_rig, const std::vector<Eigen::Isometry3d>& rig_from_object) {
  std::vector<Eigen::Isometry3d> cam_from_object;
  cam_from_object.reserve(rig_from_object.size());
  for (const Eigen::Isometry3d& pose : rig_from_object)
    cam_from_object.push_back(cam_from_rig * pose);
  return cam_from_object;
}

Status WriteAnnotationPoses(const std::string& annotation_dir, const Rig& rig,
                            const std::vector<Eigen::Isometry3d>& rig_from_object) {
  BCOT_RETURN_IF_ERROR(CreateDirectories(annotation_dir));
  BCOT_RETURN_IF_ERROR(
      WritePoseFile(annotation_dir + "/" + kRigFromObjectFileName, rig_from_object));
  return WriteDerivedCameraPoses(annotation_dir, rig, rig_from_object);
}

Status WriteDerivedCameraPoses(const std::string& annotation_dir, const Rig& rig,
                               const std::vector<Eigen::Isometry3d>& rig_from_object) {
  for (const RigCamera& camera : rig.cameras()) {
    const std::string camera_dir = annotation_dir + "/" + camera.camera.name;
    BCOT_RETURN_IF_ERROR(CreateDirectories(camera_dir));
    BCOT_RETURN_IF_ERROR(WritePoseFile(camera_dir + "/pose.txt",
                                       CamFromObjectPoses(camera.cam_from_rig, rig_from_object)));
  }
  return Status::Ok();
}

}  // namespace bcot

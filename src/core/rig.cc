#include "bcot/core/rig.h"

#include <set>

#include <fmt/format.h>

#include "bcot/core/se3.h"

namespace bcot {

int Rig::Find(const std::string& name) const {
  for (int i = 0; i < size(); ++i) {
    if (cameras_[i].camera.name == name) return i;
  }
  return -1;
}

Status Rig::Validate() const {
  if (cameras_.empty()) return Status::InvalidInput("rig has no cameras");
  std::set<std::string> names;
  for (int i = 0; i < size(); ++i) {
    const Camera& camera = cameras_[i].camera;
    const std::string context = fmt::format("cameras[{}]", i);
    if (camera.name.empty()) return Status::InvalidInput(context + ".name is empty");
    if (!names.insert(camera.name).second) {
      return Status::InvalidInput(fmt::format("{}.name '{}' is used twice", context, camera.name));
    }
    BCOT_RETURN_IF_ERROR(camera.Validate(context));
    std::string why;
    if (!IsRotationMatrix(cameras_[i].cam_from_rig.linear(), 1e-6, &why)) {
      return Status::InvalidInput(context + ".cam_from_rig: " + why);
    }
  }
  return Status::Ok();
}

}  // namespace bcot

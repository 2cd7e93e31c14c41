// Object meshes: Mesh::Load (assimp + bcot's checks, bcot/render/mesh.h) of an OBJ file, and
// the BVH and a silhouette render of what loads, so that no mesh that passes the checks can make
// the ray caster fail.
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bcot::StatusOr<bcot::Mesh> mesh =
      bcot::Mesh::Load(bcot::fuzz::ScratchFile("mesh.obj", bcot::fuzz::Text(data, size)));
  if (!mesh.ok()) return 0;
  const bcot::RayCaster caster(*mesh);
  const bcot::Camera camera("fuzz", 64, 48, 60, 60, 32, 24);
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
  cam_from_object.translation() = Eigen::Vector3d(0, 0, 3 * mesh->diameter()) - mesh->bbox_center();
  (void)caster.Render(camera, cam_from_object, bcot::RenderOptions{});
  return 0;
}

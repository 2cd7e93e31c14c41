// `bcot export --format bop`: an annotated sequence → one scene of a dataset in the BOP
// "scenewise" format (bop_toolkit, docs/bop_datasets_format.md); docs/export.md for users.
//
//   <out>/models/obj_<OBJ>.ply              ASCII PLY, mm, origin at the mesh's bounding-box
//                                           centre (BOP's model frame = O_o of DESIGN.md)
//   <out>/models/models_info.json           per obj_id: diameter (largest distance between two
//                                           vertices), min_x/y/z, size_x/y/z (mm); merged with
//                                           the entries of other objects already there
//   <out>/<split>/<SCENE>/rgb[_CAM]/IMID.png|jpg          the selected frames, ids 0, 1, …
//   <out>/<split>/<SCENE>/scene_camera[_CAM].json         per image id: cam_K (row-major 9),
//                                           cam_R_w2c (row-major 9), cam_t_w2c (mm, 3);
//                                           world = the rig frame, so R|t_w2c = cam_from_rig
//   <out>/<split>/<SCENE>/scene_gt[_CAM].json             per image id: [{obj_id, cam_R_m2c,
//                                           cam_t_m2c}], m2c = cam_from_objcentre (mm)
//   <out>/<split>/<SCENE>/scene_gt_info[_CAM].json        per image id: [BopGtInfo]
//   <out>/<split>/<SCENE>/mask[_CAM]/IMID_000000.png      silhouette inside the image (0/255)
//   <out>/<split>/<SCENE>/mask_visib[_CAM]/IMID_000000.png  the same (one object, no occluder)
// OBJ, SCENE, IMID: 6-digit zero-padded ids. _CAM is "_<camera name>" (BOP's _CAMTYPE, as in
// bop_toolkit's multi-sensor datasets) when more than one camera is exported, absent for one.
// Images are undistorted and scaled like the BCOT export (exporter.h); their extension is the
// input's (.png or .jpg); an image that needs neither step is copied byte for byte. No depth
// is written, so scene_camera has no depth_scale and px_count_valid is 0.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "bcot/core/camera.h"
#include "bcot/core/rotational_symmetry.h"
#include "bcot/core/status.h"
#include "bcot/export/exporter.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

// models_info.json's entry of a mesh given in BOP's model frame (mm).
struct BopModelInfo {
  double diameter = 0.0;  // largest distance between any two vertices (exact)
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  // "symmetries_continuous": [{"axis", "offset"}] (a point on the axis, mm) when set.
  std::optional<RotationalSymmetry> symmetry;
};
BopModelInfo ComputeBopModelInfo(const Mesh& mesh);

// scene_gt_info.json's entry of one object in one image, as bop_toolkit's calc_gt_info.py
// defines it: the silhouette is rendered on a canvas of 3× the image size centred on it, so
// px_count_all and bbox_obj include the part outside the image; px_count_visib and bbox_visib
// count the part inside. Boxes are [x, y, w, h] with w = x_max − x_min (that script's
// convention), [−1, −1, −1, −1] when nothing is visible; visib_fract = visib / all (0 if none).
struct BopGtInfo {
  std::array<int, 4> bbox_obj{-1, -1, -1, -1};
  std::array<int, 4> bbox_visib{-1, -1, -1, -1};
  int px_count_all = 0;
  int px_count_valid = 0;  // pixels with a depth measurement: none without depth
  int px_count_visib = 0;
  double visib_fract = 0.0;
};

// Ray-casts the mask of `caster`'s mesh (one ray per pixel centre) for a pinhole `camera` and
// `cam_from_object` (the frame of caster's mesh); `*mask` receives the image-size mask (255 on
// the object, 0 elsewhere).
BopGtInfo RenderBopMask(const RayCaster& caster, const Camera& camera,
                        const Eigen::Isometry3d& cam_from_object, cv::Mat1b* mask);

// Writes the layout above (options.bop: split, scene id, object id; the frame, camera, scale
// and overwrite options as for the BCOT export). Errors as ExportToBcot's; an existing
// obj_<OBJ>.ply holding another mesh is kInvalidConfig unless overwrite. The summary's
// scene_dirs holds the scene folder.
StatusOr<ExportSummary> ExportToBop(const std::string& sequence_dir,
                                    const std::string& annotation_dir, const std::string& out_root,
                                    const ExportOptions& options);

}  // namespace bcot

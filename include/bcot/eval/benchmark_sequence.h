// One monocular benchmark sequence as the evaluator sees it, whatever the dataset layout
// (BCOT release, RBOT): frames, intrinsics, mesh and ground truth cam_from_object per frame.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/camera.h"

namespace bcot {

struct BenchmarkSequence {
  std::string scene;      // BCOT: scene folder; RBOT: the image variant ("a_regular")
  std::string object;     // BCOT: object folder (may hold spaces); RBOT: body name
  std::string mesh_path;  // mesh in mm, template frame O_t (the frame the GT refers to)
  // Pinhole intrinsics (no distortion: benchmark images are undistorted). width/height are 0
  // until the first image is read (the online runner does; offline scoring never needs them).
  Camera camera;
  std::vector<std::string> image_paths;               // frame i → image path
  std::vector<Eigen::Isometry3d> gt_cam_from_object;  // frame i → GT pose (mm)
  std::string gt_path;                                // the file the GT came from, for messages

  // "<scene>/<object>": also where offline results live below the results root.
  std::string RelativeDir() const { return scene + "/" + object; }
};

}  // namespace bcot

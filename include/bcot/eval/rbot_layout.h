// The RBOT dataset layout (Tjaden et al., TPAMI 2019) as its public evaluators read it:
//
//   <root>/camera_calibration.txt   an optional header line ("fx fy cx cy ..."), then one line
//                                   whose first 4 numbers are fx fy cx cy (px)
//   <root>/poses_first.txt          an optional header line, then one pose per frame,
//                                   cam_from_object in pose_io.h format (mm)
//   <root>/<body>/<body>.obj        mesh in mm
//   <root>/<body>/frames/<variant>%04d.png   e.g. a_regular0000.png ... a_regular1000.png
// The same ground truth applies to every body.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/eval/benchmark_sequence.h"

namespace bcot {

// Errors (kInvalidInput) name the file and 1-based line.
StatusOr<Camera> ReadRbotCalibration(const std::string& path);
// A first line that does not start with a number is taken as the header and skipped.
StatusOr<std::vector<Eigen::Isometry3d>> ReadRbotPoses(const std::string& path);

// Every body folder of `root` holding frames/<variant>0000.png, sorted by name; scene =
// `variant`, object = body. `poses_file` is relative to root (poses_first.txt). Each body
// needs as many frames as there are poses.
StatusOr<std::vector<BenchmarkSequence>> LoadRbotDataset(const std::string& root,
                                                         const std::string& variant,
                                                         const std::string& poses_file);

}  // namespace bcot

// The BCOT release layout (paper §4.1, DESIGN.md "Release export and evaluation"):
//
//   <root>/models/<Object>.obj            mesh in mm, template frame O_t
//   <root>/<scene>/K.txt                  `Matx33f K = Matx33f(fx, 0, cx, 0, fy, cy, 0, 0, 1);`
//                                         (readers also accept the bare `Matx33f(...)` literal
//                                         or 9 plain numbers, row-major, any separators)
//   <root>/<scene>/<Object>/0000.png ...  undistorted frames
//   <root>/<scene>/<Object>/pose.txt      cam_from_object per frame (pose_io.h format; tabs, a
//                                         trailing tab and CRLF are accepted)
// Object and scene names may contain spaces ("3D Touch").
#pragma once

#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/eval/benchmark_sequence.h"

namespace bcot {

// Parses K.txt text. The 9 numbers must form [[fx, 0, cx], [0, fy, cy], [0, 0, 1]] with
// fx, fy > 0. Errors (kInvalidInput) read "<source>:<line>: ...". The camera has no name,
// size or distortion.
StatusOr<Camera> ParseBcotIntrinsics(const std::string& text, const std::string& source);
StatusOr<Camera> ReadBcotIntrinsics(const std::string& path);
// `Matx33f K = Matx33f(fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0);` and a line end; numbers in
// shortest round-trip form, so the text reads back to the same doubles.
std::string FormatBcotIntrinsics(const Camera& camera);

// "<root>/models/<object>.obj".
std::string BcotModelPath(const std::string& root, const std::string& object);

// Every sequence of a BCOT tree, sorted by scene then object: each folder <root>/<scene>/<obj>
// holding pose.txt (scene = any top-level folder except `models`). Checks that K.txt, the
// model and the frames exist and that pose.txt has one line per frame. Images are not read.
StatusOr<std::vector<BenchmarkSequence>> LoadBcotDataset(const std::string& root);

}  // namespace bcot

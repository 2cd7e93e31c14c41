// rig.yaml (DESIGN.md, input contract):
//   cameras:
//     - name: cam0
//       image_size: [1280, 1024]
//       K: [fx, fy, cx, cy]
//       distortion: [k1, k2, p1, p2, k3]     # optional, default zeros
//       cam_from_rig: [16 numbers, row-major 4×4, mm]
// Unknown keys, missing keys, wrong types and invalid values are errors naming the file,
// 1-based line and key path (`rig.yaml:7: cameras[1].K: expected 4 numbers, got 3`).
#pragma once

#include <string>

#include "bcot/core/rig.h"
#include "bcot/core/status.h"

namespace bcot {

StatusOr<Rig> ReadRigYaml(const std::string& path);
// Parses YAML text; `source_name` is used in messages in place of a file name.
StatusOr<Rig> ParseRigYaml(const std::string& text, const std::string& source_name);
std::string FormatRigYaml(const Rig& rig);
Status WriteRigYaml(const std::string& path, const Rig& rig);  // atomic

}  // namespace bcot

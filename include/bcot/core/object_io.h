// object.yaml (DESIGN.md, input contract):
//   name: cat
//   mesh: ../models/cat.obj     # relative to the directory holding object.yaml
//   unit_to_mm: 1               # optional, > 0; mesh units × unit_to_mm = mm
#pragma once

#include <string>

#include "bcot/core/status.h"

namespace bcot {

struct ObjectSpec {
  std::string name;
  std::string mesh;         // as written in the file
  std::string mesh_path;    // `mesh` resolved against the file's directory (filled by Read)
  double unit_to_mm = 1.0;
};

// Unknown keys, missing or empty name/mesh and unit_to_mm <= 0 are InvalidInput errors naming
// the file, line and key. Does not look at the mesh file.
StatusOr<ObjectSpec> ReadObjectYaml(const std::string& path);
// ReadObjectYaml, and a NotFound error naming `object.yaml:line: mesh` when mesh_path is not
// an existing file (the mesh itself is loaded by the render layer).
StatusOr<ObjectSpec> ReadObjectYamlAndCheckMesh(const std::string& path);
std::string FormatObjectYaml(const ObjectSpec& object);  // writes name, mesh, unit_to_mm
Status WriteObjectYaml(const std::string& path, const ObjectSpec& object);  // atomic

}  // namespace bcot

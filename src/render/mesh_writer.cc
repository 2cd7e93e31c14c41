#include "bcot/render/mesh_writer.h"

#include <fmt/format.h>

#include <sstream>

namespace bcot {

std::string FormatObjMesh(const Mesh& mesh, const std::string& comment) {
  std::string text;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) text += "# " + line + "\n";
  for (const Eigen::Vector3f& v : mesh.vertices()) {
    text += fmt::format("v {} {} {}\n", v.x(), v.y(), v.z());
  }
  for (const Eigen::Vector3i& t : mesh.triangles()) {
    text += fmt::format("f {} {} {}\n", t.x() + 1, t.y() + 1, t.z() + 1);
  }
  return text;
}

}  // namespace bcot

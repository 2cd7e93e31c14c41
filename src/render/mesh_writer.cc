#include "bcot/render/mesh_writer.h"

#include <fmt/format.h>

#include <sstream>
#include <vector>

namespace bcot {
namespace {

// Each line of `comment` prefixed with `prefix`, one per line.
std::string CommentLines(const std::string& comment, const std::string& prefix) {
  std::string text;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) text += prefix + line + "\n";
  return text;
}

}  // namespace

std::string FormatObjMesh(const Mesh& mesh, const std::string& comment) {
  std::string text = CommentLines(comment, "# ");
  for (const Eigen::Vector3f& v : mesh.vertices()) {
    text += fmt::format("v {} {} {}\n", v.x(), v.y(), v.z());
  }
  for (const Eigen::Vector3i& t : mesh.triangles()) {
    text += fmt::format("f {} {} {}\n", t.x() + 1, t.y() + 1, t.z() + 1);
  }
  return text;
}

std::string FormatPlyMesh(const Mesh& mesh, const std::string& comment) {
  std::string text = "ply\nformat ascii 1.0\n" + CommentLines(comment, "comment ");
  text += fmt::format(
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
      mesh.vertices().size(), mesh.triangles().size());
  const std::vector<Eigen::Vector3f> normals = mesh.VertexNormals();
  for (size_t i = 0; i < normals.size(); ++i) {
    const Eigen::Vector3f& v = mesh.vertices()[i];
    text += fmt::format("{} {} {} {} {} {}\n", v.x(), v.y(), v.z(), normals[i].x(), normals[i].y(),
                        normals[i].z());
  }
  for (const Eigen::Vector3i& t : mesh.triangles()) {
    text += fmt::format("3 {} {} {}\n", t.x(), t.y(), t.z());
  }
  return text;
}

}  // namespace bcot

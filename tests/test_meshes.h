// Procedural meshes shared by the render tests and the render benchmark.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <utility>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/render/mesh.h"

namespace bcot::test {

// Axis-aligned box with half sides `half` (mm; a cube when all equal), centred at the origin.
inline Mesh MakeBox(const Eigen::Vector3d& half) {
  std::vector<Eigen::Vector3f> vertices;
  for (int i = 0; i < 8; ++i) {
    vertices.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                          (i & 4) ? half.z() : -half.z());
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Eigen::Vector3i> triangles;
  for (const auto& q : quads) {
    triangles.emplace_back(q[0], q[1], q[2]);
    triangles.emplace_back(q[0], q[2], q[3]);
  }
  return Mesh::FromArrays(std::move(vertices), std::move(triangles));
}
inline Mesh MakeBox(double half) { return MakeBox(Eigen::Vector3d::Constant(half)); }

// Torus around the z axis: tube centre circle radius `major`, tube radius `minor` (mm),
// `segments_u` × `segments_v` quads (2·u·v triangles).
inline Mesh MakeTorus(double major, double minor, int segments_u, int segments_v) {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
  for (int i = 0; i < segments_u; ++i) {
    const double u = 2.0 * kPi * i / segments_u;
    for (int j = 0; j < segments_v; ++j) {
      const double v = 2.0 * kPi * j / segments_v;
      vertices.emplace_back((major + minor * std::cos(v)) * std::cos(u),
                            (major + minor * std::cos(v)) * std::sin(u), minor * std::sin(v));
    }
  }
  auto index = [&](int i, int j) { return (i % segments_u) * segments_v + (j % segments_v); };
  for (int i = 0; i < segments_u; ++i) {
    for (int j = 0; j < segments_v; ++j) {
      triangles.emplace_back(index(i, j), index(i + 1, j), index(i + 1, j + 1));
      triangles.emplace_back(index(i, j), index(i + 1, j + 1), index(i, j + 1));
    }
  }
  return Mesh::FromArrays(std::move(vertices), std::move(triangles));
}

}  // namespace bcot::test

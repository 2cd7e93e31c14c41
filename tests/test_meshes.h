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

// Closed cylinder around the z axis: radius `radius`, from z = −half_length to +half_length
// (mm), `segments` side facets, caps as triangle fans; wound counter-clockwise seen from outside
// (outward normals), so its rims are 90° creases.
inline Mesh MakeCylinder(double radius, double half_length, int segments) {
  std::vector<Eigen::Vector3f> vertices;
  for (const double z : {-half_length, half_length}) {
    for (int i = 0; i < segments; ++i) {
      const double angle = 2.0 * kPi * i / segments;
      vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
    }
  }
  const int bottom_centre = 2 * segments, top_centre = 2 * segments + 1;
  vertices.emplace_back(0.0, 0.0, -half_length);
  vertices.emplace_back(0.0, 0.0, half_length);
  std::vector<Eigen::Vector3i> triangles;
  for (int i = 0; i < segments; ++i) {
    const int next = (i + 1) % segments;
    triangles.emplace_back(i, next, segments + next);  // side
    triangles.emplace_back(i, segments + next, segments + i);
    triangles.emplace_back(top_centre, segments + i, segments + next);
    triangles.emplace_back(bottom_centre, next, i);
  }
  return Mesh::FromArrays(std::move(vertices), std::move(triangles));
}

}  // namespace bcot::test

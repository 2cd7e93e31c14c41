// A triangle mesh in millimetres, in the object template frame O_t (the mesh file's frame,
// which the ground truth refers to). The object-centred frame O_o of the paper (§3.1) is O_t
// shifted to the bounding-box centre: objcentre_from_template() = translation by −centre.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/status.h"

namespace bcot {

class Mesh {
 public:
  // Loads OBJ, PLY, OFF, STL (anything assimp reads), merges all meshes of the file (node
  // transforms applied, so the result is in the file's root frame), merges vertices with
  // identical positions, scales by `unit_to_mm`. Point and line primitives mixed with
  // triangles are ignored. Errors (message names the path): missing file (kNotFound),
  // unreadable file (assimp's reason), no triangles (only points/lines or nothing), faces that
  // cannot be triangulated, non-finite coordinates, zero-size bounding box or zero total area
  // (kInvalidInput); unit_to_mm not finite and > 0 (kInvalidConfig).
  static StatusOr<Mesh> Load(const std::string& path, double unit_to_mm = 1.0);

  // Builds a mesh from arrays (tests, procedural shapes). CHECKs that indices are in range.
  static Mesh FromArrays(std::vector<Eigen::Vector3f> vertices,
                         std::vector<Eigen::Vector3i> triangles);

  const std::vector<Eigen::Vector3f>& vertices() const { return vertices_; }
  const std::vector<Eigen::Vector3i>& triangles() const { return triangles_; }

  const Eigen::Vector3d& bbox_min() const { return bbox_min_; }
  const Eigen::Vector3d& bbox_max() const { return bbox_max_; }
  Eigen::Vector3d bbox_center() const { return 0.5 * (bbox_min_ + bbox_max_); }
  // Longest bounding-box side d (mm), the ADD threshold scale of BCOT.
  double diameter() const { return (bbox_max_ - bbox_min_).maxCoeff(); }
  // O_o from O_t: a pure translation by −bbox_center().
  Eigen::Isometry3d objcentre_from_template() const;
  // Per-vertex normals in vertices() order: the area-weighted sum of the normals of the
  // triangles around a vertex (from their winding), normalised; zero at a vertex of degenerate
  // triangles only.
  std::vector<Eigen::Vector3f> VertexNormals() const;

  // Returns a copy with every vertex mapped to scale · (new_from_old · v): the rigid transform
  // first, then a uniform scale about the new origin, so that
  // `Transformed(m.objcentre_from_template(), 100.0 / m.diameter())` centres a mesh and
  // normalises its longest bounding-box side to 100 mm.
  Mesh Transformed(const Eigen::Isometry3d& new_from_old, double scale = 1.0) const;

 private:
  Mesh(std::vector<Eigen::Vector3f> vertices, std::vector<Eigen::Vector3i> triangles);
  void ComputeBounds();

  std::vector<Eigen::Vector3f> vertices_;
  std::vector<Eigen::Vector3i> triangles_;
  Eigen::Vector3d bbox_min_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_max_ = Eigen::Vector3d::Zero();
};

}  // namespace bcot

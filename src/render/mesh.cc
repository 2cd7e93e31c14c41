#include "bcot/render/mesh.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <unordered_map>
#include <utility>

namespace bcot {
namespace {

// Exact-position key: assimp keeps one vertex per (position, normal, uv) combination, so a cube
// with per-face normals arrives with 24 vertices. Merging identical positions restores the
// file's vertex list (what ADD is computed over) and a closed topology.
struct PositionHash {
  size_t operator()(const Eigen::Vector3f& p) const {
    size_t h = 0;
    for (int i = 0; i < 3; ++i) {
      // +0.0f folds −0 into +0 so that both hash alike (they compare equal).
      const float v = p[i] + 0.0f;
      uint32_t bits;
      std::memcpy(&bits, &v, sizeof(bits));
      h = h * 0x9E3779B97F4A7C15ull + bits;
    }
    return h;
  }
};

struct Collected {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::unordered_map<Eigen::Vector3f, int, PositionHash> index_of_position;
  size_t point_primitives = 0;
  size_t line_primitives = 0;
  size_t polygon_primitives = 0;  // more than 3 indices after triangulation
  bool non_finite = false;
};

void CollectNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent_from_root,
                 double unit_to_mm, Collected* out) {
  // assimp's aiMatrix4x4 maps child coordinates into the parent frame; the product walks
  // from the node up to the scene root.
  const aiMatrix4x4 root_from_node = parent_from_root * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    std::vector<int> merged_index(mesh.mNumVertices, -1);
    auto vertex_index = [&](unsigned i) {
      if (merged_index[i] >= 0) return merged_index[i];
      const aiVector3D p = root_from_node * mesh.mVertices[i];
      const Eigen::Vector3f position(static_cast<float>(p.x * unit_to_mm),
                                     static_cast<float>(p.y * unit_to_mm),
                                     static_cast<float>(p.z * unit_to_mm));
      if (!position.allFinite()) out->non_finite = true;
      auto [it, inserted] =
          out->index_of_position.emplace(position, static_cast<int>(out->vertices.size()));
      if (inserted) out->vertices.push_back(position);
      merged_index[i] = it->second;
      return it->second;
    };
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices == 1) {
        ++out->point_primitives;
      } else if (face.mNumIndices == 2) {
        ++out->line_primitives;
      } else if (face.mNumIndices == 3) {
        out->triangles.emplace_back(vertex_index(face.mIndices[0]), vertex_index(face.mIndices[1]),
                                    vertex_index(face.mIndices[2]));
      } else {
        ++out->polygon_primitives;
      }
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    CollectNode(scene, *node.mChildren[c], root_from_node, unit_to_mm, out);
  }
}

double TotalArea(const std::vector<Eigen::Vector3f>& vertices,
                 const std::vector<Eigen::Vector3i>& triangles) {
  double area = 0.0;
  for (const Eigen::Vector3i& t : triangles) {
    const Eigen::Vector3d a = vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = vertices[t[2]].cast<double>();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

}  // namespace

Mesh::Mesh(std::vector<Eigen::Vector3f> vertices, std::vector<Eigen::Vector3i> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  ComputeBounds();
}

void Mesh::ComputeBounds() {
  if (vertices_.empty()) {
    bbox_min_.setZero();
    bbox_max_.setZero();
    return;
  }
  bbox_min_ = bbox_max_ = vertices_.front().cast<double>();
  for (const Eigen::Vector3f& v : vertices_) {
    bbox_min_ = bbox_min_.cwiseMin(v.cast<double>());
    bbox_max_ = bbox_max_.cwiseMax(v.cast<double>());
  }
}

StatusOr<Mesh> Mesh::Load(const std::string& path, double unit_to_mm) {
  if (!(unit_to_mm > 0.0) || !std::isfinite(unit_to_mm)) {
    return Status::InvalidConfig(
        fmt::format("{}: unit_to_mm = {}, must be finite and > 0", path, unit_to_mm));
  }
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return Status::NotFound(fmt::format("{}: mesh file does not exist or is not a file", path));
  }

  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    return Status::InvalidInput(
        fmt::format("{}: cannot read mesh: {}", path, importer.GetErrorString()));
  }

  Collected collected;
  CollectNode(*scene, *scene->mRootNode, aiMatrix4x4(), unit_to_mm, &collected);

  if (collected.non_finite) {
    return Status::InvalidInput(fmt::format(
        "{}: mesh has non-finite vertex coordinates (NaN or inf) after scaling by unit_to_mm = {}",
        path, unit_to_mm));
  }
  if (collected.polygon_primitives > 0) {
    return Status::InvalidInput(
        fmt::format("{}: {} faces with more than 3 vertices could not be triangulated", path,
                    collected.polygon_primitives));
  }
  if (collected.triangles.empty()) {
    if (collected.point_primitives + collected.line_primitives > 0) {
      return Status::InvalidInput(fmt::format(
          "{}: mesh has no triangles, only {} point and {} line primitives (a surface is needed)",
          path, collected.point_primitives, collected.line_primitives));
    }
    return Status::InvalidInput(fmt::format("{}: mesh has no faces", path));
  }

  Mesh mesh(std::move(collected.vertices), std::move(collected.triangles));
  if (!(mesh.diameter() > 0.0)) {
    return Status::InvalidInput(
        fmt::format("{}: zero-size bounding box (all vertices coincide)", path));
  }
  // An object this tool annotates is between a grain and a room in size; anything outside
  // comes from a wrong unit_to_mm or a stray vertex, and would make rays Embree cannot take.
  constexpr double kMinDiameterMm = 0.01, kMaxDiameterMm = 1e5;
  if (mesh.diameter() < kMinDiameterMm || mesh.diameter() > kMaxDiameterMm) {
    return Status::InvalidInput(fmt::format(
        "{}: the mesh's bounding box is {:g} mm across (longest side) with unit_to_mm = {}; "
        "expected {} mm to {:g} m: check unit_to_mm in object.yaml or stray vertices",
        path, mesh.diameter(), unit_to_mm, kMinDiameterMm, kMaxDiameterMm / 1000));
  }
  if (!(TotalArea(mesh.vertices_, mesh.triangles_) > 0.0)) {
    return Status::InvalidInput(fmt::format(
        "{}: all {} triangles have zero area (degenerate bounding box or collinear vertices)", path,
        mesh.triangles_.size()));
  }
  return mesh;
}

Mesh Mesh::FromArrays(std::vector<Eigen::Vector3f> vertices,
                      std::vector<Eigen::Vector3i> triangles) {
  const int n = static_cast<int>(vertices.size());
  for (const Eigen::Vector3i& t : triangles) {
    BCOT_CHECK(t.minCoeff() >= 0 && t.maxCoeff() < n);
  }
  return Mesh(std::move(vertices), std::move(triangles));
}

Eigen::Isometry3d Mesh::objcentre_from_template() const {
  Eigen::Isometry3d objcentre_from_template = Eigen::Isometry3d::Identity();
  objcentre_from_template.translation() = -bbox_center();
  return objcentre_from_template;
}

std::vector<Eigen::Vector3f> Mesh::VertexNormals() const {
  std::vector<Eigen::Vector3f> normals(vertices_.size(), Eigen::Vector3f::Zero());
  for (const Eigen::Vector3i& t : triangles_) {
    const Eigen::Vector3f& a = vertices_[t.x()];
    const Eigen::Vector3f twice_area_normal = (vertices_[t.y()] - a).cross(vertices_[t.z()] - a);
    for (int i = 0; i < 3; ++i) normals[t[i]] += twice_area_normal;
  }
  for (Eigen::Vector3f& n : normals) {
    if (n.norm() > 0.0f) n.normalize();
  }
  return normals;
}

Mesh Mesh::Transformed(const Eigen::Isometry3d& new_from_old, double scale) const {
  std::vector<Eigen::Vector3f> vertices;
  vertices.reserve(vertices_.size());
  for (const Eigen::Vector3f& v : vertices_) {
    vertices.push_back((scale * (new_from_old * v.cast<double>())).cast<float>());
  }
  return Mesh(std::move(vertices), triangles_);
}

}  // namespace bcot

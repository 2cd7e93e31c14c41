// A sparse viewpoint model of the silhouette contour (issue 19; the contour models of SRT3D
// and M3T): for viewpoints spread evenly over a sphere around the object, a fixed number of
// points of the silhouette contour seen from there, each with its outward normal and how far
// the silhouette continues on either side of it. The region rounds of the sparse energy
// (correspondence_lines.h) need only these per line, so a model whose viewpoints are each
// rendered once replaces the silhouette render of every round by a table lookup and a
// projection of some hundred points (docs/sparse_viewpoint_model.md; measured with
// scripts/bench_render.sh).
//
// Build, per viewpoint direction v (unit, O_t, from the bounding-box centre c towards the
// camera): a virtual pinhole camera at c + d·v (d = distance_factor·r, r = half the bounding-box
// diagonal, so the whole object is in front of it), looking at c, with a square image of
// image_size_px in which the bounding sphere fills 90 %. Its mask is rendered and its contour
// extracted (RayCaster::ExtractContour, 1/64 px); points_per_viewpoint of the contour samples,
// evenly spaced along all contours, are kept with
//   point      the contour's model point X (O_t, mm);
//   normal     the contour's outward 2D normal n as a 3D direction in O_t: R_tc·(n_x, n_y, 0),
//              orthogonal to the virtual camera's optical axis;
//   inside, outside  the distance (mm at X's depth) along −n and +n over which the virtual mask
//              keeps its value: a line through the point that must not cross a second contour
//              stops there. Outside is +∞ where nothing of the object lies beyond the point (a
//              cap would shorten the coarse levels' lines around small objects, whose length in
//              mm is not known here: with a cap of half the bounding-sphere radius the real
//              BCOT Cat was lost from the coarse levels, docs/sparse_viewpoint_model.md).
// The viewpoints are the vertices of an icosahedron whose faces are split in four
// `sphere_subdivisions` times (10·4^k + 2 of them; k = 5: 10,242, about 2° apart; M3T uses
// k = 4, which was up to 60 % worse at the tracking setting on the Cycles scenes in a first
// measurement, docs/sparse_viewpoint_model.md).
//
// Use. For a camera at cam_from_template, Nearest() is the viewpoint closest in direction to
// the camera's centre as seen from c; Project() maps its points into the camera: pixel x(X),
// 2D normal = the projection of the 3D normal at X (∂x/∂X·R·N, normalised), extents scaled by
// the same projection. The contour of the nearest viewpoint differs from the camera's own by
// the angle between them (at most half the viewpoint spacing) and by the distance: the lines
// built on it measure where the image's boundary lies relative to each point, so the model
// moves the lines' anchors, not what they measure. The exact contour (RenderSilhouette) stays
// where the anchor matters to a fraction of a pixel: the edge stage, the colour models, the
// quality check.
//
// Build. Build() renders all 10,242 viewpoints (20–40 s of CPU); BuildOnDemand() renders each
// when it is first used, and a sequence uses a few hundred at most (30 binocular frames of the
// bunny as scripts/bench_throughput.sh synthesizes them: 69), so the tracker needs neither a
// build step nor a cache. Serialize()/Deserialize() write and read a model as a binary file
// (host byte order, not an exchange format) whose header holds CacheKey(mesh, options), so a
// file made for another mesh or other options is never used.
//
// Frames and units: O_t (the mesh's template frame), mm; pixels as ray_caster.h.
// Thread safety: a built model is immutable, one built on demand only fills its viewpoints (each
// once, under its own flag); the const methods of either may run concurrently.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct SparseViewpointModelOptions {
  // Icosahedron subdivisions: 10·4^k + 2 viewpoints; in [0, 6].
  int sphere_subdivisions = 5;
  // Contour points kept per viewpoint; >= 1.
  int points_per_viewpoint = 200;
  // Distance of the virtual cameras from the bounding-box centre, in units of r (half the
  // bounding-box diagonal); > 1. 8: an object 100 mm across seen from some 400–700 mm.
  double distance_factor = 8.0;
  // Side of the virtual cameras' square images (px); in [64, 4096].
  int image_size_px = 400;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

struct ViewpointContourPoint {
  Eigen::Vector3f point = Eigen::Vector3f::Zero();   // X in O_t, mm
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // outward contour normal, unit, O_t
  float inside_mm = 0.0f;                            // extent along −normal
  float outside_mm = 0.0f;                           // extent along +normal; may be +∞
};

struct Viewpoint {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit, O_t, centre → camera
  std::vector<ViewpointContourPoint> points;             // along the contours, in order
};

// A point of the model projected into a camera.
struct ProjectedContourPoint {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();          // unit, outward
  Eigen::Vector3d point_in_object = Eigen::Vector3d::Zero();  // X in O_t, mm
  double inside_px = 0.0;
  double outside_px = 0.0;  // may be +∞
};

// cam_from_object of a camera at `target` + distance·direction (unit `direction`, object frame)
// looking at `target`, its image x axis orthogonal to the view, rolled by `roll_rad` about it.
Eigen::Isometry3d LookAtCamFromObject(const Eigen::Vector3d& target,
                                      const Eigen::Vector3d& direction, double distance,
                                      double roll_rad = 0.0);

// The unit vertices of an icosahedron subdivided `subdivisions` times (in [0, 6], CHECKed):
// 10·4^k + 2 directions spread evenly over the sphere.
std::vector<Eigen::Vector3d> GeodesicSphere(int subdivisions);

class SparseViewpointModel {
 public:
  // Builds the model of caster.mesh(); `options` must be valid (CHECKed). Viewpoints are
  // rendered in parallel on the calling TBB arena.
  static SparseViewpointModel Build(const RayCaster& caster,
                                    const SparseViewpointModelOptions& options);
  // The same model with each viewpoint's contour built when it is first used (viewpoint(),
  // Project(), Serialize()), once, from any thread; the directions and Nearest() are ready at
  // once. A sequence visits a few hundred of the 10,242 viewpoints, so this costs well under a
  // second instead of Build()'s 20–40 s; every viewpoint is the one Build() makes. `caster` must
  // outlive the model.
  static SparseViewpointModel BuildOnDemand(const RayCaster& caster,
                                            const SparseViewpointModelOptions& options);

  SparseViewpointModel();
  SparseViewpointModel(SparseViewpointModel&&) noexcept;
  SparseViewpointModel& operator=(SparseViewpointModel&&) noexcept;
  ~SparseViewpointModel();

  // A hash (16 hex digits) of the mesh's vertices and triangles, the options and the format
  // version: what a cached model must have been built from.
  static std::string CacheKey(const Mesh& mesh, const SparseViewpointModelOptions& options);

  // The model as bytes (header with CacheKey, then the viewpoints).
  std::string Serialize() const;
  // A model from Serialize()'s bytes, read from `source` (named in errors). Errors
  // (kInvalidInput): not a viewpoint model, another format version or byte order, a key other
  // than `expected_key`, truncated or inconsistent contents.
  static StatusOr<SparseViewpointModel> Deserialize(const std::string& bytes,
                                                    const std::string& expected_key,
                                                    const std::string& source);

  const std::string& key() const { return key_; }
  int size() const { return static_cast<int>(viewpoints_.size()); }
  // Viewpoint i, its contour built first when the model builds on demand.
  const Viewpoint& viewpoint(int i) const;
  // How many viewpoints have their contour: size() unless built on demand.
  int num_built() const;
  // The bounding-box centre c the directions are taken from (O_t, mm).
  const Eigen::Vector3d& centre() const { return centre_; }

  // Index of the viewpoint whose direction is closest to that of the camera's centre as seen
  // from c, for a camera at `cam_from_template`.
  int Nearest(const Eigen::Isometry3d& cam_from_template) const;

  // The points of viewpoint `index` projected into `camera` at `cam_from_template`; points
  // behind the camera or whose pixel is outside the image are left out.
  std::vector<ProjectedContourPoint> Project(int index, const Camera& camera,
                                             const Eigen::Isometry3d& cam_from_template) const;

 private:
  struct OnDemand;  // what builds the viewpoints not built yet (BuildOnDemand)

  // Builds viewpoint i's contour unless it has been built.
  void EnsureBuilt(size_t i) const;
  // EnsureBuilt of every viewpoint, in parallel on the calling TBB arena.
  void EnsureAllBuilt() const;

  std::string key_;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  // The directions are set when the model is made and never change (Nearest() reads them from
  // any thread); a model built on demand fills each viewpoint's points once, in EnsureBuilt.
  mutable std::vector<Viewpoint> viewpoints_;
  std::unique_ptr<OnDemand> on_demand_;  // null when every viewpoint is built
};

}  // namespace bcot

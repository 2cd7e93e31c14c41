#include "bcot/render/sparse_viewpoint_model.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "bcot/core/content_hash.h"
#include "bcot/core/violations.h"

namespace bcot {
namespace {

// Serialized format: kMagic, then uint32 kFormatVersion and kByteOrderMark, the 16-character
// key, the centre (3 doubles), uint32 viewpoint count; per viewpoint its direction (3 doubles),
// uint32 point count and per point 8 floats (point, normal, inside, outside).
constexpr char kMagic[8] = {'B', 'C', 'O', 'T', 'S', 'V', 'M', '\n'};
constexpr uint32_t kFormatVersion = 2;
constexpr uint32_t kByteOrderMark = 0x01020304;
constexpr size_t kKeyLength = 16;
constexpr int kFloatsPerPoint = 8;
// Share of the virtual image the bounding sphere's projection spans (its diameter).
constexpr double kSphereImageFraction = 0.9;
// Contour extraction of the virtual views: samples every pixel, 1/64 px bisection.
constexpr double kContourSpacingPx = 1.0;
constexpr double kContourPrecisionPx = 1.0 / 64.0;
// Step (virtual px) of the walk that measures the extents, and where it starts: a pixel centre
// is up to 0.71 px from the contour point it is looked up for, so a flip within the first pixel
// may be the rounding of the point's own contour.
constexpr double kExtentStepPx = 0.25;
constexpr double kExtentStartPx = 1.0;
constexpr double kUnboundedExtent = std::numeric_limits<double>::infinity();

// Distance (px) from `start` (in the roi) along the unit `direction` to where `mask` (the
// render of `roi`) stops being `inside`; kUnboundedExtent when the walk leaves the roi outside
// the object (the object lies within the roi, so nothing beyond it can flip back).
double MaskExtentPx(const cv::Mat1b& mask, const cv::Rect& roi, const Eigen::Vector2d& start,
                    const Eigen::Vector2d& direction, bool inside) {
  // A unit step leaves the roi within its width plus height; the bound also ends the walk of a
  // degenerate (zero) direction.
  const double longest = roi.width + roi.height + kExtentStartPx;
  for (double t = kExtentStartPx; t <= longest; t += kExtentStepPx) {
    const Eigen::Vector2d p = start + t * direction;
    const int x = static_cast<int>(std::lround(p.x())) - roi.x;
    const int y = static_cast<int>(std::lround(p.y())) - roi.y;
    const bool in_roi = x >= 0 && y >= 0 && x < mask.cols && y < mask.rows;
    if (!in_roi && !inside) return kUnboundedExtent;
    const bool hit = in_roi && mask(y, x) != 0;
    // The flip lies between this sample and the previous one.
    if (hit != inside) return t - 0.5 * kExtentStepPx;
  }
  return inside ? longest : kUnboundedExtent;
}

Viewpoint BuildViewpoint(const RayCaster& caster, const SparseViewpointModelOptions& options,
                         const Eigen::Vector3d& centre, double radius,
                         const Eigen::Vector3d& direction) {
  const double distance = options.distance_factor * radius;
  const double size = options.image_size_px;
  const double focal =
      0.5 * kSphereImageFraction * size * std::sqrt(distance * distance - radius * radius) / radius;
  const Camera camera("viewpoint", options.image_size_px, options.image_size_px, focal, focal,
                      0.5 * (size - 1.0), 0.5 * (size - 1.0));
  const Eigen::Isometry3d cam_from_template = LookAtCamFromObject(centre, direction, distance);
  ContourOptions contour_options;
  contour_options.sample_spacing_px = kContourSpacingPx;
  contour_options.precision_px = kContourPrecisionPx;
  RenderOptions render_options;
  render_options.margin_px = contour_options.margin_px;
  render_options.depth = render_options.normal_in_cam = render_options.point_in_object =
      render_options.triangle_id = false;
  const RenderedView view = caster.Render(camera, cam_from_template, render_options);
  const std::vector<ContourPoint> contour =
      caster.ExtractContour(camera, cam_from_template, contour_options, &view);

  Viewpoint viewpoint;
  viewpoint.direction = direction;
  if (contour.empty()) return viewpoint;
  const int count = std::min<int>(options.points_per_viewpoint, static_cast<int>(contour.size()));
  const Eigen::Matrix3d template_from_cam = cam_from_template.linear().transpose();
  viewpoint.points.reserve(count);
  for (int j = 0; j < count; ++j) {
    const ContourPoint& c = contour[static_cast<size_t>((j + 0.5) * contour.size() / count)];
    const double depth = (cam_from_template * c.point_in_object).z();
    const double mm_per_px = depth / focal;
    ViewpointContourPoint p;
    p.point = c.point_in_object.cast<float>();
    p.normal = (template_from_cam * Eigen::Vector3d(c.normal.x(), c.normal.y(), 0.0)).cast<float>();
    p.inside_mm = static_cast<float>(
        mm_per_px * MaskExtentPx(view.mask, view.roi, c.pixel, -c.normal, /*inside=*/true));
    p.outside_mm = static_cast<float>(
        mm_per_px * MaskExtentPx(view.mask, view.roi, c.pixel, c.normal, /*inside=*/false));
    viewpoint.points.push_back(p);
  }
  return viewpoint;
}

// Appends the raw bytes of `value`.
template <typename T>
void Put(std::string* out, const T& value) {
  out->append(reinterpret_cast<const char*>(&value), sizeof(T));
}

// Reads values from serialized bytes, failing (sticky) when they run out.
class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  bool Get(T* value) {
    if (!ok_ || bytes_.size() - offset_ < sizeof(T)) return ok_ = false;
    std::memcpy(value, bytes_.data() + offset_, sizeof(T));
    offset_ += sizeof(T);
    return true;
  }
  bool GetBytes(size_t count, std::string* value) {
    if (!ok_ || bytes_.size() - offset_ < count) return ok_ = false;
    value->assign(bytes_, offset_, count);
    offset_ += count;
    return true;
  }
  size_t remaining() const { return bytes_.size() - offset_; }

 private:
  const std::string& bytes_;
  size_t offset_ = 0;
  bool ok_ = true;
};

}  // namespace

Status SparseViewpointModelOptions::Validate() const {
  std::vector<std::string> violations;
  if (sphere_subdivisions < 0 || sphere_subdivisions > 6) {
    violations.push_back(
        fmt::format("sphere_subdivisions = {}, must be in [0, 6]", sphere_subdivisions));
  }
  if (points_per_viewpoint < 1) {
    violations.push_back(
        fmt::format("points_per_viewpoint = {}, must be >= 1", points_per_viewpoint));
  }
  if (!(distance_factor > 1.0) || !std::isfinite(distance_factor)) {
    violations.push_back(
        fmt::format("distance_factor = {}, must be finite and > 1", distance_factor));
  }
  if (image_size_px < 64 || image_size_px > 4096) {
    violations.push_back(fmt::format("image_size_px = {}, must be in [64, 4096]", image_size_px));
  }
  return internal::JoinViolations("sparse viewpoint model", violations);
}

Eigen::Isometry3d LookAtCamFromObject(const Eigen::Vector3d& target,
                                      const Eigen::Vector3d& direction, double distance,
                                      double roll_rad) {
  const Eigen::Vector3d z = -direction;
  // Any axis orthogonal to z will do before the roll: a silhouette does not depend on it.
  const Eigen::Vector3d x = z.unitOrthogonal();
  Eigen::Matrix3d object_from_cam;
  object_from_cam << x, z.cross(x), z;
  object_from_cam = object_from_cam * Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitZ());
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
  cam_from_object.linear() = object_from_cam.transpose();
  cam_from_object.translation() = -object_from_cam.transpose() * (target + distance * direction);
  return cam_from_object;
}

std::vector<Eigen::Vector3d> GeodesicSphere(int subdivisions) {
  BCOT_CHECK(subdivisions >= 0 && subdivisions <= 6);
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  std::vector<Eigen::Vector3d> vertices = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                           {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                           {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (Eigen::Vector3d& v : vertices) v.normalize();
  std::vector<std::array<int, 3>> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    // Each edge's midpoint, projected to the sphere, is made once and shared by its two faces.
    std::map<std::pair<int, int>, int> midpoints;
    const auto midpoint = [&](int a, int b) {
      const std::pair<int, int> edge = std::minmax(a, b);
      const auto found = midpoints.find(edge);
      if (found != midpoints.end()) return found->second;
      vertices.push_back((vertices[a] + vertices[b]).normalized());
      const int index = static_cast<int>(vertices.size()) - 1;
      midpoints.emplace(edge, index);
      return index;
    };
    std::vector<std::array<int, 3>> finer;
    finer.reserve(4 * faces.size());
    for (const std::array<int, 3>& f : faces) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }
  return vertices;
}

struct SparseViewpointModel::OnDemand {
  OnDemand(const RayCaster& caster, const SparseViewpointModelOptions& options, size_t size)
      : caster(caster),
        options(options),
        radius(0.5 * (caster.mesh().bbox_max() - caster.mesh().bbox_min()).norm()),
        built_once(new std::once_flag[size]) {}

  const RayCaster& caster;
  const SparseViewpointModelOptions options;
  const double radius;  // half the mesh's bounding-box diagonal
  const std::unique_ptr<std::once_flag[]> built_once;
  std::atomic<int> num_built{0};
};

SparseViewpointModel::SparseViewpointModel() = default;
SparseViewpointModel::SparseViewpointModel(SparseViewpointModel&&) noexcept = default;
SparseViewpointModel& SparseViewpointModel::operator=(SparseViewpointModel&&) noexcept = default;
SparseViewpointModel::~SparseViewpointModel() = default;

SparseViewpointModel SparseViewpointModel::BuildOnDemand(
    const RayCaster& caster, const SparseViewpointModelOptions& options) {
  const Status status = options.Validate();
  BCOT_CHECK(status.ok());
  const Mesh& mesh = caster.mesh();
  SparseViewpointModel model;
  model.key_ = CacheKey(mesh, options);
  model.centre_ = mesh.bbox_center();
  const std::vector<Eigen::Vector3d> directions = GeodesicSphere(options.sphere_subdivisions);
  model.viewpoints_.resize(directions.size());
  for (size_t i = 0; i < directions.size(); ++i) model.viewpoints_[i].direction = directions[i];
  model.on_demand_ = std::make_unique<OnDemand>(caster, options, directions.size());
  return model;
}

SparseViewpointModel SparseViewpointModel::Build(const RayCaster& caster,
                                                 const SparseViewpointModelOptions& options) {
  SparseViewpointModel model = BuildOnDemand(caster, options);
  model.EnsureAllBuilt();
  model.on_demand_.reset();
  return model;
}

void SparseViewpointModel::EnsureBuilt(size_t i) const {
  if (on_demand_ == nullptr) return;
  std::call_once(on_demand_->built_once[i], [&] {
    // Isolated: while this thread waits for the render's own parallel loop, it must not take
    // another task of the caller's loop, which could ask for this viewpoint again and wait on
    // its own flag.
    tbb::this_task_arena::isolate([&] {
      viewpoints_[i].points = BuildViewpoint(on_demand_->caster, on_demand_->options, centre_,
                                             on_demand_->radius, viewpoints_[i].direction)
                                  .points;
    });
    on_demand_->num_built.fetch_add(1, std::memory_order_relaxed);
  });
}

void SparseViewpointModel::EnsureAllBuilt() const {
  if (on_demand_ == nullptr) return;
  tbb::parallel_for(size_t{0}, viewpoints_.size(), [&](size_t i) { EnsureBuilt(i); });
}

const Viewpoint& SparseViewpointModel::viewpoint(int i) const {
  BCOT_CHECK(i >= 0 && i < size());
  EnsureBuilt(static_cast<size_t>(i));
  return viewpoints_[static_cast<size_t>(i)];
}

int SparseViewpointModel::num_built() const {
  return on_demand_ == nullptr ? size() : on_demand_->num_built.load(std::memory_order_relaxed);
}

std::string SparseViewpointModel::CacheKey(const Mesh& mesh,
                                           const SparseViewpointModelOptions& options) {
  ContentHash hash;
  hash.Add(fmt::format("sparse viewpoint model {}", kFormatVersion));
  hash.Add(std::string_view(reinterpret_cast<const char*>(mesh.vertices().data()),
                            mesh.vertices().size() * sizeof(Eigen::Vector3f)));
  hash.Add(std::string_view(reinterpret_cast<const char*>(mesh.triangles().data()),
                            mesh.triangles().size() * sizeof(Eigen::Vector3i)));
  hash.Add(fmt::format("{} {} {:.17g} {}", options.sphere_subdivisions,
                       options.points_per_viewpoint, options.distance_factor,
                       options.image_size_px));
  return hash.Hex();
}

std::string SparseViewpointModel::Serialize() const {
  EnsureAllBuilt();
  std::string out(kMagic, sizeof(kMagic));
  Put(&out, kFormatVersion);
  Put(&out, kByteOrderMark);
  BCOT_CHECK(key_.size() == kKeyLength);
  out += key_;
  for (int k = 0; k < 3; ++k) Put(&out, centre_[k]);
  Put(&out, static_cast<uint32_t>(viewpoints_.size()));
  for (const Viewpoint& viewpoint : viewpoints_) {
    for (int k = 0; k < 3; ++k) Put(&out, viewpoint.direction[k]);
    Put(&out, static_cast<uint32_t>(viewpoint.points.size()));
    for (const ViewpointContourPoint& p : viewpoint.points) {
      const std::array<float, kFloatsPerPoint> values = {p.point.x(),  p.point.y(),  p.point.z(),
                                                         p.normal.x(), p.normal.y(), p.normal.z(),
                                                         p.inside_mm,  p.outside_mm};
      for (float value : values) Put(&out, value);
    }
  }
  return out;
}

StatusOr<SparseViewpointModel> SparseViewpointModel::Deserialize(const std::string& bytes,
                                                                 const std::string& expected_key,
                                                                 const std::string& source) {
  const auto invalid = [&](const std::string& reason) {
    return Status::InvalidInput(fmt::format("{}: {}", source, reason));
  };
  ByteReader reader(bytes);
  std::string magic;
  if (!reader.GetBytes(sizeof(kMagic), &magic) || magic != std::string(kMagic, sizeof(kMagic))) {
    return invalid("not a sparse viewpoint model");
  }
  uint32_t version = 0, byte_order = 0;
  if (!reader.Get(&version) || version != kFormatVersion) {
    return invalid(fmt::format("format version {}, expected {}", version, kFormatVersion));
  }
  if (!reader.Get(&byte_order) || byte_order != kByteOrderMark) {
    return invalid("written on a machine of another byte order");
  }
  SparseViewpointModel model;
  if (!reader.GetBytes(kKeyLength, &model.key_)) return invalid("truncated header");
  if (model.key_ != expected_key) {
    return invalid(fmt::format("built for key {}, expected {} (another mesh or other options)",
                               model.key_, expected_key));
  }
  uint32_t count = 0;
  for (int k = 0; k < 3; ++k) reader.Get(&model.centre_[k]);
  if (!reader.Get(&count)) return invalid("truncated header");
  // Each viewpoint takes at least its direction and point count.
  if (count > reader.remaining() / (3 * sizeof(double) + sizeof(uint32_t))) {
    return invalid(fmt::format("{} viewpoints do not fit in the file", count));
  }
  model.viewpoints_.resize(count);
  for (uint32_t i = 0; i < count; ++i) {
    Viewpoint& viewpoint = model.viewpoints_[i];
    for (int k = 0; k < 3; ++k) reader.Get(&viewpoint.direction[k]);
    uint32_t points = 0;
    if (!reader.Get(&points) || points > reader.remaining() / (kFloatsPerPoint * sizeof(float))) {
      return invalid(fmt::format("viewpoint {} is truncated", i));
    }
    if (!(std::abs(viewpoint.direction.norm() - 1.0) < 1e-6)) {
      return invalid(fmt::format("viewpoint {}: direction is not a unit vector", i));
    }
    viewpoint.points.resize(points);
    for (ViewpointContourPoint& p : viewpoint.points) {
      std::array<float, kFloatsPerPoint> values{};
      for (float& value : values) reader.Get(&value);
      p.point = Eigen::Vector3f(values[0], values[1], values[2]);
      p.normal = Eigen::Vector3f(values[3], values[4], values[5]);
      p.inside_mm = values[6];
      p.outside_mm = values[7];
      // Point, normal and inside extent finite; the outside extent may be unbounded.
      const bool finite = std::all_of(values.begin(), values.begin() + 7,
                                      [](float value) { return std::isfinite(value); });
      if (!finite || p.inside_mm < 0.0f || !(p.outside_mm >= 0.0f)) {
        return invalid(fmt::format(
            "viewpoint {}: a point is not finite or has a negative or undefined extent", i));
      }
    }
  }
  if (reader.remaining() != 0) {
    return invalid(fmt::format("{} bytes after the last viewpoint", reader.remaining()));
  }
  return model;
}

int SparseViewpointModel::Nearest(const Eigen::Isometry3d& cam_from_template) const {
  BCOT_CHECK(!viewpoints_.empty());
  const Eigen::Vector3d camera_in_template = cam_from_template.inverse().translation();
  const Eigen::Vector3d direction = camera_in_template - centre_;
  int best = 0;
  double best_dot = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < size(); ++i) {
    const double dot = viewpoints_[static_cast<size_t>(i)].direction.dot(direction);
    if (dot > best_dot) {
      best_dot = dot;
      best = i;
    }
  }
  return best;
}

std::vector<ProjectedContourPoint> SparseViewpointModel::Project(
    int index, const Camera& camera, const Eigen::Isometry3d& cam_from_template) const {
  const Viewpoint& source = viewpoint(index);
  const Eigen::Matrix3d rotation = cam_from_template.linear();
  std::vector<ProjectedContourPoint> projected;
  projected.reserve(source.points.size());
  Eigen::Matrix<double, 2, 3> d_pixel_d_point;
  for (const ViewpointContourPoint& p : source.points) {
    ProjectedContourPoint out;
    out.point_in_object = p.point.cast<double>();
    const Eigen::Vector3d in_cam = cam_from_template * out.point_in_object;
    if (!(in_cam.z() > 0.0)) continue;
    out.pixel = camera.Project(in_cam, &d_pixel_d_point);
    if (!camera.InImage(out.pixel)) continue;
    // Pixels per mm along the 3D normal at X: the projection's derivative in that direction.
    const Eigen::Vector2d along = d_pixel_d_point * (rotation * p.normal.cast<double>());
    const double px_per_mm = along.norm();
    if (!(px_per_mm > 0.0)) continue;
    out.normal = along / px_per_mm;
    out.inside_px = p.inside_mm * px_per_mm;
    out.outside_px = p.outside_mm * px_per_mm;
    projected.push_back(out);
  }
  return projected;
}

}  // namespace bcot

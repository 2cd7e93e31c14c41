#include "bcot/render/ray_caster.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "ray_caster_internal.h"

namespace bcot {

// ---------------------------------------------------------------------------------------------
// Options
// ---------------------------------------------------------------------------------------------

namespace {

// Box corners closer to the camera plane than this (mm) count as behind the camera.
constexpr double kMinDepthMm = 1e-3;

Status JoinViolations(const std::string& context, const std::vector<std::string>& violations) {
  if (violations.empty()) return Status::Ok();
  std::string message = context + ": " + violations[0];
  for (size_t i = 1; i < violations.size(); ++i) message += "; " + violations[i];
  return Status::InvalidConfig(message);
}

}  // namespace

Status RenderOptions::Validate() const {
  std::vector<std::string> violations;
  if (roi.width < 0 || roi.height < 0) {
    violations.push_back(
        fmt::format("roi = [{}, {}, {}, {}] (x, y, width, height), width and "
                    "height must be >= 0 (0 = projected bounding box)",
                    roi.x, roi.y, roi.width, roi.height));
  }
  if (margin_px < 0) {
    violations.push_back(fmt::format("margin_px = {}, must be >= 0", margin_px));
  }
  if (samples_per_axis < 1 || samples_per_axis > kMaxSamplesPerAxis) {
    violations.push_back(fmt::format("samples_per_axis = {}, must be in [1, {}]", samples_per_axis,
                                     kMaxSamplesPerAxis));
  }
  if (point_stride_px < 1) {
    violations.push_back(fmt::format("point_stride_px = {}, must be >= 1", point_stride_px));
  }
  if (point_stride_px > 1 && samples_per_axis != 1) {
    violations.push_back(fmt::format("point_stride_px = {} needs samples_per_axis = 1, not {}",
                                     point_stride_px, samples_per_axis));
  }
  if (!mask_everywhere && !(depth || normal_in_cam || point_in_object || triangle_id)) {
    violations.push_back(
        "mask_everywhere = false needs depth, normal_in_cam, point_in_object or "
        "triangle_id (else nothing is traced)");
  }
  return JoinViolations("render", violations);
}

// ---------------------------------------------------------------------------------------------
// Embree scene
// ---------------------------------------------------------------------------------------------

RayCaster::Impl::Impl(const Mesh& mesh_in) : mesh(mesh_in) {
  device = rtcNewDevice(nullptr);
  BCOT_CHECK(device != nullptr);
  scene = rtcNewScene(device);
  BCOT_CHECK(scene != nullptr);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  // Robust mode keeps rays from slipping through shared edges, which would punch pinholes into
  // masks and make the contour bisection see spurious misses.
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);

  if (!mesh.triangles().empty()) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    BCOT_CHECK(geometry != nullptr);
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_MEDIUM);
    // rtcSetNewGeometryBuffer over-allocates vertex buffers so that the last vertex can be read
    // with a 16-byte load (the padding LIBRARIES.md mentions for shared buffers).
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices().size()));
    BCOT_CHECK(vertices != nullptr);
    for (size_t i = 0; i < mesh.vertices().size(); ++i) {
      const Eigen::Vector3f& v = mesh.vertices()[i];
      vertices[3 * i + 0] = v.x();
      vertices[3 * i + 1] = v.y();
      vertices[3 * i + 2] = v.z();
    }
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles().size()));
    BCOT_CHECK(indices != nullptr);
    for (size_t i = 0; i < mesh.triangles().size(); ++i) {
      const Eigen::Vector3i& t = mesh.triangles()[i];
      indices[3 * i + 0] = static_cast<unsigned>(t[0]);
      indices[3 * i + 1] = static_cast<unsigned>(t[1]);
      indices[3 * i + 2] = static_cast<unsigned>(t[2]);
    }
    rtcCommitGeometry(geometry);
    const unsigned geometry_id = rtcAttachGeometry(scene, geometry);
    BCOT_CHECK(geometry_id == 0);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene);
  BCOT_CHECK(rtcGetDeviceError(device) == RTC_ERROR_NONE);
}

RayCaster::Impl::~Impl() {
  if (scene != nullptr) rtcReleaseScene(scene);
  if (device != nullptr) rtcReleaseDevice(device);
}

// ---------------------------------------------------------------------------------------------
// Ray helpers
// ---------------------------------------------------------------------------------------------

namespace render_internal {

RayFrame::RayFrame(const Eigen::Isometry3d& cam_from_object) {
  cam_from_object_rotation = cam_from_object.linear();
  object_from_cam_rotation = cam_from_object_rotation.transpose();
  cam_centre_in_object = -(object_from_cam_rotation * cam_from_object.translation());
}

Eigen::Vector3d PixelToRayNear(const Camera& camera, const Eigen::Vector2d& pixel,
                               Eigen::Vector2d* normalized_guess) {
  const Eigen::Vector2d target((pixel.x() - camera.cx) / camera.fx,
                               (pixel.y() - camera.cy) / camera.fy);
  if (!camera.HasDistortion()) return {target.x(), target.y(), 1.0};
  Eigen::Vector2d normalized = *normalized_guess;
  // Same Newton iteration and stopping rule as Camera::PixelToRay.
  bool converged = false;
  for (int iteration = 0; iteration < 20; ++iteration) {
    Eigen::Matrix2d jacobian;
    const Eigen::Vector2d residual = camera.Distort(normalized, &jacobian) - target;
    if (residual.squaredNorm() < 1e-26) {
      converged = true;
      break;
    }
    normalized -= jacobian.partialPivLu().solve(residual);
  }
  if (!converged || !normalized.allFinite()) normalized = camera.PixelToRay(pixel).head<2>();
  *normalized_guess = normalized;
  return {normalized.x(), normalized.y(), 1.0};
}

void RowDirectionsInObject(const Camera& camera, const RayFrame& frame, const SampleGrid& grid,
                           int r, std::vector<Eigen::Vector3f>* directions_in_object) {
  directions_in_object->resize(grid.cols);
  if (!camera.HasDistortion()) {
    const Eigen::Vector2d first = grid.Pixel(0, r);
    const Eigen::Vector3d start = frame.DirectionInObject(
        {(first.x() - camera.cx) / camera.fx, (first.y() - camera.cy) / camera.fy, 1.0});
    const Eigen::Vector3d increment = frame.DirectionInObject({grid.step / camera.fx, 0.0, 0.0});
    for (int c = 0; c < grid.cols; ++c) {
      (*directions_in_object)[c] = (start + c * increment).cast<float>();
    }
    return;
  }
  Eigen::Vector2d guess = camera.PixelToRay(grid.Pixel(0, r)).head<2>();
  for (int c = 0; c < grid.cols; ++c) {
    (*directions_in_object)[c] =
        frame.DirectionInObject(PixelToRayNear(camera, grid.Pixel(c, r), &guess)).cast<float>();
  }
}

namespace {

// The ray from the camera centre along `direction_in_object`; when Embree could not take it
// (IsCastableRay), *castable is false and the ray is a harmless stand-in that must not be cast.
RTCRay MakeRay(const RayFrame& frame, const Eigen::Vector3d& direction_in_object, bool* castable) {
  *castable =
      IsCastableRay(frame.cam_centre_in_object.cast<float>(), direction_in_object.cast<float>());
  if (!*castable) {
    return MakeRay(RayFrame(Eigen::Isometry3d::Identity()), Eigen::Vector3d::UnitZ(), castable);
  }
  RTCRay ray;
  ray.org_x = static_cast<float>(frame.cam_centre_in_object.x());
  ray.org_y = static_cast<float>(frame.cam_centre_in_object.y());
  ray.org_z = static_cast<float>(frame.cam_centre_in_object.z());
  ray.tnear = 0.0f;
  ray.dir_x = static_cast<float>(direction_in_object.x());
  ray.dir_y = static_cast<float>(direction_in_object.y());
  ray.dir_z = static_cast<float>(direction_in_object.z());
  ray.time = 0.0f;
  ray.tfar = std::numeric_limits<float>::infinity();
  ray.mask = ~0u;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

}  // namespace

bool Occluded(RTCScene scene, const RayFrame& frame, const Eigen::Vector3d& direction_in_cam) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  bool castable = false;
  RTCRay ray = MakeRay(frame, frame.DirectionInObject(direction_in_cam), &castable);
  if (!castable) return false;
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0.0f;
}

void Occluded8(RTCScene scene, const RayFrame& frame, const Eigen::Vector3d* directions_in_cam,
               const bool* active, bool* hits) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay8 packet;
  alignas(32) int valid[kPacketSize];  // Embree requires the valid mask 32-byte aligned
  bool cast[kPacketSize];
  for (int lane = 0; lane < kPacketSize; ++lane) {
    // Inactive lanes still get a well-defined ray: Embree may load the whole packet.
    const RTCRay ray = MakeRay(frame,
                               active[lane] ? frame.DirectionInObject(directions_in_cam[lane])
                                            : Eigen::Vector3d(0.0, 0.0, 1.0),
                               &cast[lane]);
    cast[lane] = cast[lane] && active[lane];
    valid[lane] = cast[lane] ? -1 : 0;
    packet.org_x[lane] = ray.org_x;
    packet.org_y[lane] = ray.org_y;
    packet.org_z[lane] = ray.org_z;
    packet.tnear[lane] = ray.tnear;
    packet.dir_x[lane] = ray.dir_x;
    packet.dir_y[lane] = ray.dir_y;
    packet.dir_z[lane] = ray.dir_z;
    packet.time[lane] = ray.time;
    packet.tfar[lane] = ray.tfar;
    packet.mask[lane] = ray.mask;
    packet.id[lane] = static_cast<unsigned>(lane);
    packet.flags[lane] = ray.flags;
  }
  rtcOccluded8(valid, scene, &context, &packet);
  for (int lane = 0; lane < kPacketSize; ++lane) {
    if (active[lane]) hits[lane] = cast[lane] && packet.tfar[lane] < 0.0f;
  }
}

std::optional<SingleHit> Intersect(RTCScene scene, const RayFrame& frame,
                                   const Eigen::Vector3d& direction_in_cam) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const Eigen::Vector3d direction_in_object = frame.DirectionInObject(direction_in_cam);
  RTCRayHit ray_hit;
  bool castable = false;
  ray_hit.ray = MakeRay(frame, direction_in_object, &castable);
  if (!castable) return std::nullopt;
  ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  ray_hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context, &ray_hit);
  if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  SingleHit hit;
  hit.t = ray_hit.ray.tfar;
  hit.triangle_id = static_cast<int>(ray_hit.hit.primID);
  // Origin and direction in double: the point then lies exactly on the pixel's ray, so it
  // reprojects onto the pixel whatever the float error of t.
  hit.point_in_object = frame.cam_centre_in_object + hit.t * direction_in_object;
  return hit;
}

}  // namespace render_internal

// ---------------------------------------------------------------------------------------------
// RayCaster
// ---------------------------------------------------------------------------------------------

using render_internal::LaneHit;
using render_internal::RayFrame;
using render_internal::SampleGrid;

RayCaster::RayCaster(const Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

const Mesh& RayCaster::mesh() const { return impl_->mesh; }

cv::Rect RayCaster::ProjectedBoundingBox(const Camera& camera,
                                         const Eigen::Isometry3d& cam_from_object,
                                         int margin_px) const {
  const cv::Rect image(0, 0, std::max(camera.width, 0), std::max(camera.height, 0));
  const Mesh& mesh = impl_->mesh;
  if (mesh.triangles().empty() || image.empty()) return {};

  const Eigen::Vector3d& lo = mesh.bbox_min();
  const Eigen::Vector3d& hi = mesh.bbox_max();
  std::array<Eigen::Vector3d, 8> corners_in_cam;
  int in_front = 0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                                 (i & 4) ? hi.z() : lo.z());
    corners_in_cam[i] = cam_from_object * corner;
    if (corners_in_cam[i].z() > kMinDepthMm) ++in_front;
  }
  if (in_front == 0) return {};
  // The box straddles the camera plane: its projection is unbounded, so every pixel may see
  // the object.
  if (in_front < 8) return image;

  // Without distortion the projection of the box is the convex hull of its projected corners.
  // With distortion, box edges map to curves, so edges are sampled; where the distortion
  // polynomial folds (Jacobian determinant <= 0, far outside any real lens' field of view)
  // the projection is unreliable and the whole image is returned.
  const int samples_per_edge = camera.HasDistortion() ? 16 : 1;
  double u_min = std::numeric_limits<double>::infinity();
  double v_min = u_min;
  double u_max = -u_min;
  double v_max = -u_min;
  for (int a = 0; a < 8; ++a) {
    for (int axis = 0; axis < 3; ++axis) {
      const int b = a | (1 << axis);
      if (b == a) continue;
      for (int k = 0; k <= samples_per_edge; ++k) {
        const double s = static_cast<double>(k) / samples_per_edge;
        const Eigen::Vector3d p_in_cam = (1.0 - s) * corners_in_cam[a] + s * corners_in_cam[b];
        if (camera.HasDistortion()) {
          Eigen::Matrix2d jacobian;
          camera.Distort(p_in_cam.head<2>() / p_in_cam.z(), &jacobian);
          if (!(jacobian.determinant() > 0.0)) return image;
        }
        const Eigen::Vector2d pixel = camera.Project(p_in_cam);
        if (!pixel.allFinite()) return image;
        u_min = std::min(u_min, pixel.x());
        u_max = std::max(u_max, pixel.x());
        v_min = std::min(v_min, pixel.y());
        v_max = std::max(v_max, pixel.y());
      }
    }
  }
  // Pixel centres are integers: position u lies in pixel round(u). Clamp before converting so
  // that far-away projections cannot overflow int.
  const double limit = 4.0 * std::max(image.width, image.height) + 4.0 * std::abs(margin_px);
  auto to_int = [limit](double x) { return static_cast<int>(std::clamp(x, -limit, limit)); };
  const int x0 = to_int(std::floor(u_min + 0.5) - margin_px);
  const int y0 = to_int(std::floor(v_min + 0.5) - margin_px);
  const int x1 = to_int(std::floor(u_max + 0.5) + margin_px);
  const int y1 = to_int(std::floor(v_max + 0.5) + margin_px);
  if (x1 < x0 || y1 < y0) return {};
  return cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1) & image;
}

RenderedView RayCaster::Render(const Camera& camera, const Eigen::Isometry3d& cam_from_object,
                               const RenderOptions& options) const {
  RenderedView view;
  Render(camera, cam_from_object, options, &view);
  return view;
}

void RayCaster::Render(const Camera& camera, const Eigen::Isometry3d& cam_from_object,
                       const RenderOptions& options, RenderedView* view) const {
  BCOT_CHECK(options.Validate().ok());
  BCOT_CHECK(view != nullptr);
  view->samples_per_axis = options.samples_per_axis;
  view->point_stride_px = options.point_stride_px;
  view->roi = options.roi.area() > 0
                  ? options.roi
                  : ProjectedBoundingBox(camera, cam_from_object, options.margin_px);
  const int n = options.samples_per_axis;
  const int cols = view->roi.width * n;
  const int rows = view->roi.height * n;
  // create() keeps the buffers when the size is unchanged; setTo then only rewrites them.
  // Images left out are released (0×0).
  auto prepare = [rows, cols](bool wanted, auto* image, const cv::Scalar& empty) {
    if (!wanted) {
      image->release();
      return;
    }
    image->create(rows, cols);
    if (rows > 0 && cols > 0) image->setTo(empty);
  };
  prepare(true, &view->mask, cv::Scalar::all(0));
  prepare(options.depth, &view->depth, cv::Scalar::all(0));
  prepare(options.normal_in_cam, &view->normal_in_cam, cv::Scalar::all(0));
  prepare(options.point_in_object, &view->point_in_object, cv::Scalar::all(0));
  prepare(options.triangle_id, &view->triangle_id, cv::Scalar::all(-1));
  if (cols == 0 || rows == 0) return;
  const bool geometry =
      options.depth || options.normal_in_cam || options.point_in_object || options.triangle_id;
  const int stride = options.point_stride_px;

  SampleGrid grid;
  grid.step = 1.0 / n;
  grid.u0 = view->roi.x + 0.5 * grid.step - 0.5;
  grid.v0 = view->roi.y + 0.5 * grid.step - 0.5;
  grid.cols = cols;
  grid.rows = rows;
  const RayFrame frame(cam_from_object);
  const Eigen::Matrix3f cam_from_object_rotation = frame.cam_from_object_rotation.cast<float>();
  const Eigen::Vector3f origin = frame.cam_centre_in_object.cast<float>();
  // Row and column of the view image a sample of the traced grid lands on.
  int col_offset = 0;
  int row_offset = 0;
  int grid_step = 1;
  if (!geometry || stride > 1) {
    // The mask everywhere from occlusion rays (unless the caller takes it from the contour).
    if (options.mask_everywhere) {
      render_internal::TraceGrid(impl_->scene, frame, camera, grid, /*occlusion_only=*/true,
                                 [&](const LaneHit& hit) { view->mask(hit.row, hit.col) = 255; });
    }
    if (!geometry) return;
    // Then closest-hit rays on the pixels whose image coordinates are multiples of the stride;
    // their mask is the closest-hit result, so a set mask always comes with its geometry.
    auto first_multiple = [stride](int value) {
      return value >= 0 ? (value + stride - 1) / stride * stride : -(-value / stride * stride);
    };
    const int x0 = first_multiple(view->roi.x);
    const int y0 = first_multiple(view->roi.y);
    col_offset = x0 - view->roi.x;
    row_offset = y0 - view->roi.y;
    grid_step = stride;
    grid.u0 = x0;
    grid.v0 = y0;
    grid.step = stride;
    grid.cols = col_offset < cols ? (cols - 1 - col_offset) / stride + 1 : 0;
    grid.rows = row_offset < rows ? (rows - 1 - row_offset) / stride + 1 : 0;
    for (int r = 0; r < grid.rows; ++r) {
      uchar* mask_row = view->mask.ptr(row_offset + r * stride);
      for (int c = 0; c < grid.cols; ++c) mask_row[col_offset + c * stride] = 0;
    }
  }
  render_internal::TraceGrid(
      impl_->scene, frame, camera, grid, /*occlusion_only=*/false, [&](const LaneHit& lane_hit) {
        LaneHit hit = lane_hit;
        hit.row = row_offset + lane_hit.row * grid_step;
        hit.col = col_offset + lane_hit.col * grid_step;
        view->mask(hit.row, hit.col) = 255;
        const Eigen::Vector3f& direction = *hit.direction_in_object;
        // t is the camera depth because the direction's camera z is 1.
        if (options.depth) view->depth(hit.row, hit.col) = hit.t;
        if (options.normal_in_cam) {
          Eigen::Vector3f normal = hit.ng_in_object;
          // Face the camera: against the ray direction.
          if (normal.dot(direction) > 0.0f) normal = -normal;
          Eigen::Vector3f normal_in_cam = cam_from_object_rotation * normal;
          const float length = normal_in_cam.norm();
          if (length > 0.0f) normal_in_cam /= length;
          view->normal_in_cam(hit.row, hit.col) =
              cv::Vec3f(normal_in_cam.x(), normal_in_cam.y(), normal_in_cam.z());
        }
        if (options.point_in_object) {
          const Eigen::Vector3f point_in_object = origin + hit.t * direction;
          view->point_in_object(hit.row, hit.col) =
              cv::Vec3f(point_in_object.x(), point_in_object.y(), point_in_object.z());
        }
        if (options.triangle_id) {
          view->triangle_id(hit.row, hit.col) = static_cast<int>(hit.triangle_id);
        }
      });
}

std::optional<Eigen::Vector3d> RayCaster::Intersect(const Camera& camera,
                                                    const Eigen::Isometry3d& cam_from_object,
                                                    const Eigen::Vector2d& pixel,
                                                    int* triangle) const {
  const auto hit =
      render_internal::Intersect(impl_->scene, RayFrame(cam_from_object), camera.PixelToRay(pixel));
  if (!hit) return std::nullopt;
  if (triangle != nullptr) *triangle = hit->triangle_id;
  return hit->point_in_object;
}

}  // namespace bcot

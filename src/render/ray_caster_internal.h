// Internals shared by ray_caster.cc and contour.cc: the Embree scene (RayCaster::Impl), camera
// rays expressed in the object frame, and packet tracing over regular sample grids.
#pragma once

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <optional>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

// Owns the Embree device and the committed scene of one mesh, built in the object frame O_t.
// Only const queries after construction: rtcIntersect*/rtcOccluded* on a committed scene are
// thread-safe.
struct RayCaster::Impl {
  explicit Impl(const Mesh& mesh);
  ~Impl();
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  Mesh mesh;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

namespace render_internal {

// The camera's rays in the object frame. A camera-frame direction (x, y, 1) maps to
// object_from_cam_rotation · (x, y, 1) from cam_centre_in_object; because the direction is not
// normalised and its camera z is 1, the hit distance t is the camera-frame depth z.
struct RayFrame {
  explicit RayFrame(const Eigen::Isometry3d& cam_from_object);
  Eigen::Vector3d DirectionInObject(const Eigen::Vector3d& direction_in_cam) const {
    return object_from_cam_rotation * direction_in_cam;
  }

  Eigen::Matrix3d object_from_cam_rotation;
  Eigen::Matrix3d cam_from_object_rotation;
  Eigen::Vector3d cam_centre_in_object;
};

// Embree requires every ray component to be finite and within ±1.844e18 (FLT_LARGE) and asserts
// (aborting the process) otherwise. Such rays come only from absurd inputs (an object 1e20 mm
// away, a focal length of 1e-300 px); they are not cast and count as a miss. The bound below
// keeps a wide margin to FLT_LARGE.
inline bool IsCastableRay(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
  constexpr float kMaxComponent = 1e15f;
  return origin.allFinite() && direction.allFinite() &&
         origin.cwiseAbs().maxCoeff() < kMaxComponent &&
         direction.cwiseAbs().maxCoeff() < kMaxComponent && direction.squaredNorm() > 0.0f;
}

// A regular grid of image positions: sample (c, r) sits at (u0 + c·step, v0 + r·step).
struct SampleGrid {
  double u0 = 0.0;
  double v0 = 0.0;
  double step = 1.0;
  int cols = 0;
  int rows = 0;
  Eigen::Vector2d Pixel(int c, int r) const { return {u0 + c * step, v0 + r * step}; }
};

// Camera::PixelToRay (direction (x, y, 1) in the camera frame), but with distortion the Newton
// iteration starts from `normalized_guess`, the solution for a nearby pixel, and converges in
// two or three steps instead of Camera::PixelToRay's cold start; the guess is updated to the
// solution. Falls back to Camera::PixelToRay if the warm start does not converge.
Eigen::Vector3d PixelToRayNear(const Camera& camera, const Eigen::Vector2d& pixel,
                               Eigen::Vector2d* normalized_guess);

// Object-frame ray directions object_from_cam_rotation · (x, y, 1) of row `r` of `grid`, in
// float as Embree takes them, honouring lens distortion (each sample warm-started from its
// left neighbour). Without distortion the direction is affine along the row.
void RowDirectionsInObject(const Camera& camera, const RayFrame& frame, const SampleGrid& grid,
                           int r, std::vector<Eigen::Vector3f>* directions_in_object);

// One single-ray result.
struct SingleHit {
  double t = 0.0;  // camera-frame depth of the hit
  int triangle_id = -1;
  Eigen::Vector3d point_in_object = Eigen::Vector3d::Zero();
};

// Occlusion (any hit) and closest-hit queries for the camera ray with camera-frame direction
// `direction_in_cam` = (x, y, 1).
bool Occluded(RTCScene scene, const RayFrame& frame, const Eigen::Vector3d& direction_in_cam);
// Occluded for up to kPacketSize rays at once (one rtcOccluded8): lane i is traced when
// active[i], and hits[i] is then what Occluded(directions_in_cam[i]) returns (the same float
// ray); inactive lanes are left unchanged.
constexpr int kPacketSize = 8;
void Occluded8(RTCScene scene, const RayFrame& frame, const Eigen::Vector3d* directions_in_cam,
               const bool* active, bool* hits);
std::optional<SingleHit> Intersect(RTCScene scene, const RayFrame& frame,
                                   const Eigen::Vector3d& direction_in_cam);

// What TraceGrid reports per hit sample: the packet's result for one lane.
struct LaneHit {
  int col = 0;
  int row = 0;
  float t = 0.0f;  // camera depth (intersection mode only)
  Eigen::Vector3f ng_in_object =
      Eigen::Vector3f::Zero();   // unnormalised geometric normal (intersection mode only)
  unsigned int triangle_id = 0;  // (intersection mode only)
  const Eigen::Vector3f* direction_in_object = nullptr;
};

// Casts one ray per grid sample with rtcIntersect8 (or rtcOccluded8 when `occlusion_only`) on
// 4×2 tiles (the fastest packet shape measured, LIBRARIES.md), pairs of rows in parallel
// (TBB), and calls on_hit(const LaneHit&) for every hit. on_hit runs concurrently for different
// row pairs, so it must only write memory owned by its sample.
template <typename OnHit>
void TraceGrid(RTCScene scene, const RayFrame& frame, const Camera& camera, const SampleGrid& grid,
               bool occlusion_only, const OnHit& on_hit) {
  if (grid.cols <= 0 || grid.rows <= 0) return;
  const Eigen::Vector3f origin = frame.cam_centre_in_object.cast<float>();
  const int row_pairs = (grid.rows + 1) / 2;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, row_pairs), [&](const tbb::blocked_range<int>& pairs) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        std::vector<Eigen::Vector3f> directions[2];
        for (int pair = pairs.begin(); pair != pairs.end(); ++pair) {
          const int row0 = 2 * pair;
          for (int j = 0; j < 2; ++j) {
            if (row0 + j < grid.rows) {
              RowDirectionsInObject(camera, frame, grid, row0 + j, &directions[j]);
            }
          }
          for (int col0 = 0; col0 < grid.cols; col0 += 4) {
            RTCRayHit8 packet;
            alignas(32) int valid[8];  // Embree requires the valid mask 32-byte aligned
            for (int lane = 0; lane < 8; ++lane) {
              const int col = col0 + (lane & 3);
              const int row = row0 + (lane >> 2);
              const bool inside = col < grid.cols && row < grid.rows &&
                                  IsCastableRay(origin, directions[lane >> 2][col]);
              valid[lane] = inside ? -1 : 0;
              // Invalid lanes still get a well-defined ray: Embree may load the whole packet.
              const Eigen::Vector3f direction =
                  inside ? directions[lane >> 2][col] : Eigen::Vector3f(0.0f, 0.0f, 1.0f);
              const Eigen::Vector3f lane_origin = inside ? origin : Eigen::Vector3f::Zero();
              RTCRay8& ray = packet.ray;
              ray.org_x[lane] = lane_origin.x();
              ray.org_y[lane] = lane_origin.y();
              ray.org_z[lane] = lane_origin.z();
              ray.tnear[lane] = 0.0f;
              ray.dir_x[lane] = direction.x();
              ray.dir_y[lane] = direction.y();
              ray.dir_z[lane] = direction.z();
              ray.time[lane] = 0.0f;
              ray.tfar[lane] = std::numeric_limits<float>::infinity();
              ray.mask[lane] = ~0u;
              ray.id[lane] = static_cast<unsigned>(lane);
              ray.flags[lane] = 0;
              packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
              packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
            }
            if (occlusion_only) {
              rtcOccluded8(valid, scene, &context, &packet.ray);
            } else {
              rtcIntersect8(valid, scene, &context, &packet);
            }
            for (int lane = 0; lane < 8; ++lane) {
              if (valid[lane] == 0) continue;
              // rtcOccluded sets tfar to −inf on a hit; rtcIntersect fills geomID.
              const bool hit = occlusion_only ? packet.ray.tfar[lane] < 0.0f
                                              : packet.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID;
              if (!hit) continue;
              LaneHit lane_hit;
              lane_hit.col = col0 + (lane & 3);
              lane_hit.row = row0 + (lane >> 2);
              lane_hit.direction_in_object = &directions[lane >> 2][lane_hit.col];
              if (!occlusion_only) {
                lane_hit.t = packet.ray.tfar[lane];
                lane_hit.ng_in_object = Eigen::Vector3f(
                    packet.hit.Ng_x[lane], packet.hit.Ng_y[lane], packet.hit.Ng_z[lane]);
                lane_hit.triangle_id = packet.hit.primID[lane];
              }
              on_hit(lane_hit);
            }
          }
        }
      });
}

}  // namespace render_internal
}  // namespace bcot

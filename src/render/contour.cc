// RayCaster::ExtractContour: silhouette contours with sub-pixel boundary positions and exact
// model points (method in ray_caster.h and LIBRARIES.md, "Embree 3.13").
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "bcot/core/violations.h"
#include "bcot/render/ray_caster.h"
#include "ray_caster_internal.h"

namespace bcot {

Status ContourOptions::Validate() const {
  std::vector<std::string> violations;
  if (coarse_step_px < 1) {
    violations.push_back(fmt::format("coarse_step_px = {}, must be >= 1", coarse_step_px));
  }
  if (!(sample_spacing_px > 0.0) || !std::isfinite(sample_spacing_px)) {
    violations.push_back(
        fmt::format("sample_spacing_px = {}, must be finite and > 0", sample_spacing_px));
  }
  if (!(precision_px >= 1e-6 && precision_px <= 0.5)) {
    violations.push_back(fmt::format("precision_px = {}, must be in [1e-6, 0.5]", precision_px));
  }
  if (margin_px < 0) {
    violations.push_back(fmt::format("margin_px = {}, must be >= 0", margin_px));
  }
  return internal::JoinViolations("contour", violations);
}

namespace {

using render_internal::RayFrame;

// A closed polyline parametrised by arc length (wrapping around).
class ClosedPolyline {
 public:
  explicit ClosedPolyline(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {
    cumulative_.resize(points_.size() + 1, 0.0);
    for (size_t i = 0; i < points_.size(); ++i) {
      cumulative_[i + 1] = cumulative_[i] + (Next(i) - points_[i]).norm();
    }
  }

  double length() const { return cumulative_.back(); }

  Eigen::Vector2d At(double arc) const {
    arc = std::fmod(arc, length());
    if (arc < 0.0) arc += length();
    // Segment i spans [cumulative_[i], cumulative_[i + 1]).
    const size_t i = std::min<size_t>(
        std::upper_bound(cumulative_.begin(), cumulative_.end(), arc) - cumulative_.begin() - 1,
        points_.size() - 1);
    const double segment = cumulative_[i + 1] - cumulative_[i];
    const double s = segment > 0.0 ? (arc - cumulative_[i]) / segment : 0.0;
    return (1.0 - s) * points_[i] + s * Next(i);
  }

  // Shoelace area; its sign gives the traversal direction in any axis convention.
  double SignedArea() const {
    double twice_area = 0.0;
    for (size_t i = 0; i < points_.size(); ++i) {
      const Eigen::Vector2d& a = points_[i];
      const Eigen::Vector2d& b = Next(i);
      twice_area += a.x() * b.y() - b.x() * a.y();
    }
    return 0.5 * twice_area;
  }

 private:
  const Eigen::Vector2d& Next(size_t i) const { return points_[(i + 1) % points_.size()]; }

  std::vector<Eigen::Vector2d> points_;
  std::vector<double> cumulative_;
};

// A point on a traced (coarse) contour and a guess of the outward normal there.
struct Seed {
  Eigen::Vector2d pixel;
  Eigen::Vector2d normal;
  int contour = 0;  // index into the findContours output
  double spacing = 1.0;
};

struct Refined {
  bool valid = false;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();  // from the hit end towards the miss end
  Eigen::Vector3d point_in_object = Eigen::Vector3d::Zero();
};

// Refines up to kPacketSize seeds in lock-step, one rtcOccluded8 per step: every lane casts
// exactly the rays a seed-by-seed refinement would (same order, same float rays), so the
// result does not depend on the batching; the packet only shares the traversal.
//
// Per seed: the true boundary lies between a traced (inside) grid sample and an outside
// neighbour, so within about √2 grid steps; oblique normals stretch that, hence 2 steps + 1 px
// of reach. Steps of at most 1 px keep the bracket on the first transition, not one across a
// gap. The guessed orientation is walked first; the opposite one rescues degenerate
// (zero-area) traced contours whose orientation is arbitrary. From a hit the walk goes outwards
// to the first miss, from a miss inwards to the first hit; then bisection to precision_px and
// one closest-hit ray at the inside end for the model point.
void RefineSeeds(RTCScene scene, const RayFrame& frame, const Camera& camera, const Seed* seeds,
                 int count, const ContourOptions& options, Refined* refined) {
  using render_internal::kPacketSize;
  BCOT_CHECK(count >= 1 && count <= kPacketSize);
  const double step = std::min(1.0, 0.5 * options.coarse_step_px);
  const int max_steps = static_cast<int>(std::ceil((2.0 * options.coarse_step_px + 1.0) / step));
  enum class Phase { kStart, kWalk, kBisect, kDone };
  struct Lane {
    Phase phase = Phase::kDone;
    Eigen::Vector2d normalized_guess;  // warm start of the undistortion, as in PixelToRayNear
    bool start_hits = false;
    double sign = 1.0;  // walked orientation: +1 the guessed normal, then −1
    int k = 1;          // walk step
    Eigen::Vector2d previous, inside, outside, normal, query;
    int iteration = 0;
  };
  std::array<Lane, kPacketSize> lanes;
  for (int i = 0; i < count; ++i) {
    lanes[i].phase = Phase::kStart;
    // Every ray of a seed is within a few pixels of the first: warm-start the undistortion.
    lanes[i].normalized_guess = camera.PixelToRay(seeds[i].pixel).head<2>();
    refined[i] = Refined();
  }
  // The next query of a lane, or kDone once its bisection has converged.
  auto bisection_done = [&](const Lane& lane) {
    return !(lane.iteration < 60 && (lane.outside - lane.inside).norm() > options.precision_px);
  };
  std::array<Eigen::Vector3d, kPacketSize> directions;
  bool active[kPacketSize];
  bool hits[kPacketSize];
  for (;;) {
    bool any = false;
    for (int i = 0; i < kPacketSize; ++i) {
      Lane& lane = lanes[i];
      active[i] = false;
      if (lane.phase == Phase::kDone) continue;
      const Seed& seed = seeds[i];
      if (lane.phase == Phase::kStart) {
        lane.query = seed.pixel;
      } else if (lane.phase == Phase::kWalk) {
        const Eigen::Vector2d outward = lane.sign * seed.normal;
        const Eigen::Vector2d walk = lane.start_hits ? outward : Eigen::Vector2d(-outward);
        lane.query = seed.pixel + (lane.k * step) * walk;
      } else {
        if (bisection_done(lane)) {
          // Each halving costs one occlusion ray; 60 iterations cannot be reached with a valid
          // precision_px, the bound only guards against float rays that stop changing.
          lane.phase = Phase::kDone;
          const auto hit = render_internal::Intersect(
              scene, frame,
              render_internal::PixelToRayNear(camera, lane.inside, &lane.normalized_guess));
          const Eigen::Vector2d pixel = 0.5 * (lane.inside + lane.outside);
          if (!hit || !camera.InImage(pixel)) continue;
          refined[i].pixel = pixel;
          refined[i].normal = lane.normal;
          refined[i].point_in_object = hit->point_in_object;
          refined[i].valid = true;
          continue;
        }
        lane.query = 0.5 * (lane.inside + lane.outside);
      }
      directions[i] = render_internal::PixelToRayNear(camera, lane.query, &lane.normalized_guess);
      active[i] = true;
      any = true;
    }
    if (!any) return;
    render_internal::Occluded8(scene, frame, directions.data(), active, hits);
    for (int i = 0; i < kPacketSize; ++i) {
      if (!active[i]) continue;
      Lane& lane = lanes[i];
      const Seed& seed = seeds[i];
      if (lane.phase == Phase::kStart) {
        lane.start_hits = hits[i];
        lane.phase = Phase::kWalk;
        lane.sign = 1.0;
        lane.k = 1;
        lane.previous = seed.pixel;
      } else if (lane.phase == Phase::kWalk) {
        if (hits[i] != lane.start_hits) {
          lane.inside = lane.start_hits ? lane.previous : lane.query;
          lane.outside = lane.start_hits ? lane.query : lane.previous;
          lane.normal = lane.sign * seed.normal;
          lane.phase = Phase::kBisect;
          lane.iteration = 0;
        } else {
          lane.previous = lane.query;
          if (++lane.k > max_steps) {
            if (lane.sign > 0.0) {
              lane.sign = -1.0;
              lane.k = 1;
              lane.previous = seed.pixel;
            } else {
              lane.phase = Phase::kDone;  // no bracket
            }
          }
        }
      } else {
        (hits[i] ? lane.inside : lane.outside) = lane.query;
        ++lane.iteration;
      }
    }
  }
}

// Replaces the bracket direction (from the coarse, staircase polyline: several degrees off) by
// the normal of the chord between the refined neighbours, when both exist, are about one
// spacing away and agree with the bracket direction within 60°.
void RefineNormals(std::vector<Refined>* samples, double spacing) {
  const size_t n = samples->size();
  if (n < 3) return;
  std::vector<Eigen::Vector2d> normals(n);
  for (size_t i = 0; i < n; ++i) {
    const Refined& sample = (*samples)[i];
    normals[i] = sample.normal;
    if (!sample.valid) continue;
    const Refined& previous = (*samples)[(i + n - 1) % n];
    const Refined& next = (*samples)[(i + 1) % n];
    if (!previous.valid || !next.valid) continue;
    const Eigen::Vector2d chord = next.pixel - previous.pixel;
    const double length = chord.norm();
    if (length < 0.5 * spacing || length > 4.0 * spacing) continue;
    Eigen::Vector2d normal(chord.y() / length, -chord.x() / length);
    if (normal.dot(sample.normal) < 0.0) normal = -normal;
    if (normal.dot(sample.normal) > 0.5) normals[i] = normal;
  }
  for (size_t i = 0; i < n; ++i) (*samples)[i].normal = normals[i];
}

}  // namespace

std::vector<ContourPoint> RayCaster::ExtractContour(const Camera& camera,
                                                    const Eigen::Isometry3d& cam_from_object,
                                                    const ContourOptions& options,
                                                    const RenderedView* rendered) const {
  BCOT_CHECK(options.Validate().ok());
  const cv::Rect roi = ProjectedBoundingBox(camera, cam_from_object, options.margin_px);
  if (roi.empty()) return {};
  const RayFrame frame(cam_from_object);
  const int grid_step = options.coarse_step_px;

  // Coarse mask with a one-cell empty border, so that every traced contour is closed even
  // where the object leaves the (clipped) region.
  render_internal::SampleGrid grid;
  grid.u0 = roi.x;
  grid.v0 = roi.y;
  grid.step = grid_step;
  grid.cols = (roi.width - 1) / grid_step + 1;
  grid.rows = (roi.height - 1) / grid_step + 1;
  cv::Mat1b coarse = cv::Mat1b::zeros(grid.rows + 2, grid.cols + 2);
  if (rendered != nullptr) {
    BCOT_CHECK(rendered->samples_per_axis == 1 && rendered->roi == roi &&
               rendered->mask.rows == roi.height && rendered->mask.cols == roi.width);
    for (int r = 0; r < grid.rows; ++r) {
      for (int c = 0; c < grid.cols; ++c) {
        coarse(r + 1, c + 1) = rendered->mask(r * grid_step, c * grid_step) != 0 ? 1 : 0;
      }
    }
  } else {
    render_internal::TraceGrid(
        impl_->scene, frame, camera, grid, /*occlusion_only=*/true,
        [&](const render_internal::LaneHit& hit) { coarse(hit.row + 1, hit.col + 1) = 1; });
  }

  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(coarse, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);

  std::vector<Seed> seeds;
  for (size_t c = 0; c < contours.size(); ++c) {
    // A single grid sample is a part thinner than the grid: no direction to refine along.
    if (contours[c].size() < 2) continue;
    std::vector<Eigen::Vector2d> points;
    points.reserve(contours[c].size());
    for (const cv::Point& p : contours[c]) {
      points.emplace_back(roi.x + (p.x - 1) * grid_step, roi.y + (p.y - 1) * grid_step);
    }
    const ClosedPolyline polyline(std::move(points));
    const double length = polyline.length();
    if (!(length > 0.0)) continue;
    // RETR_CCOMP puts holes on the second level (they have a parent). Outward from the
    // silhouette is away from the enclosed area for outer contours and into it for holes.
    const bool is_hole = hierarchy[c][3] >= 0;
    const double orientation = (polyline.SignedArea() >= 0.0 ? 1.0 : -1.0) * (is_hole ? -1 : 1);
    const int count =
        std::max(1, static_cast<int>(std::ceil(length / options.sample_spacing_px - 1e-9)));
    const double spacing = length / count;
    // Tangent from a chord over ±2 grid steps smooths the staircase of the traced polyline.
    const double half_window = std::min(2.0 * grid_step, 0.25 * length);
    for (int k = 0; k < count; ++k) {
      const double arc = k * spacing;
      Eigen::Vector2d tangent = polyline.At(arc + half_window) - polyline.At(arc - half_window);
      if (tangent.squaredNorm() < 1e-12) {
        // Turning point of a degenerate (back-and-forth) contour.
        tangent = polyline.At(arc + 0.5 * grid_step) - polyline.At(arc);
      }
      if (tangent.squaredNorm() < 1e-12) continue;
      tangent.normalize();
      Seed seed;
      seed.pixel = polyline.At(arc);
      seed.normal = orientation * Eigen::Vector2d(tangent.y(), -tangent.x());
      seed.contour = static_cast<int>(c);
      seed.spacing = spacing;
      seeds.push_back(seed);
    }
  }

  // Packets of consecutive seeds: neighbours along a contour, so their rays are coherent.
  std::vector<Refined> refined(seeds.size());
  const size_t packet = render_internal::kPacketSize;
  const size_t num_packets = (seeds.size() + packet - 1) / packet;
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, num_packets, 2), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t p = range.begin(); p != range.end(); ++p) {
          const size_t first = p * packet;
          const int count = static_cast<int>(std::min(packet, seeds.size() - first));
          RefineSeeds(impl_->scene, frame, camera, &seeds[first], count, options, &refined[first]);
        }
      });

  std::vector<ContourPoint> contour_points;
  contour_points.reserve(seeds.size());
  int next_contour_id = 0;
  for (size_t begin = 0; begin < seeds.size();) {
    size_t end = begin;
    while (end < seeds.size() && seeds[end].contour == seeds[begin].contour) ++end;
    std::vector<Refined> samples(refined.begin() + begin, refined.begin() + end);
    RefineNormals(&samples, seeds[begin].spacing);
    const bool is_hole = hierarchy[seeds[begin].contour][3] >= 0;
    bool any = false;
    for (const Refined& sample : samples) {
      if (!sample.valid) continue;
      ContourPoint point;
      point.pixel = sample.pixel;
      point.normal = sample.normal;
      point.point_in_object = sample.point_in_object;
      point.contour_id = next_contour_id;
      point.is_hole = is_hole;
      contour_points.push_back(point);
      any = true;
    }
    if (any) ++next_contour_id;
    begin = end;
  }
  return contour_points;
}

}  // namespace bcot

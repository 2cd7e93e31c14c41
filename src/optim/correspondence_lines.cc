#include "bcot/optim/correspondence_lines.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "bcot/core/violations.h"

namespace bcot {
namespace {

// Walk step (px) when measuring how far a line may extend along the rendered mask.
constexpr double kWalkStepPx = 0.5;
// A mask flip closer than this to the walk position may be the pixel rounding of the line's own
// contour (a pixel centre is up to 0.71 px from the point it is looked up for); the walk starts
// here and ends this far before a flip.
constexpr double kMaskMarginPx = 1.0;

struct PendingLine {
  CorrespondenceLine line;
  int first_sample = 0;  // k of the first sample: offset k·h
  int num_samples = 0;
  int first_query = 0;  // index into the bilinear query list
};

// Extent (px, >= 0) from `centre` along `direction` over which `keeps(x, y)` holds at the
// nearest pixel and the bilinear footprint stays in the image, capped at `limit`.
template <typename Keeps>
double Extent(const Camera& camera, const Eigen::Vector2d& centre, const Eigen::Vector2d& direction,
              double limit, const Keeps& keeps) {
  double reached = 0.0;
  for (double t = kMaskMarginPx; t <= limit + kMaskMarginPx; t += kWalkStepPx) {
    const Eigen::Vector2d p = centre + t * direction;
    if (!(p.x() >= 0.0 && p.y() >= 0.0 && p.x() < camera.width - 1.0 &&
          p.y() < camera.height - 1.0)) {
      return std::min(limit, t - kWalkStepPx);
    }
    const int x = static_cast<int>(std::lround(p.x()));
    const int y = static_cast<int>(std::lround(p.y()));
    if (!keeps(x, y)) return std::min(limit, std::max(0.0, t - kMaskMarginPx));
    reached = t;
  }
  return std::min(limit, reached);
}

// Extent over which `mask` keeps the value `inside`.
double MaskExtent(const cv::Mat1b& mask, const Camera& camera, const Eigen::Vector2d& centre,
                  const Eigen::Vector2d& direction, bool inside, double limit) {
  return Extent(camera, centre, direction, limit,
                [&](int x, int y) { return (mask(y, x) != 0) == inside; });
}

// How far a line through a contour point may extend (px): inward and outward.
struct LineSides {
  double inside_px = 0.0;
  double outside_px = 0.0;
};

}  // namespace

Status CorrespondenceLineOptions::Validate() const {
  std::vector<std::string> violations;
  if (num_lines < 1) violations.push_back(fmt::format("num_lines = {}, must be >= 1", num_lines));
  if (!(scale_px > 0.0) || !std::isfinite(scale_px)) {
    violations.push_back(fmt::format("scale_px = {}, must be finite and > 0", scale_px));
  }
  if (!(half_length_px > scale_px) || !std::isfinite(half_length_px)) {
    violations.push_back(
        fmt::format("half_length_px = {}, must be finite and > scale_px", half_length_px));
  }
  if (!(min_side_px >= 0.0) || !std::isfinite(min_side_px)) {
    violations.push_back(fmt::format("min_side_px = {}, must be finite and >= 0", min_side_px));
  }
  if (!(slope_px > 0.0) || !std::isfinite(slope_px)) {
    violations.push_back(fmt::format("slope_px = {}, must be finite and > 0", slope_px));
  }
  if (!(amplitude > 0.0 && amplitude < 0.5)) {
    violations.push_back(fmt::format("amplitude = {}, must be in (0, 0.5)", amplitude));
  }
  if (hypothesis_subdivisions < 1) {
    violations.push_back(
        fmt::format("hypothesis_subdivisions = {}, must be >= 1", hypothesis_subdivisions));
  }
  if (!(min_sigma_px > 0.0) || !std::isfinite(min_sigma_px)) {
    violations.push_back(fmt::format("min_sigma_px = {}, must be finite and > 0", min_sigma_px));
  }
  if (!(max_sigma_px > min_sigma_px) || !std::isfinite(max_sigma_px)) {
    violations.push_back(
        fmt::format("max_sigma_px = {}, must be finite and > min_sigma_px", max_sigma_px));
  }
  if (!(weight >= 0.0) || !std::isfinite(weight)) {
    violations.push_back(fmt::format("weight = {}, must be finite and >= 0", weight));
  }
  return internal::JoinViolations("correspondence_lines", violations);
}

namespace {

// The smoothed step h_f(m·step) = ½ − α·tanh(m·step / (2·slope)), step = h / subdivisions, for
// every integer m with |m| <= max_index: the offsets s_k − d of every (sample, hypothesis)
// pair of a line with at most max_index / subdivisions + 2 samples. Built once per view, so
// the lines share its tanh evaluations.
class SmoothedStepTable {
 public:
  SmoothedStepTable(const CorrespondenceLineOptions& options, int max_index)
      : max_index_(max_index), values_(2 * static_cast<size_t>(max_index) + 1) {
    const double step = options.scale_px / options.hypothesis_subdivisions;
    const double inverse_width = 1.0 / (2.0 * options.slope_px);
    for (int m = -max_index; m <= max_index; ++m) {
      values_[m + max_index] = 0.5 - options.amplitude * std::tanh(m * step * inverse_width);
    }
  }

  // The largest |m| a line of `num_samples` samples needs (see ContourDistributionFromTable).
  static int MaxIndex(int num_samples, const CorrespondenceLineOptions& options) {
    return std::max(0, num_samples - 2) * options.hypothesis_subdivisions;
  }

  int max_index() const { return max_index_; }
  // h_f at offset m·step; |m| <= max_index.
  double operator[](int m) const { return values_[m + max_index_]; }

 private:
  int max_index_;
  std::vector<double> values_;
};

// Products of line terms below this are folded into the log-likelihood sum (one log) and
// restarted at 1: every term is >= ½ − α > 0, so the product never underflows.
constexpr double kRenormaliseBelow = 1e-100;

bool ContourDistributionFromTable(const std::vector<double>& p_foreground, double first_offset_px,
                                  const CorrespondenceLineOptions& options,
                                  const SmoothedStepTable& smoothed_step, double* mean_px,
                                  double* sigma_px) {
  const int n = static_cast<int>(p_foreground.size());
  if (n < 3) return false;
  BCOT_CHECK(SmoothedStepTable::MaxIndex(n, options) <= smoothed_step.max_index());
  const double h = options.scale_px;
  const int subdivisions = options.hypothesis_subdivisions;
  const double step = h / subdivisions;
  // Hypotheses from the second to the second-last sample: a boundary at the very end of the
  // line would have a single sample on one side.
  const int num_hypotheses = (n - 3) * subdivisions + 1;
  const double first_hypothesis = first_offset_px + h;
  // Term k of hypothesis j: h_f·P_f + (1 − h_f)·(1 − P_f) = (1 − P_f) + h_f·(2P_f − 1), with
  // h_f at s_k − d_j = (k·S − S − j)·step (S = subdivisions). log Π_k instead of Σ_k log: one
  // log per hypothesis instead of one per sample and hypothesis.
  std::vector<double> background(n);
  std::vector<double> contrast(n);
  for (int k = 0; k < n; ++k) {
    background[k] = 1.0 - p_foreground[k];
    contrast[k] = 2.0 * p_foreground[k] - 1.0;
  }
  std::vector<double> log_likelihood(num_hypotheses, 0.0);
  for (int j = 0; j < num_hypotheses; ++j) {
    double sum = 0.0;
    double product = 1.0;
    for (int k = 0; k < n; ++k) {
      product *= background[k] + contrast[k] * smoothed_step[(k - 1) * subdivisions - j];
      if (product < kRenormaliseBelow) {
        sum += std::log(product);
        product = 1.0;
      }
    }
    log_likelihood[j] = sum + std::log(product);
  }
  const auto best = std::max_element(log_likelihood.begin(), log_likelihood.end());
  const int mode = static_cast<int>(best - log_likelihood.begin());
  const double max_log = *best;
  std::vector<double>& weights = log_likelihood;  // p(d_j) up to normalisation, in place
  double total = 0.0;
  double first_moment = 0.0;
  for (int j = 0; j < num_hypotheses; ++j) {
    weights[j] = std::exp(log_likelihood[j] - max_log);
    total += weights[j];
    first_moment += weights[j] * (first_hypothesis + j * step);
  }
  const double mean = first_moment / total;
  double variance = 0.0;
  for (int j = 0; j < num_hypotheses; ++j) {
    const double deviation = first_hypothesis + j * step - mean;
    variance += weights[j] * deviation * deviation;
  }
  *mean_px = mean;
  *sigma_px = std::sqrt(variance / total);
  return num_hypotheses >= 3 && mode != 0 && mode != num_hypotheses - 1;
}

}  // namespace

bool ContourDistribution(const std::vector<double>& p_foreground, double first_offset_px,
                         const CorrespondenceLineOptions& options, double* mean_px,
                         double* sigma_px) {
  const int n = static_cast<int>(p_foreground.size());
  const SmoothedStepTable table(options, SmoothedStepTable::MaxIndex(n, options));
  return ContourDistributionFromTable(p_foreground, first_offset_px, options, table, mean_px,
                                      sigma_px);
}

LineAnchors::LineAnchors(const RayCaster& caster, const Camera& camera,
                         const Eigen::Isometry3d& cam_from_rig,
                         const Eigen::Isometry3d& rig_from_objcentre,
                         const std::vector<ContourPoint>& contour, int num_lines)
    : camera_(camera),
      contour_(contour),
      objcentre_from_template_(caster.mesh().objcentre_from_template()),
      cam_from_objcentre_(cam_from_rig * rig_from_objcentre),
      size_(std::min(num_lines, static_cast<int>(contour.size()))) {}

size_t LineAnchors::index(int j) const {
  BCOT_CHECK(j >= 0 && j < size_);
  return static_cast<size_t>((j + 0.5) * contour_.size() / size_);
}

const ContourPoint& LineAnchors::point(int j) const { return contour_[index(j)]; }

bool LineAnchors::Anchor(int j, CorrespondenceLine* line) const {
  const ContourPoint& p = point(j);
  line->centre = p.pixel;
  line->normal = p.normal;
  line->point_in_objcentre = objcentre_from_template_ * p.point_in_object;
  const Eigen::Vector3d point_in_cam = cam_from_objcentre_ * line->point_in_objcentre;
  if (!(point_in_cam.z() > 0.0)) return false;
  line->projection0 = camera_.Project(point_in_cam);
  return true;
}

namespace {

// The lines of one view along `contour`: sides(i) gives the extents of contour sample i's line,
// at most options.half_length_px each.
template <typename Sides>
CorrespondenceLines BuildLines(const RayCaster& caster, const Camera& camera,
                               const Eigen::Isometry3d& cam_from_rig,
                               const Eigen::Isometry3d& rig_from_objcentre, const cv::Mat3b& image,
                               const ColorModel& color_model,
                               const std::vector<ContourPoint>& contour,
                               const CorrespondenceLineOptions& options, const Sides& sides) {
  CorrespondenceLines result;
  result.rig_from_objcentre = rig_from_objcentre;
  const LineAnchors anchors(caster, camera, cam_from_rig, rig_from_objcentre, contour,
                            options.num_lines);
  const double h = options.scale_px;
  // Sub-points per sample segment (bilinear posteriors averaged over the segment).
  const int sub_points = std::max(1, static_cast<int>(std::lround(h)));
  std::vector<PendingLine> pending;
  std::vector<Eigen::Vector2i> queries;
  std::vector<Eigen::Vector2d> query_points;  // the sub-points, 4 queries each
  for (int j = 0; j < anchors.size(); ++j) {
    const ContourPoint& point = anchors.point(j);
    ++result.candidates;
    if (!camera.InImage(point.pixel)) {
      ++result.rejected_off_image;
      continue;
    }
    const LineSides line_sides = sides(anchors.index(j));
    const double inside_px = line_sides.inside_px;
    const double outside_px = line_sides.outside_px;
    if (inside_px < options.min_side_px || outside_px < options.min_side_px) {
      ++result.rejected_short;
      continue;
    }
    PendingLine p;
    if (!anchors.Anchor(j, &p.line)) {
      ++result.rejected_off_image;
      continue;
    }
    p.first_sample = -static_cast<int>(std::floor((inside_px - 0.5 * h) / h));
    const int last_sample = static_cast<int>(std::floor((outside_px - 0.5 * h) / h));
    p.num_samples = last_sample - p.first_sample + 1;
    if (p.num_samples < 3) {
      ++result.rejected_short;
      continue;
    }
    p.first_query = static_cast<int>(query_points.size());
    for (int k = p.first_sample; k <= last_sample; ++k) {
      for (int m = 0; m < sub_points; ++m) {
        const double s = k * h - 0.5 * h + (m + 0.5) * h / sub_points;
        const Eigen::Vector2d q = point.pixel + s * point.normal;
        query_points.push_back(q);
        const int x0 = static_cast<int>(std::floor(q.x()));
        const int y0 = static_cast<int>(std::floor(q.y()));
        queries.emplace_back(x0, y0);
        queries.emplace_back(x0 + 1, y0);
        queries.emplace_back(x0, y0 + 1);
        queries.emplace_back(x0 + 1, y0 + 1);
      }
    }
    pending.push_back(std::move(p));
  }
  if (pending.empty()) return result;
  const std::vector<double> posteriors = color_model.ForegroundPosteriors(image, queries);
  int max_samples = 0;
  for (const PendingLine& p : pending) max_samples = std::max(max_samples, p.num_samples);
  const SmoothedStepTable smoothed_step(options, SmoothedStepTable::MaxIndex(max_samples, options));

  std::vector<double> samples;
  for (const PendingLine& p : pending) {
    samples.assign(p.num_samples, 0.0);
    for (int k = 0; k < p.num_samples; ++k) {
      double sum = 0.0;
      for (int m = 0; m < sub_points; ++m) {
        const int index = p.first_query + k * sub_points + m;
        const Eigen::Vector2d& q = query_points[index];
        const double fx = q.x() - std::floor(q.x());
        const double fy = q.y() - std::floor(q.y());
        const double* v = &posteriors[4 * static_cast<size_t>(index)];
        sum += (1.0 - fy) * ((1.0 - fx) * v[0] + fx * v[1]) + fy * ((1.0 - fx) * v[2] + fx * v[3]);
      }
      samples[k] = sum / sub_points;
    }
    CorrespondenceLine line = p.line;
    double sigma = 0.0;
    if (!ContourDistributionFromTable(samples, p.first_sample * h, options, smoothed_step,
                                      &line.mean_px, &sigma) ||
        sigma > options.max_sigma_px) {
      ++result.rejected_ambiguous;
      continue;
    }
    line.sigma_px = std::max(sigma, options.min_sigma_px);
    result.lines.push_back(line);
  }
  return result;
}

}  // namespace

StatusOr<CorrespondenceLines> BuildCorrespondenceLines(
    const RayCaster& caster, const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
    const Eigen::Isometry3d& rig_from_objcentre, const cv::Mat3b& image,
    const ColorModel& color_model, const Silhouette& silhouette,
    const CorrespondenceLineOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_RETURN_IF_ERROR(CheckSilhouetteInputs(camera, image, silhouette));
  const std::vector<ContourPoint>& contour = silhouette.contour;
  return BuildLines(caster, camera, cam_from_rig, rig_from_objcentre, image, color_model, contour,
                    options, [&](size_t i) {
                      const ContourPoint& point = contour[i];
                      return LineSides{
                          MaskExtent(silhouette.mask, camera, point.pixel, -point.normal,
                                     /*inside=*/true, options.half_length_px),
                          MaskExtent(silhouette.mask, camera, point.pixel, point.normal,
                                     /*inside=*/false, options.half_length_px)};
                    });
}

StatusOr<CorrespondenceLines> BuildCorrespondenceLines(
    const RayCaster& caster, const Camera& camera, const Eigen::Isometry3d& cam_from_rig,
    const Eigen::Isometry3d& rig_from_objcentre, const cv::Mat3b& image,
    const ColorModel& color_model, const std::vector<ProjectedContourPoint>& points,
    const CorrespondenceLineOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_RETURN_IF_ERROR(CheckViewImage(camera, image));
  std::vector<ContourPoint> contour(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    contour[i].pixel = points[i].pixel;
    contour[i].normal = points[i].normal;
    contour[i].point_in_object = points[i].point_in_object;
  }
  const auto always = [](int, int) { return true; };
  return BuildLines(caster, camera, cam_from_rig, rig_from_objcentre, image, color_model, contour,
                    options, [&](size_t i) {
                      // The model's extents end at its own mask's flip; the same margin as the
                      // rendered mask's walk (kMaskMarginPx) is kept from it.
                      const ProjectedContourPoint& point = points[i];
                      const auto side = [&](double extent_px, double sign) {
                        const double limit =
                            std::clamp(extent_px - kMaskMarginPx, 0.0, options.half_length_px);
                        return Extent(camera, point.pixel, sign * point.normal, limit, always);
                      };
                      return LineSides{side(point.inside_px, -1.0), side(point.outside_px, 1.0)};
                    });
}

}  // namespace bcot

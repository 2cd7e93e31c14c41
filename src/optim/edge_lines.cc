#include "bcot/optim/edge_lines.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "bcot/core/linear_rgb.h"
#include "bcot/core/violations.h"
#include "bcot/render/occlusion_contour.h"

namespace bcot {

Status EdgeLineOptions::Validate() const {
  std::vector<std::string> violations;
  if (num_lines < 1) violations.push_back(fmt::format("num_lines = {}, must be >= 1", num_lines));
  if (!(line_spacing_px > 0.0) || !std::isfinite(line_spacing_px)) {
    violations.push_back(
        fmt::format("line_spacing_px = {}, must be finite and > 0", line_spacing_px));
  }
  if (!(step_px > 0.0) || !std::isfinite(step_px)) {
    violations.push_back(fmt::format("step_px = {}, must be finite and > 0", step_px));
  }
  if (!(window_px >= 2.0) || !std::isfinite(window_px)) {
    violations.push_back(fmt::format("window_px = {}, must be finite and >= 2", window_px));
  }
  if (!(search_px > 0.0) || !std::isfinite(search_px)) {
    violations.push_back(fmt::format("search_px = {}, must be finite and > 0", search_px));
  }
  if (!(fit_half_px > step_px) || !std::isfinite(fit_half_px)) {
    violations.push_back(
        fmt::format("fit_half_px = {}, must be finite and > step_px", fit_half_px));
  }
  if (!(min_width_px > 0.0) || !(max_width_px > min_width_px) || !std::isfinite(max_width_px)) {
    violations.push_back(fmt::format("min_width_px = {}, max_width_px = {}: need 0 < min < max",
                                     min_width_px, max_width_px));
  }
  if (!(min_contrast >= 0.0) || !std::isfinite(min_contrast)) {
    violations.push_back(fmt::format("min_contrast = {}, must be finite and >= 0", min_contrast));
  }
  if (!(min_snr >= 0.0) || !std::isfinite(min_snr)) {
    violations.push_back(fmt::format("min_snr = {}, must be finite and >= 0", min_snr));
  }
  if (!(min_sigma_px > 0.0) || !std::isfinite(min_sigma_px)) {
    violations.push_back(fmt::format("min_sigma_px = {}, must be finite and > 0", min_sigma_px));
  }
  if (!(clip_level > 0.0) || std::isnan(clip_level)) {
    violations.push_back(fmt::format("clip_level = {}, must be > 0", clip_level));
  }
  if (!response.IsValid()) {
    violations.push_back(
        response.kind == ImageResponse::Kind::kTable
            ? std::string("response table: needs 256 finite, non-decreasing values >= 0 "
                          "(the last > 0)")
            : fmt::format("gamma = {}, must be in [{}, {}]", response.gamma,
                          ImageResponse::kMinGamma, ImageResponse::kMaxGamma));
  }
  return internal::JoinViolations("edge", violations);
}

namespace {

constexpr double kInvSqrt2 = 0.70710678118654752440;
constexpr double kInvSqrt2Pi = 0.39894228040143267794;

double NormalCdf(double z) { return 0.5 * std::erfc(-z * kInvSqrt2); }

constexpr int kParams = 6;
using Params = Eigen::Matrix<double, kParams, 1>;
using ParamsMatrix = Eigen::Matrix<double, kParams, kParams>;

// The Gauss-Newton normal equations of one evaluation: JᵀJ and Jᵀr.
struct NormalEquations {
  ParamsMatrix jtj;
  Params jtr;
};

// The samples a profile is fitted to, and the work arrays of one evaluation (sized once per
// fit, so the iterations allocate nothing). j is the m×6 Jacobian; its columns of a (ones) and
// g (u) are constant and set with the samples.
struct FitSamples {
  explicit FitSamples(int m)
      : s(m),
        u(m),
        p(m),
        z(m),
        gauss(m),
        t(m),
        tail(m),
        cdf(m),
        pdf(m),
        ramp(m),
        residual(m),
        step_slope(m),
        j(m, kParams) {}

  Eigen::ArrayXd s;  // offsets along the line (px)
  Eigen::ArrayXd u;  // s − μ0
  Eigen::ArrayXd p;  // profile values
  Eigen::ArrayXd z, gauss, t, tail, cdf, pdf, ramp, residual, step_slope;
  Eigen::Matrix<double, Eigen::Dynamic, kParams> j;
};

// Residuals of the step model with parameters x = (a, g, b, μ, w, k) and, optionally, the
// normal equations of its Jacobian: a + g·u + b·Φ(z) + k·w·R(z), u = s − μ0, z = (s − μ)/w,
// R(z) = z·Φ(z) + φ(z) (the Gaussian-blurred kink max(0, s − μ)/w: the outside trend differs
// from the inside one by k). Returns the residual sum of squares.
//
// Φ(z) and φ(z) come from one exponential: Φ(z) = ½·erfc(|z|/√2) for z <= 0, else 1 − that,
// with erfc(x) = t·(a1 + t·(a2 + t·(a3 + t·(a4 + t·a5))))·e^{−x²}, t = 1/(1 + p·x), x >= 0
// (Abramowitz & Stegun 7.1.26, |error| <= 1.5e-7, so |ΔΦ| <= 7.5e-8: far below the profile's
// noise), and e^{−x²} = e^{−z²/2} = √(2π)·φ(z). Array expressions over all samples, so the
// exponentials are vectorised.
double Residuals(const Params& x, FitSamples* f, NormalEquations* normal) {
  constexpr double kP = 0.3275911;
  constexpr double kA1 = 0.254829592, kA2 = -0.284496736, kA3 = 1.421413741;
  constexpr double kA4 = -1.453152027, kA5 = 1.061405429;
  const double inv_w = 1.0 / x[4];
  f->z = (f->s - x[3]) * inv_w;
  f->gauss = (-0.5 * f->z.square()).exp();
  f->t = (1.0 + (kP * kInvSqrt2) * f->z.abs()).inverse();
  f->tail = 0.5 * f->t * (kA1 + f->t * (kA2 + f->t * (kA3 + f->t * (kA4 + f->t * kA5)))) *
            f->gauss;  // ½·erfc(|z|/√2)
  f->cdf = (f->z <= 0.0).select(f->tail, 1.0 - f->tail);
  f->pdf = kInvSqrt2Pi * f->gauss;
  f->ramp = f->z * f->cdf + f->pdf;
  f->residual = x[0] + x[1] * f->u + x[2] * f->cdf + (x[5] * x[4]) * f->ramp - f->p;
  if (normal != nullptr) {
    f->step_slope = (x[2] * inv_w) * f->pdf;  // b·φ(z)/w
    f->j.col(2) = f->cdf.matrix();
    f->j.col(3) = (-f->step_slope - x[5] * f->cdf).matrix();
    f->j.col(4) = (-f->step_slope * f->z + x[5] * f->pdf).matrix();
    f->j.col(5) = (x[4] * f->ramp).matrix();
    normal->jtj.noalias() = f->j.transpose().lazyProduct(f->j);
    normal->jtr.noalias() = f->j.transpose().lazyProduct(f->residual.matrix());
  }
  return f->residual.square().sum();
}

}  // namespace

bool FitEdgeProfile(const std::vector<double>& values, double first_offset_px,
                    const EdgeLineOptions& options, EdgeFit* fit) {
  const int n = static_cast<int>(values.size());
  if (n < 7) return false;
  const double h = options.step_px;
  // Start: the steepest descent (the profile falls from inside to outside) within search_px.
  int best = -1;
  double steepest = 0.0;
  for (int k = 1; k + 1 < n; ++k) {
    const double s = first_offset_px + k * h;
    if (std::abs(s) > options.search_px) continue;
    const double slope = (values[k + 1] - values[k - 1]) / (2.0 * h);
    if (best < 0 || slope < steepest) {
      best = k;
      steepest = slope;
    }
  }
  if (best < 0 || !(steepest < 0.0)) return false;
  const double mu0 = first_offset_px + best * h;
  // The fit window: the samples within fit_half_px of μ0 (a contiguous run, offsets increase).
  int first = n, last = -1;
  for (int k = 0; k < n; ++k) {
    if (std::abs(first_offset_px + k * h - mu0) <= options.fit_half_px + 1e-9) {
      first = std::min(first, k);
      last = k;
    }
  }
  const int m = last - first + 1;
  if (m < 8) return false;
  FitSamples samples(m);
  for (int i = 0; i < m; ++i) samples.s[i] = first_offset_px + (first + i) * h;
  samples.u = samples.s - mu0;
  samples.p = Eigen::Map<const Eigen::ArrayXd>(values.data() + first, m);
  // The Jacobian's columns of a and g do not depend on the parameters.
  samples.j.col(0).setOnes();
  samples.j.col(1) = samples.u.matrix();

  // Initial (a, g, b) by linear least squares at μ = μ0, w = 0.7, k = 0.
  Params x;
  x << 0.0, 0.0, 0.0, mu0, 0.7, 0.0;
  {
    Eigen::MatrixXd a(m, 3);
    a.leftCols(2) = samples.j.leftCols(2);
    for (int i = 0; i < m; ++i) a(i, 2) = NormalCdf((samples.s[i] - x[3]) / x[4]);
    const Eigen::Vector3d linear = a.colPivHouseholderQr().solve(samples.p.matrix());
    x[0] = linear[0];
    x[1] = linear[1];
    x[2] = linear[2];
  }
  NormalEquations normal, normal_new;
  double rss = Residuals(x, &samples, &normal);
  double lambda = 1e-3;
  bool converged = false;
  for (int iteration = 0; iteration < 30; ++iteration) {
    ParamsMatrix damped = normal.jtj;
    damped.diagonal() += lambda * normal.jtj.diagonal().cwiseMax(1e-12);
    // λ > 0 makes the damped matrix positive definite; LDLT is the fallback for round-off.
    const Eigen::LLT<ParamsMatrix> cholesky(damped);
    const Params delta = cholesky.info() == Eigen::Success
                             ? Params(-cholesky.solve(normal.jtr))
                             : Params(-damped.ldlt().solve(normal.jtr));
    Params candidate = x + delta;
    if (!candidate.allFinite()) return false;
    candidate[4] = std::max(candidate[4], 0.05);
    // The normal equations cost little beside Φ and φ, which they share: evaluated with the
    // residuals, they are ready when the step is accepted.
    const double rss_new = Residuals(candidate, &samples, &normal_new);
    if (rss_new <= rss) {
      x = candidate;
      rss = rss_new;
      normal = normal_new;
      lambda = std::max(lambda * 0.3, 1e-9);
      if (std::abs(delta[3]) < 1e-4 && std::abs(delta[4]) < 1e-4) {
        converged = true;
        break;
      }
    } else {
      lambda *= 10.0;
      if (lambda > 1e8) {
        converged = true;  // no further decrease possible: at a minimum within precision
        break;
      }
    }
  }
  if (!converged) return false;
  Eigen::FullPivLU<ParamsMatrix> lu(normal.jtj);
  if (!lu.isInvertible()) return false;
  const double noise_variance = rss / std::max(1, m - kParams);
  const double variance = noise_variance * lu.inverse()(3, 3);
  fit->mean_px = x[3];
  fit->width_px = x[4];
  fit->step = x[2];
  fit->sigma_px = std::sqrt(std::max(0.0, variance));
  if (!std::isfinite(fit->sigma_px)) return false;
  if (std::abs(fit->mean_px) > options.search_px) return false;
  if (fit->width_px < options.min_width_px || fit->width_px > options.max_width_px) return false;
  // b < 0: the profile falls from inside (d̂ side) to outside.
  if (!(-fit->step >= options.min_snr * std::sqrt(noise_variance))) return false;
  return true;
}

bool SampleEdgeLine(const cv::Mat3b& image, const LinearTable& table, const Eigen::Vector2d& centre,
                    const Eigen::Vector2d& normal, const EdgeLineOptions& options,
                    EdgeLineSamples* samples) {
  const double h = options.step_px;
  const int half = static_cast<int>(std::floor(options.window_px / h + 1e-9));
  if (!CanSampleBilinear(image.size(), centre - half * h * normal) ||
      !CanSampleBilinear(image.size(), centre + half * h * normal)) {
    return false;
  }
  samples->colors.resize(2 * half + 1);
  Eigen::Vector3d inside = Eigen::Vector3d::Zero(), outside = Eigen::Vector3d::Zero();
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
  int inside_count = 0, outside_count = 0;
  for (int k = -half; k <= half; ++k) {
    const double s = k * h;
    Eigen::Vector3d& color = samples->colors[k + half];
    color = SampleLinearRgb(image, table, centre + s * normal);
    peak = peak.cwiseMax(PeakLinearRgb(image, table, centre + s * normal));
    if (s <= -1.0) {
      inside += color;
      ++inside_count;
    } else if (s >= 1.0) {
      outside += color;
      ++outside_count;
    }
  }
  samples->inside = inside / std::max(1, inside_count);
  samples->outside = outside / std::max(1, outside_count);
  samples->peak = peak;
  return true;
}

EdgeAcross FitEdgeAcross(const cv::Mat3b& image, const LinearTable& table,
                         const Eigen::Vector2d& centre, const Eigen::Vector2d& normal,
                         const EdgeLineOptions& options, EdgeFit* fit) {
  EdgeLineSamples samples;
  if (!SampleEdgeLine(image, table, centre, normal, options, &samples)) {
    return EdgeAcross::kOffImage;
  }
  Eigen::Vector3d d = samples.inside - samples.outside;
  // Clipped channels carry no contrast (see "clipping" in the header).
  for (int c = 0; c < 3; ++c) {
    if (samples.peak[c] >= options.clip_level) d[c] = 0.0;
  }
  if (!(d.norm() >= options.min_contrast) || d.norm() == 0.0) return EdgeAcross::kAmbiguous;
  const Eigen::Vector3d direction = d.normalized();
  const int half = static_cast<int>(samples.colors.size() / 2);
  std::vector<double> profile(samples.colors.size());
  for (size_t k = 0; k < profile.size(); ++k) profile[k] = direction.dot(samples.colors[k]);
  return FitEdgeProfile(profile, -half * options.step_px, options, fit) ? EdgeAcross::kFound
                                                                        : EdgeAcross::kAmbiguous;
}

double TracedContourLengthPx(const std::vector<ContourPoint>& contour) {
  double length_px = 0.0;
  for (size_t i = 0; i + 1 < contour.size(); ++i) {
    if (contour[i + 1].contour_id != contour[i].contour_id) continue;
    length_px += (contour[i + 1].pixel - contour[i].pixel).norm();
  }
  return length_px;
}

namespace {

// Lines along `length_px` of a non-empty contour (see EdgeLineOptions::line_spacing_px).
int NumEdgeLinesForLength(double length_px, const EdgeLineOptions& options) {
  const double lines = std::ceil(length_px / options.line_spacing_px);
  return static_cast<int>(std::clamp(lines, 1.0, static_cast<double>(options.num_lines)));
}

}  // namespace

int NumEdgeLines(const std::vector<ContourPoint>& contour, const EdgeLineOptions& options) {
  if (contour.empty()) return 0;
  return NumEdgeLinesForLength(TracedContourLengthPx(contour), options);
}

namespace {

// Where a line's window must lie on the rendered mask at T0: inside over [−window, −1] and
// outside over [1, window] across the silhouette; inside throughout across an occlusion contour,
// whose far side is the object too.
enum class WindowOnMask { kInsideThenOutside, kInsideThroughout };

bool WindowIsClean(const cv::Mat1b& mask, const ContourPoint& point, double window_px,
                   WindowOnMask rule) {
  for (double t = 1.0; t <= window_px + 1e-9; t += 0.5) {
    for (int side = -1; side <= 1; side += 2) {
      const Eigen::Vector2d q = point.pixel + side * t * point.normal;
      const bool in =
          mask(static_cast<int>(std::lround(q.y())), static_cast<int>(std::lround(q.x()))) != 0;
      if (in != (side < 0 || rule == WindowOnMask::kInsideThroughout)) return false;
    }
  }
  return true;
}

// Measures the edge across every candidate of `anchors` whose window lies on the image and on
// the mask by `rule`, appending the lines found to `result` and counting the others.
void MeasureEdgeLines(const LineAnchors& anchors, WindowOnMask rule, const cv::Mat3b& image,
                      const LinearTable& table, const cv::Mat1b& mask,
                      const EdgeLineOptions& options, CorrespondenceLines* result) {
  const double h = options.step_px;
  const int half = static_cast<int>(std::floor(options.window_px / h + 1e-9));
  for (int j = 0; j < anchors.size(); ++j) {
    const ContourPoint& point = anchors.point(j);
    ++result->candidates;
    const Eigen::Vector2d first = point.pixel - half * h * point.normal;
    const Eigen::Vector2d last = point.pixel + half * h * point.normal;
    if (!CanSampleBilinear(image.size(), first) || !CanSampleBilinear(image.size(), last)) {
      ++result->rejected_off_image;
      continue;
    }
    if (!WindowIsClean(mask, point, options.window_px, rule)) {
      ++result->rejected_short;
      continue;
    }
    CorrespondenceLine line;
    if (!anchors.Anchor(j, &line)) {
      ++result->rejected_off_image;
      continue;
    }
    EdgeFit fit;
    if (FitEdgeAcross(image, table, point.pixel, point.normal, options, &fit) !=
        EdgeAcross::kFound) {
      ++result->rejected_ambiguous;  // off-image windows were rejected above
      continue;
    }
    line.mean_px = fit.mean_px;
    line.sigma_px = std::max(fit.sigma_px, options.min_sigma_px);
    result->lines.push_back(line);
  }
}

}  // namespace

StatusOr<CorrespondenceLines> BuildEdgeLines(const RayCaster& caster, const Camera& camera,
                                             const Eigen::Isometry3d& cam_from_rig,
                                             const Eigen::Isometry3d& rig_from_objcentre,
                                             const cv::Mat3b& image, const Silhouette& silhouette,
                                             const EdgeLineOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  if (!options.response.IsResolved()) {
    return Status::InvalidConfig("edge lines: the image response must be known (not auto)");
  }
  BCOT_RETURN_IF_ERROR(CheckSilhouetteInputs(camera, image, silhouette));
  CorrespondenceLines result;
  result.rig_from_objcentre = rig_from_objcentre;
  const double length_px = TracedContourLengthPx(silhouette.contour);
  const LineAnchors anchors(
      caster, camera, cam_from_rig, rig_from_objcentre, silhouette,
      silhouette.contour.empty() ? 0 : NumEdgeLinesForLength(length_px, options));
  if (anchors.size() > 0) result.line_spacing_px = length_px / anchors.size();
  const LinearTable table(options.response);
  MeasureEdgeLines(anchors, WindowOnMask::kInsideThenOutside, image, table, silhouette.mask,
                   options, &result);
  if (options.occlusion_contours) {
    const std::vector<ContourPoint> occlusion_contour = ExtractOcclusionContour(
        caster, camera,
        cam_from_rig * rig_from_objcentre * caster.mesh().objcentre_from_template());
    const LineAnchors occlusion_anchors(caster, camera, cam_from_rig, rig_from_objcentre,
                                        occlusion_contour, options.num_lines);
    MeasureEdgeLines(occlusion_anchors, WindowOnMask::kInsideThroughout, image, table,
                     silhouette.mask, options, &result);
  }
  return result;
}

}  // namespace bcot

#include "bcot/optim/edge_lines.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bcot/core/chroma_restoration.h"
#include "bcot/core/chroma_sampling.h"
#include "bcot/core/linear_rgb.h"
#include "bcot/core/violations.h"
#include "bcot/optim/edge_step_model.h"
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
  if (!(crease_min_angle_deg > 0.0 && crease_min_angle_deg < 180.0)) {
    violations.push_back(
        fmt::format("crease_min_angle_deg = {}, must be in (0, 180)", crease_min_angle_deg));
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

// The exact normal CDF (the fit's start; EdgeStepModel approximates it).
double NormalCdf(double z) { return 0.5 * std::erfc(-z * kInvSqrt2); }

// The samples on each side of a line's centre: offsets k·step_px for |k| <= this, within
// window_px (header, "profile").
int SamplesPerSide(const EdgeLineOptions& options) {
  return static_cast<int>(std::floor(options.window_px / options.step_px + 1e-9));
}

// The run of a profile's samples (offsets first_offset_px + k·step_px, k in [0, n)) within
// half_px of centre_px: [first, last], empty (last < first) when none is.
struct SampleRun {
  int first = 0;
  int last = -1;
  int size() const { return last - first + 1; }
};

SampleRun SamplesWithin(int n, double first_offset_px, double step_px, double centre_px,
                        double half_px) {
  SampleRun run{n, -1};
  for (int k = 0; k < n; ++k) {
    if (std::abs(first_offset_px + k * step_px - centre_px) <= half_px + 1e-9) {
      run.first = std::min(run.first, k);
      run.last = k;
    }
  }
  return run;
}

}  // namespace

bool FitEdgeProfile(const std::vector<double>& values, double first_offset_px,
                    const EdgeLineOptions& options, EdgeFit* fit, int max_iterations) {
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
  // The fit window: the samples within fit_half_px of μ0.
  const SampleRun window = SamplesWithin(n, first_offset_px, h, mu0, options.fit_half_px);
  const int first = window.first, last = window.last;
  const int m = window.size();
  if (m < 8) return false;
  const Eigen::ArrayXd offsets = first_offset_px + h * Eigen::ArrayXd::LinSpaced(m, first, last);
  EdgeStepModel model(offsets, mu0, Eigen::Map<const Eigen::ArrayXd>(values.data() + first, m));

  // Initial (a, g, b) by linear least squares at μ = μ0, w = 0.7, k = 0.
  EdgeStepParams x;
  x << 0.0, 0.0, 0.0, mu0, 0.7, 0.0;
  {
    Eigen::MatrixXd a(m, 3);
    a.col(0).setOnes();
    a.col(1) = (offsets - mu0).matrix();
    for (int i = 0; i < m; ++i) a(i, 2) = NormalCdf((offsets[i] - x[3]) / x[4]);
    const Eigen::Vector3d linear =
        a.colPivHouseholderQr().solve(Eigen::Map<const Eigen::VectorXd>(values.data() + first, m));
    x.head<3>() = linear;
  }
  EdgeStepMatrix jtj, jtj_new;
  EdgeStepParams jtr, jtr_new;
  double rss = model.Evaluate(x, &jtj, &jtr);
  double lambda = 1e-3;
  bool converged = false;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    EdgeStepMatrix damped = jtj;
    damped.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
    // λ > 0 makes the damped matrix positive definite; LDLT is the fallback for round-off.
    const Eigen::LLT<EdgeStepMatrix> cholesky(damped);
    const EdgeStepParams delta = cholesky.info() == Eigen::Success
                                     ? EdgeStepParams(-cholesky.solve(jtr))
                                     : EdgeStepParams(-damped.ldlt().solve(jtr));
    EdgeStepParams candidate = x + delta;
    if (!candidate.allFinite()) return false;
    candidate[4] = std::max(candidate[4], 0.05);
    // The normal equations cost little beside Φ and φ, which they share: evaluated with the
    // residuals, they are ready when the step is accepted.
    const double rss_new = model.Evaluate(candidate, &jtj_new, &jtr_new);
    if (rss_new <= rss) {
      x = candidate;
      rss = rss_new;
      jtj = jtj_new;
      jtr = jtr_new;
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
  Eigen::FullPivLU<EdgeStepMatrix> lu(jtj);
  if (!lu.isInvertible()) return false;
  const double noise_variance = rss / std::max(1, m - kEdgeStepParams);
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

namespace {

// The mean of `colors` (colors[k] at offset (k − half)·step_px along the line) over offsets at
// least `gap_px` before `centre_px` (inside) and at least `gap_px` after it (outside); returns
// the smaller of the two sample counts (a side without samples keeps a zero mean).
int SideMeans(const std::vector<Eigen::Vector3d>& colors, double step_px, double centre_px,
              double gap_px, Eigen::Vector3d* inside, Eigen::Vector3d* outside) {
  const int half = static_cast<int>(colors.size() / 2);
  *inside = Eigen::Vector3d::Zero();
  *outside = Eigen::Vector3d::Zero();
  int inside_count = 0, outside_count = 0;
  for (int k = 0; k < static_cast<int>(colors.size()); ++k) {
    const double s = (k - half) * step_px - centre_px;
    if (s <= -gap_px) {
      *inside += colors[k];
      ++inside_count;
    } else if (s >= gap_px) {
      *outside += colors[k];
      ++outside_count;
    }
  }
  *inside /= std::max(1, inside_count);
  *outside /= std::max(1, outside_count);
  return std::min(inside_count, outside_count);
}

}  // namespace

Eigen::Vector3d UnclippedContrast(const EdgeLineSamples& samples, const EdgeLineOptions& options) {
  Eigen::Vector3d d = samples.inside - samples.outside;
  for (int c = 0; c < 3; ++c) {
    if (samples.peak[c] >= options.clip_level) d[c] = 0.0;
  }
  return d;
}

bool SampleEdgeLine(const cv::Mat3b& image, const LinearTable& table, const Eigen::Vector2d& centre,
                    const Eigen::Vector2d& normal, const EdgeLineOptions& options,
                    EdgeLineSamples* samples) {
  const double h = options.step_px;
  const int half = SamplesPerSide(options);
  if (!CanSampleBilinear(image.size(), centre - half * h * normal) ||
      !CanSampleBilinear(image.size(), centre + half * h * normal)) {
    return false;
  }
  samples->colors.resize(2 * half + 1);
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
  for (int k = -half; k <= half; ++k) {
    const Eigen::Vector2d p = centre + k * h * normal;
    samples->colors[k + half] = SampleLinearRgb(image, table, p);
    peak = peak.cwiseMax(PeakLinearRgb(image, table, p));
  }
  SideMeans(samples->colors, h, 0.0, 1.0, &samples->inside, &samples->outside);
  samples->peak = peak;
  return true;
}

namespace {

// The fit of sampled colours (the contrast direction, clipping and profile fit of the header).
bool FitSampledEdge(const EdgeLineSamples& samples, const EdgeLineOptions& options, EdgeFit* fit,
                    int max_iterations = kEdgeFitIterations) {
  const Eigen::Vector3d d = UnclippedContrast(samples, options);
  if (!(d.norm() >= options.min_contrast) || d.norm() == 0.0) return false;
  const Eigen::Vector3d direction = d.normalized();
  const int half = static_cast<int>(samples.colors.size() / 2);
  std::vector<double> profile(samples.colors.size());
  for (size_t k = 0; k < profile.size(); ++k) profile[k] = direction.dot(samples.colors[k]);
  return FitEdgeProfile(profile, -half * options.step_px, options, fit, max_iterations);
}

// The mean linear colours of a line's samples beyond ±kPlateauPx of its edge at `mean_px`
// (inside, outside); false when either side has fewer than two samples.
constexpr double kPlateauPx = 1.5;

bool PlateauColours(const EdgeLineSamples& samples, double mean_px, const EdgeLineOptions& options,
                    Eigen::Vector3d* inside, Eigen::Vector3d* outside) {
  return SideMeans(samples.colors, options.step_px, mean_px, kPlateauPx, inside, outside) >= 2;
}

// An ideal edge for the codec simulation: per channel a step between two linear colours,
// blurred by a Gaussian: rgb(s) = inside + (outside − inside)·Φ((s − μ)/w), then clipped to
// full scale by the sensor (DrawIdealEdge; an inside colour above 1: SaturatedInsideChannels).
struct IdealEdge {
  Eigen::Vector3d inside = Eigen::Vector3d::Zero();
  Eigen::Vector3d outside = Eigen::Vector3d::Zero();
  double mean_px = 0.0;
  double width_px = 1.0;
};

// The samples of the line through `centre` along `normal` on `patch` (BGR codes, its pixel
// (0, 0) at image pixel `origin`), as SampleEdgeLine takes them from an image: codes decoded by
// `table`, then bilinear. `peak` is copied from the observed line, so the same channels count as
// clipped.
EdgeLineSamples SamplePatchLine(const cv::Mat3d& patch, const Eigen::Vector2i& origin,
                                const LinearTable& table, const Eigen::Vector2d& centre,
                                const Eigen::Vector2d& normal, const Eigen::Vector3d& peak,
                                const EdgeLineOptions& options) {
  const double h = options.step_px;
  const int half = SamplesPerSide(options);
  const auto linear = [&](int x, int y) {
    const cv::Vec3d& px = patch(y - origin.y(), x - origin.x());
    return Eigen::Vector3d(table.Decode(px[2]), table.Decode(px[1]), table.Decode(px[0]));
  };
  EdgeLineSamples samples;
  samples.colors.resize(2 * half + 1);
  for (int k = -half; k <= half; ++k) {
    const Eigen::Vector2d p = centre + k * h * normal;
    const int x0 = static_cast<int>(std::floor(p.x())), y0 = static_cast<int>(std::floor(p.y()));
    const double fx = p.x() - x0, fy = p.y() - y0;
    samples.colors[k + half] = (1 - fy) * ((1 - fx) * linear(x0, y0) + fx * linear(x0 + 1, y0)) +
                               fy * ((1 - fx) * linear(x0, y0 + 1) + fx * linear(x0 + 1, y0 + 1));
  }
  SideMeans(samples.colors, h, 0.0, 1.0, &samples.inside, &samples.outside);
  samples.peak = peak;
  return samples;
}

// A decoded profile without noise is a sharp luma step plus a blurred chroma step, outside the
// fit's model: its Levenberg-Marquardt steps crawl along a shallow valley for longer than a
// noisy image's (measured, scripts/bench_edge_fit.sh: at 30 steps a tenth of the simulated fits
// of the benchmark's lines had not converged).
constexpr int kSimulatedFitIterations = 100;

int FloorToMultiple(int value, int factor) {
  return static_cast<int>(std::floor(static_cast<double>(value) / factor)) * factor;
}

// The pixels a simulation of the line through `centre` along `normal` must draw: those its
// samples rest on (SamplePatchLine: each sample's pixel and the next one across and down), grown
// by the codec's reach (a decoded pixel's chroma comes from its own block's mean and the next
// block's along each axis: source pixels up to 2 away), rounded out to whole blocks. The decoded
// values of the sampled pixels are then those of an unbounded drawing (the blocks at the patch's
// border, whose upsampling lacks a neighbour, are not sampled). Returns the patch's pixel (0, 0)
// in `origin` and its size.
cv::Size LinePatch(const Eigen::Vector2d& centre, const Eigen::Vector2d& normal,
                   const EdgeLineOptions& options, const ChromaSampling& sampling,
                   Eigen::Vector2i* origin) {
  constexpr int kCodecReachPx = 2;
  const double h = options.step_px;
  const int half = SamplesPerSide(options);
  Eigen::Vector2i low(std::numeric_limits<int>::max(), std::numeric_limits<int>::max());
  Eigen::Vector2i high(std::numeric_limits<int>::min(), std::numeric_limits<int>::min());
  for (const int k : {-half, half}) {  // the samples' pixels are monotonic along the line
    const Eigen::Vector2d p = centre + k * h * normal;
    const Eigen::Vector2i pixel(static_cast<int>(std::floor(p.x())),
                                static_cast<int>(std::floor(p.y())));
    low = low.cwiseMin(pixel);
    high = high.cwiseMax(pixel + Eigen::Vector2i::Ones());
  }
  low -= Eigen::Vector2i::Constant(kCodecReachPx);
  high += Eigen::Vector2i::Constant(kCodecReachPx);
  *origin = Eigen::Vector2i(FloorToMultiple(low.x(), sampling.horizontal),
                            FloorToMultiple(low.y(), sampling.vertical));
  // The end of high's block.
  const Eigen::Vector2i end(FloorToMultiple(high.x(), sampling.horizontal) + sampling.horizontal,
                            FloorToMultiple(high.y(), sampling.vertical) + sampling.vertical);
  return cv::Size(end.x() - origin->x(), end.y() - origin->y());
}

// The nodes DrawIdealEdge tabulates an edge at, in blur widths from its centre: z_i = −4 + i/8.
// Spacing w/8 keeps linear interpolation of Φ within 6e-4 of it; beyond 4w, Φ is within 3e-5 of
// 0 or 1 (the end values).
constexpr double kDrawReach = 4.0;
constexpr double kDrawSpacing = 1.0 / 8.0;
constexpr int kDrawNodes = 65;
static_assert(kDrawNodes == static_cast<int>(2.0 * kDrawReach / kDrawSpacing) + 1);

// Φ(z_i) at DrawIdealEdge's nodes; the same for every edge, so computed once.
const std::array<double, kDrawNodes>& StandardNormalNodes() {
  static const std::array<double, kDrawNodes> cdf = [] {
    std::array<double, kDrawNodes> values{};
    for (int i = 0; i < kDrawNodes; ++i) values[i] = NormalCdf(-kDrawReach + i * kDrawSpacing);
    return values;
  }();
  return cdf;
}

// `edge` drawn as BGR codes on the pixels of an image around the line through `centre` along
// `normal`, its pixel (0, 0) at `origin`; linear values above full scale are clipped to code 255.
cv::Mat3d DrawIdealEdge(const IdealEdge& edge, const LinearTable& table,
                        const Eigen::Vector2i& origin, const cv::Size& size,
                        const Eigen::Vector2d& centre, const Eigen::Vector2d& normal) {
  // The codes as a function of s, tabulated at the nodes s_i = μ + z_i·w (StandardNormalNodes:
  // linear interpolation between them stays far below a code's step) and constant beyond them.
  const std::array<double, kDrawNodes>& cdf = StandardNormalNodes();
  std::array<cv::Vec3d, kDrawNodes> tabulated;
  for (int i = 0; i < kDrawNodes; ++i) {
    const Eigen::Vector3d rgb = edge.inside + (edge.outside - edge.inside) * cdf[i];
    tabulated[i] = cv::Vec3d(table.Encode(rgb[2]), table.Encode(rgb[1]), table.Encode(rgb[0]));
  }
  cv::Mat3d codes(size);
  const double first = edge.mean_px - kDrawReach * edge.width_px;
  const double inv_spacing = 1.0 / (kDrawSpacing * edge.width_px);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const double s = normal.dot(Eigen::Vector2d(origin.x() + x, origin.y() + y) - centre);
      const double t = std::clamp((s - first) * inv_spacing, 0.0, kDrawNodes - 1.0);
      const int i = std::min(static_cast<int>(t), kDrawNodes - 2);
      const double f = t - i;
      codes(y, x) = (1.0 - f) * tabulated[i] + f * tabulated[i + 1];
    }
  }
  return codes;
}

// The simulations of one line through `centre` along `normal` (observed with `peak`, so that the
// same channels count as clipped): an ideal edge drawn on the pixels around the line
// (DrawIdealEdge over LinePatch), passed through the codec's chroma path or not, sampled as
// SampleEdgeLine samples an image.
class LineSimulator {
 public:
  LineSimulator(const LinearTable& table, const Eigen::Vector2d& centre,
                const Eigen::Vector2d& normal, const Eigen::Vector3d& peak,
                const EdgeLineOptions& options, const ChromaSampling& sampling)
      : table_(table),
        centre_(centre),
        normal_(normal),
        peak_(peak),
        options_(options),
        sampling_(sampling),
        size_(LinePatch(centre, normal, options, sampling, &origin_)) {}

  cv::Mat3d Draw(const IdealEdge& edge) const {
    return DrawIdealEdge(edge, table_, origin_, size_, centre_, normal_);
  }
  EdgeLineSamples Sample(const cv::Mat3d& drawing) const {
    return SamplePatchLine(drawing, origin_, table_, centre_, normal_, peak_, options_);
  }
  EdgeLineSamples SampleDecoded(const cv::Mat3d& drawing) const {
    return Sample(SimulateChromaSubsampling(drawing, sampling_));
  }

 private:
  const LinearTable& table_;
  Eigen::Vector2d centre_, normal_;
  Eigen::Vector3d peak_;
  const EdgeLineOptions& options_;
  const ChromaSampling& sampling_;
  Eigen::Vector2i origin_;
  cv::Size size_;
};

// One fixed-point step of an ideal edge's colours beyond the blur: each moves by the observed
// minus the decoded drawing's plateau colour, kept within [0, 1].
void StepColours(const Eigen::Vector3d& observed_inside, const Eigen::Vector3d& observed_outside,
                 const Eigen::Vector3d& decoded_inside, const Eigen::Vector3d& decoded_outside,
                 IdealEdge* edge) {
  edge->inside = (edge->inside + observed_inside - decoded_inside).cwiseMax(0.0).cwiseMin(1.0);
  edge->outside = (edge->outside + observed_outside - decoded_outside).cwiseMax(0.0).cwiseMin(1.0);
}

// FitSampledEdge on simulated samples.
bool FitSimulatedEdge(const EdgeLineSamples& samples, const EdgeLineOptions& options,
                      EdgeFit* fit) {
  return FitSampledEdge(samples, options, fit, kSimulatedFitIterations);
}

// The channels at full scale on the object's side of a line (its plateau there at or above
// clip_level) and below it on the other. The light there is beyond full scale by an amount the
// plateau does not show; it sets how far the clipped top of the channel's blurred step reaches
// towards the background ("Clipping" in the header), and the codec carries that shape into the
// other channels through the chroma they share. Drawn at full scale, the channel makes the
// correction wrong by as much as the codec's whole shift (a 4:2:0 edge of a lit orange surface
// whose red is 1.6× full scale: found 0.2 px outside; FitEdgeAcrossTest).
//   A background at full scale is left drawn at full scale. Modelled the same way, it took the
// plastic bunny's lines of that kind from 0.045 px inside their PNG twins' edges to 0.003 px,
// but put the small glossy bunny's 0.10 px outside them (from 0.03 px inside; also on its
// 4:2:0 copy without quantisation), where the glossy rim mirrors that background and no
// constant inside colour draws it (docs/notes/issue12_jpeg_chroma.md).
// (A plateau at clip_level has its line's peak there too: the peak bounds every sample.)
std::vector<int> SaturatedInsideChannels(const Eigen::Vector3d& inside,
                                         const Eigen::Vector3d& outside,
                                         const EdgeLineOptions& options) {
  std::vector<int> channels;
  for (int c = 0; c < 3; ++c) {
    if (inside[c] >= options.clip_level && outside[c] < options.clip_level) channels.push_back(c);
  }
  return channels;
}

// The saturated levels' range (full scales) and start: one stop above full scale, the middle of
// the range in stops. Beyond the top, the clipped step's reach grows only with √(log level).
constexpr double kMaxSaturatedLevel = 16.0;
constexpr double kStartSaturatedLevel = 2.0;

// Analysis by synthesis of a line with saturated channels: the ideal edge whose decoded drawing
// matches the observed samples, in all three channels, within fit_half_px of the observed centre
// `centre_px`. Levenberg-Marquardt over θ = (μ, w, log L_1, ..., log L_k) (L_i the saturated
// levels), its Jacobian by forward differences (a simulation per column), in rounds between
// which the colours beyond the blur take a fixed-point step (StepColours), the saturated levels
// kept. Unlike matching the fit's outputs one by one, whose secant steps mix the level's effect
// on the decoded centre with the centre's own, it converges from the observed fit
// (FitEdgeAcrossTest). `edge` holds the start and receives the result.
class SaturatedEdgeFit {
 public:
  SaturatedEdgeFit(const EdgeLineSamples& observed, double centre_px, std::vector<int> channels,
                   const LineSimulator& simulator, const EdgeLineOptions& options)
      : observed_(observed),
        channels_(std::move(channels)),
        simulator_(simulator),
        options_(options) {
    const int n = static_cast<int>(observed.colors.size());
    window_ = SamplesWithin(n, -(n / 2) * options.step_px, options.step_px, centre_px,
                            options.fit_half_px);
  }

  void Run(const Eigen::Vector3d& observed_inside, const Eigen::Vector3d& observed_outside,
           IdealEdge* edge) const {
    for (int c : channels_) edge->inside[c] = kStartSaturatedLevel;
    for (int round = 0;; ++round) {
      Solve(edge);
      if (round + 1 == kRounds) return;
      Eigen::Vector3d decoded_inside, decoded_outside;
      if (!PlateauColours(simulator_.SampleDecoded(simulator_.Draw(*edge)), edge->mean_px, options_,
                          &decoded_inside, &decoded_outside)) {
        return;
      }
      const Eigen::Vector3d levels = edge->inside;
      StepColours(observed_inside, observed_outside, decoded_inside, decoded_outside, edge);
      for (int c : channels_) edge->inside[c] = levels[c];
    }
  }

 private:
  // Two rounds of at most three steps each, until the centre moves less than kStopPx: eight steps
  // to 0.001 px change FitEdgeAcrossTest's mean errors on clipped edges by less than 0.002 px.
  static constexpr int kRounds = 2;
  static constexpr int kSteps = 3;
  static constexpr double kStopPx = 0.01;

  Eigen::VectorXd Parameters(const IdealEdge& edge) const {
    Eigen::VectorXd x(2 + channels_.size());
    x[0] = edge.mean_px;
    x[1] = edge.width_px;
    for (size_t i = 0; i < channels_.size(); ++i) x[2 + i] = std::log(edge.inside[channels_[i]]);
    return x;
  }

  IdealEdge WithParameters(const IdealEdge& edge, const Eigen::VectorXd& x) const {
    IdealEdge result = edge;
    result.mean_px = x[0];
    result.width_px = std::clamp(x[1], options_.min_width_px, options_.max_width_px);
    for (size_t i = 0; i < channels_.size(); ++i) {
      result.inside[channels_[i]] =
          std::exp(std::clamp(x[2 + i], 0.0, std::log(kMaxSaturatedLevel)));
    }
    return result;
  }

  // The observed minus the decoded drawing's samples over window_, all three channels.
  Eigen::VectorXd Residuals(const IdealEdge& edge) const {
    const EdgeLineSamples predicted = simulator_.SampleDecoded(simulator_.Draw(edge));
    Eigen::VectorXd r(3 * std::max(window_.size(), 0));
    for (int k = window_.first; k <= window_.last; ++k) {
      r.segment<3>(3 * (k - window_.first)) = observed_.colors[k] - predicted.colors[k];
    }
    return r;
  }

  // Levenberg-Marquardt steps from `edge`. The Jacobian at the start serves every step (chord
  // steps): the steps are short, and recomputing it at each costs another simulation per
  // parameter for no measurable gain (FitEdgeAcrossTest's mean errors change by < 0.01 px).
  void Solve(IdealEdge* edge) const {
    const Eigen::VectorXd step_sizes = (Eigen::VectorXd(2 + channels_.size()) << 0.02, 0.02,
                                        Eigen::VectorXd::Constant(channels_.size(), 0.05))
                                           .finished();
    Eigen::VectorXd x = Parameters(*edge);
    Eigen::VectorXd r = Residuals(*edge);
    // r = observed − predicted, so J = −∂r/∂θ is the predicted samples' Jacobian.
    Eigen::MatrixXd jacobian(r.size(), x.size());
    for (int p = 0; p < x.size(); ++p) {
      Eigen::VectorXd moved = x;
      moved[p] += step_sizes[p];
      jacobian.col(p) = (r - Residuals(WithParameters(*edge, moved))) / step_sizes[p];
    }
    const Eigen::MatrixXd jtj = jacobian.transpose() * jacobian;
    double cost = r.squaredNorm();
    double lambda = 1e-2;
    for (int step = 0; step < kSteps; ++step) {
      const Eigen::VectorXd jtr = jacobian.transpose() * r;
      bool accepted = false;
      while (!accepted && lambda <= 1e4) {
        Eigen::MatrixXd damped = jtj;
        damped.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
        const Eigen::VectorXd delta = damped.ldlt().solve(jtr);
        const IdealEdge candidate = WithParameters(*edge, x + delta);
        const Eigen::VectorXd candidate_r = Residuals(candidate);
        if (delta.allFinite() && candidate_r.squaredNorm() <= cost) {
          *edge = candidate;
          x = Parameters(candidate);
          r = candidate_r;
          cost = r.squaredNorm();
          lambda = std::max(lambda * 0.3, 1e-6);
          accepted = true;
          if (std::abs(delta[0]) < kStopPx) return;
        } else {
          lambda *= 10.0;
        }
      }
      if (!accepted) return;
    }
  }

  const EdgeLineSamples& observed_;
  SampleRun window_;           // the samples within fit_half_px of the observed centre
  std::vector<int> channels_;  // saturated on the inside
  const LineSimulator& simulator_;
  const EdgeLineOptions& options_;
};

// The codec's shift of `edge`'s fitted centre: its decoded drawing's fit minus its clean
// drawing's (which cancels what bilinear sampling and the model do to both); false when a fit
// fails.
bool CodecShift(const LineSimulator& simulator, const cv::Mat3d& clean, const EdgeFit& decoded_fit,
                const EdgeLineOptions& options, double* shift_px) {
  EdgeFit clean_fit;
  if (!FitSimulatedEdge(simulator.Sample(clean), options, &clean_fit)) return false;
  *shift_px = decoded_fit.mean_px - clean_fit.mean_px;
  return true;
}

}  // namespace

bool ChromaSubsamplingShift(const EdgeLineSamples& samples, const EdgeFit& fit,
                            const LinearTable& table, const Eigen::Vector2d& centre,
                            const Eigen::Vector2d& normal, const EdgeLineOptions& options,
                            const ChromaSampling& sampling, ChromaShift* shift) {
  Eigen::Vector3d observed_inside, observed_outside;
  if (!sampling.simulated() ||
      !PlateauColours(samples, fit.mean_px, options, &observed_inside, &observed_outside)) {
    return false;
  }
  const LineSimulator simulator(table, centre, normal, samples.peak, options, sampling);
  IdealEdge edge{observed_inside, observed_outside, fit.mean_px, fit.width_px};
  std::vector<int> saturated =
      options.saturated_level_fit
          ? SaturatedInsideChannels(observed_inside, observed_outside, options)
          : std::vector<int>();
  if (!saturated.empty()) {
    // The edge by analysis by synthesis, then the codec's shift of the observed fit from it (so
    // that what the fit makes of a shading ramp, outside the ideal edge, stays in the fit).
    SaturatedEdgeFit(samples, fit.mean_px, std::move(saturated), simulator, options)
        .Run(observed_inside, observed_outside, &edge);
    const cv::Mat3d clean = simulator.Draw(edge);
    EdgeFit decoded_fit;
    if (!FitSimulatedEdge(simulator.SampleDecoded(clean), options, &decoded_fit)) return false;
    shift->sensitivity = 1.0;
    return CodecShift(simulator, clean, decoded_fit, options, &shift->shift_px);
  }
  // The ideal edge whose decoded image looks like the observed line to the fit (the same
  // centre, blur width and colours beyond the blur), found by fixed-point steps from the observed
  // values (indirect inference); the shift is then the one the codec causes to that edge.
  // Three simulations (two updates): on bench_edge_fit's lines the mean error is 0.056 px after
  // two, 0.039 after three, 0.031 after four, each costing a sixth more.
  constexpr int kIterations = 3;
  double previous_mean_px = 0.0, previous_decoded_mean_px = 0.0;
  double sensitivity = 1.0;
  for (int iteration = 0;; ++iteration) {
    const cv::Mat3d clean = simulator.Draw(edge);
    const EdgeLineSamples decoded_samples = simulator.SampleDecoded(clean);
    EdgeFit decoded_fit;
    if (!FitSimulatedEdge(decoded_samples, options, &decoded_fit)) return false;
    // dμ_decoded / dμ_edge by secants between the steps: where the edge's position in the
    // codec's blocks makes the decoded centre move slower than the edge, the observed centre
    // says less about the edge.
    if (iteration > 0 && std::abs(edge.mean_px - previous_mean_px) > 1e-6) {
      sensitivity = std::clamp(
          (decoded_fit.mean_px - previous_decoded_mean_px) / (edge.mean_px - previous_mean_px),
          kMinSensitivity, kMaxSensitivity);
    }
    if (iteration + 1 == kIterations) {
      shift->sensitivity = sensitivity;
      return CodecShift(simulator, clean, decoded_fit, options, &shift->shift_px);
    }
    Eigen::Vector3d decoded_inside, decoded_outside;
    if (!PlateauColours(decoded_samples, decoded_fit.mean_px, options, &decoded_inside,
                        &decoded_outside)) {
      return false;
    }
    StepColours(observed_inside, observed_outside, decoded_inside, decoded_outside, &edge);
    // μ by secant steps (the first a fixed-point step), w and the colours by fixed-point steps.
    previous_mean_px = edge.mean_px;
    previous_decoded_mean_px = decoded_fit.mean_px;
    edge.mean_px += (fit.mean_px - decoded_fit.mean_px) / sensitivity;
    edge.width_px = std::clamp(edge.width_px + fit.width_px - decoded_fit.width_px,
                               options.min_width_px, options.max_width_px);
  }
}

EdgeAcross FitEdgeAcross(const cv::Mat3b& image, const LinearTable& table,
                         const Eigen::Vector2d& centre, const Eigen::Vector2d& normal,
                         const EdgeLineOptions& options, EdgeFit* fit,
                         const ChromaSampling& sampling) {
  EdgeLineSamples samples;
  if (!SampleEdgeLine(image, table, centre, normal, options, &samples)) {
    return EdgeAcross::kOffImage;
  }
  if (!FitSampledEdge(samples, options, fit)) return EdgeAcross::kAmbiguous;
  if (sampling.subsampled() && sampling.simulated()) {
    ChromaShift shift;
    if (!ChromaSubsamplingShift(samples, *fit, table, centre, normal, options, sampling, &shift)) {
      return EdgeAcross::kAmbiguous;
    }
    fit->mean_px -= shift.shift_px;
    fit->sigma_px /= shift.sensitivity;
  }
  return EdgeAcross::kFound;
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
                      const LinearTable& table, const ChromaSampling& sampling,
                      const cv::Mat1b& mask, const EdgeLineOptions& options,
                      CorrespondenceLines* result) {
  const double h = options.step_px;
  const int half = SamplesPerSide(options);
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
    if (FitEdgeAcross(image, table, point.pixel, point.normal, options, &fit, sampling) !=
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
                                             const EdgeLineOptions& options,
                                             const ChromaSampling& sampling,
                                             const std::vector<Crease>* creases) {
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
  MeasureEdgeLines(anchors, WindowOnMask::kInsideThenOutside, image, table, sampling,
                   silhouette.mask, options, &result);
  if (options.occlusion_contours) {
    const std::vector<ContourPoint> occlusion_contour = ExtractOcclusionContour(
        caster, camera,
        cam_from_rig * rig_from_objcentre * caster.mesh().objcentre_from_template());
    const LineAnchors occlusion_anchors(caster, camera, cam_from_rig, rig_from_objcentre,
                                        occlusion_contour, options.num_lines);
    MeasureEdgeLines(occlusion_anchors, WindowOnMask::kInsideThroughout, image, table, sampling,
                     silhouette.mask, options, &result);
  }
  if (options.crease_contours) {
    CreaseContourOptions crease_options;
    crease_options.min_angle_deg = options.crease_min_angle_deg;
    crease_options.sample_spacing_px = options.line_spacing_px;
    crease_options.clear_px = options.window_px;
    std::vector<Crease> found;
    if (creases == nullptr) found = FindCreases(caster.mesh(), options.crease_min_angle_deg);
    const std::vector<ContourPoint> crease_contour = ExtractCreaseContour(
        caster, camera, cam_from_rig * rig_from_objcentre * caster.mesh().objcentre_from_template(),
        creases != nullptr ? *creases : found, crease_options);
    const LineAnchors crease_anchors(caster, camera, cam_from_rig, rig_from_objcentre,
                                     crease_contour, options.num_lines);
    MeasureEdgeLines(crease_anchors, WindowOnMask::kInsideThroughout, image, table, sampling,
                     silhouette.mask, options, &result);
  }
  return result;
}

EdgeImage EdgeImageOf(const cv::Mat3b& image, const ChromaSampling& sampling,
                      const ChromaRestorationOptions& restoration, const Silhouette& silhouette,
                      const EdgeLineOptions& options) {
  if (!restoration.enabled || !sampling.subsampled() || !sampling.simulated() ||
      silhouette.contour.empty()) {
    return {image, sampling};
  }
  // Every line lies within window_px of a contour point (crease lines within the contour), and
  // its samples are read bilinearly: one pixel more.
  Eigen::Vector2d low = silhouette.contour.front().pixel, high = low;
  for (const ContourPoint& point : silhouette.contour) {
    low = low.cwiseMin(point.pixel);
    high = high.cwiseMax(point.pixel);
  }
  const double margin = options.window_px + 1.0;
  const int x0 = static_cast<int>(std::floor(low.x() - margin));
  const int y0 = static_cast<int>(std::floor(low.y() - margin));
  const int x1 = static_cast<int>(std::ceil(high.x() + margin)) + 1;
  const int y1 = static_cast<int>(std::ceil(high.y() + margin)) + 1;
  return {RestoreSubsampledChroma(image, sampling, restoration, cv::Rect(x0, y0, x1 - x0, y1 - y0)),
          ChromaSampling::Full()};
}

}  // namespace bcot

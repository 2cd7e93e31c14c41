#include "bcot/optim/response_estimation.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/core/violations.h"
#include "bcot/optim/edge_lines.h"
#include "bcot/optim/silhouette.h"

namespace bcot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One measured edge line: its offset μ from the contour at the solved pose, σ and its polarity
// feature.
struct PolarLine {
  double mean_px = 0.0;
  double sigma_px = 1.0;
  double polarity = 0.0;
};

// The median of `values` (non-empty; reordered).
double Median(std::vector<double>* values) {
  const size_t k = values->size() / 2;
  std::nth_element(values->begin(), values->begin() + k, values->end());
  return (*values)[k];
}

// Interquartile range of `values` (non-empty; reordered).
double InterquartileRange(std::vector<double>* values) {
  const auto quantile = [&](double q) {
    const size_t k = static_cast<size_t>(q * (values->size() - 1));
    std::nth_element(values->begin(), values->begin() + k, values->end());
    return (*values)[k];
  };
  const double upper = quantile(0.75);
  return upper - quantile(0.25);
}

// Standard deviation of the interquartile range of `values` (non-empty) over `samples`
// bootstrap resamples (fixed seed).
double BootstrapStandardError(const std::vector<double>& values, int samples) {
  std::mt19937 generator(12345);
  std::uniform_int_distribution<size_t> pick(0, values.size() - 1);
  std::vector<double> resample(values.size());
  double sum = 0.0, sum_squares = 0.0;
  for (int b = 0; b < samples; ++b) {
    for (double& value : resample) value = values[pick(generator)];
    const double spread = InterquartileRange(&resample);
    sum += spread;
    sum_squares += spread * spread;
  }
  const double mean = sum / samples;
  return std::sqrt(std::max(0.0, sum_squares / samples - mean * mean));
}

// The polarity feature of the edge across `line` (header): per channel PowerShiftRate of its
// mean linear levels inside and outside (SampleEdgeLine), signed positive when the outside is
// brighter, weighted by the channel's share d_k² of the contrast (the fit's scalar profile is
// d̂·I). Clipped channels are left out, as the fit leaves them out.
double PolarityFeature(const cv::Mat3b& image, const LinearTable& table,
                       const CorrespondenceLine& line, const EdgeLineOptions& options) {
  EdgeLineSamples samples;
  if (!SampleEdgeLine(image, table, line.centre, line.normal, options, &samples)) return 0.0;
  double weighted = 0.0, weights = 0.0;
  for (int c = 0; c < 3; ++c) {
    if (samples.peak[c] >= options.clip_level) continue;
    const double inside = samples.inside[c], outside = samples.outside[c];
    const double d = inside - outside;
    const double dark = std::min(inside, outside), bright = std::max(inside, outside);
    const double rate = PowerShiftRate(dark > 0.0 ? bright / dark : kMaxLevelRatio);
    weighted += d * d * (outside > inside ? rate : -rate);
    weights += d * d;
  }
  return weights > 0.0 ? weighted / weights : 0.0;
}

// The edge lines `problem` measures at `rig_from_objcentre` (a pose it solved) in every view,
// as its last edge round measures them: with each view's subsampled chroma corrected for. That
// shift moves an edge with its colours much as a wrong response does
// (docs/notes/issue12_jpeg_chroma.md), so left in, it would be read as the response's.
std::vector<PolarLine> MeasurePolarLines(const FrameProblem& problem,
                                         const std::vector<FrameView>& views,
                                         const Eigen::Isometry3d& rig_from_objcentre) {
  // Model points are read from the contour only (as the edge stage does).
  constexpr int kPointStridePx = 64;
  const RayCaster& caster = problem.caster();
  const EdgeLineOptions& options = problem.options().edge.lines;
  const LinearTable table(options.response);
  const Eigen::Isometry3d objcentre_from_template = caster.mesh().objcentre_from_template();
  std::vector<PolarLine> lines;
  for (const FrameView& view : views) {
    if (view.weight == 0.0) continue;
    const Silhouette silhouette = RenderSilhouette(
        caster, *view.camera, view.cam_from_rig * rig_from_objcentre * objcentre_from_template,
        problem.options().region.contour, kPointStridePx);
    const StatusOr<CorrespondenceLines> measured =
        BuildEdgeLines(caster, *view.camera, view.cam_from_rig, rig_from_objcentre, *view.image,
                       silhouette, options, view.chroma);
    BCOT_CHECK(measured.ok());  // validated with the problem's options
    for (const CorrespondenceLine& line : measured->lines) {
      lines.push_back(
          {line.mean_px, line.sigma_px, PolarityFeature(*view.image, table, line, options)});
    }
  }
  return lines;
}

// The polarity slope β of `lines` (header) and its standard error: weighted (1/σ²) least
// squares of μ − median(μ) on the feature, lines beyond kOutlierSigmas robust standard
// deviations (IQR / 1.349) of μ left out; the standard error is the sandwich (heteroscedasticity-
// consistent) one, as the lines' errors are not all of the size their σ says. NaN when no kept
// line has a feature.
std::pair<double, double> PolaritySlope(const std::vector<PolarLine>& lines) {
  constexpr double kOutlierSigmas = 3.0;
  std::vector<double> offsets;
  for (const PolarLine& line : lines) offsets.push_back(line.mean_px);
  const double median = Median(&offsets);
  const double bound = kOutlierSigmas * InterquartileRange(&offsets) / 1.349;
  double sff = 0.0, sfm = 0.0;
  for (const PolarLine& line : lines) {
    if (std::abs(line.mean_px - median) > bound) continue;
    const double w = 1.0 / (line.sigma_px * line.sigma_px);
    sff += w * line.polarity * line.polarity;
    sfm += w * line.polarity * (line.mean_px - median);
  }
  if (!(sff > 0.0)) return {kNaN, kNaN};
  const double slope = sfm / sff;
  double meat = 0.0;
  for (const PolarLine& line : lines) {
    if (std::abs(line.mean_px - median) > bound) continue;
    const double w = 1.0 / (line.sigma_px * line.sigma_px);
    const double error = line.mean_px - median - slope * line.polarity;
    meat += w * w * line.polarity * line.polarity * error * error;
  }
  return {slope, std::sqrt(meat) / sff};
}

// Test 1 of the header: the index of the candidate with the smallest |β| if the first's |β| is
// clearly not zero and clearly larger; else 0.
int PolarityChoice(const std::vector<ResponseScore>& scores,
                   const ResponseEstimationOptions& options) {
  int nearest = 0;
  for (size_t c = 1; c < scores.size(); ++c) {
    if (std::abs(scores[c].slope_px) < std::abs(scores[nearest].slope_px)) {
      nearest = static_cast<int>(c);
    }
  }
  const ResponseScore& first = scores.front();
  const ResponseScore& near = scores[nearest];
  const bool first_off =
      std::abs(first.slope_px) > options.min_slope_z * first.slope_standard_error_px;
  const bool clearly_nearer =
      std::abs(first.slope_px) - std::abs(near.slope_px) >
      options.min_slope_z * std::hypot(first.slope_standard_error_px, near.slope_standard_error_px);
  return first_off && clearly_nearer ? nearest : 0;
}

// Test 2 of the header: the index of the candidate whose offsets spread least if clearly less
// than the first's; else 0.
int ConsistencyChoice(const std::vector<ResponseScore>& scores,
                      const ResponseEstimationOptions& options) {
  int tightest = 0;
  for (size_t c = 1; c < scores.size(); ++c) {
    if (scores[c].spread_px < scores[tightest].spread_px) tightest = static_cast<int>(c);
  }
  const ResponseScore& first = scores.front();
  const ResponseScore& tight = scores[tightest];
  return first.spread_px - tight.spread_px >
                 options.min_spread_z *
                     std::hypot(first.spread_standard_error_px, tight.spread_standard_error_px)
             ? tightest
             : 0;
}

}  // namespace

double PowerShiftRate(double rho) {
  if (!(rho > 1.0 + 1e-9)) return 0.0;
  rho = std::min(rho, kMaxLevelRatio);
  const double half = 0.5 * (1.0 + rho);
  const double fraction_rate =
      half * (rho * std::log(rho) / (1.0 + rho) - std::log(half)) / (rho - 1.0);
  return std::sqrt(2.0 * kPi) * fraction_rate;
}

std::vector<ImageResponse> DefaultResponseCandidates() {
  std::vector<ImageResponse> candidates = {ImageResponse()};
  for (int tenths = 10; tenths <= 30; tenths += 4) {
    candidates.push_back(ImageResponse::Gamma(tenths / 10.0));
  }
  for (const double stops : {8.0, 10.0, 12.0}) candidates.push_back(ImageResponse::Log(stops));
  return candidates;
}

Status ResponseEstimationOptions::Validate() const {
  std::vector<std::string> violations;
  if (candidates.empty()) violations.push_back("candidates: empty");
  for (const ImageResponse& response : candidates) {
    if (!response.IsValid() || !response.IsResolved()) {
      violations.push_back(
          fmt::format("candidate {} is not a valid known response", response.Name()));
    }
  }
  if (!(min_slope_z >= 0.0) || !std::isfinite(min_slope_z)) {
    violations.push_back(fmt::format("min_slope_z = {}, must be finite and >= 0", min_slope_z));
  }
  if (!(min_spread_z >= 0.0) || !std::isfinite(min_spread_z)) {
    violations.push_back(fmt::format("min_spread_z = {}, must be finite and >= 0", min_spread_z));
  }
  if (bootstrap_samples < 10) {
    violations.push_back(fmt::format("bootstrap_samples = {}, must be >= 10", bootstrap_samples));
  }
  if (edge_rounds < 1)
    violations.push_back(fmt::format("edge_rounds = {}, must be >= 1", edge_rounds));
  return internal::JoinViolations("response estimation", violations);
}

StatusOr<ResponseEstimate> EstimateImageResponse(const FrameProblem& problem,
                                                 const std::vector<FrameView>& views,
                                                 const Eigen::Isometry3d& rig_from_objcentre,
                                                 const ResponseEstimationOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  ResponseEstimate estimate;
  // The candidates are independent solves of the same frame: concurrent, each score in its
  // candidate's place, so the result does not depend on the threads.
  estimate.scores.resize(options.candidates.size());
  tbb::parallel_for(size_t{0}, options.candidates.size(), [&](size_t c) {
    const ImageResponse& response = options.candidates[c];
    FrameProblemOptions frame = problem.options();
    // Without the crease lines, as the estimate was calibrated: where a coarse mesh's facet
    // edges pass as creases their lines scatter (docs/notes/issue12_crease_contours.md), and
    // they moved EstimateImageResponseTest's display-gamma scene off sRGB.
    frame.edge.lines.crease_contours = false;
    frame.edge.lines.response = response;
    frame.edge.rounds = options.edge_rounds;
    frame.edge.redescending_rounds = 0;  // Cauchy solves only, as calibrated
    const FrameProblem candidate(problem.caster(), frame, std::nullopt, problem.viewpoint_model());
    Eigen::Isometry3d solved = rig_from_objcentre;
    ResponseScore& score = estimate.scores[c];
    score.response = response;
    score.slope_px = kNaN;
    score.slope_standard_error_px = kNaN;
    score.spread_px = kNaN;
    score.spread_standard_error_px = kNaN;
    if (candidate.SolveEdges(views, &solved)) {
      const std::vector<PolarLine> lines = MeasurePolarLines(candidate, views, solved);
      score.lines = static_cast<int>(lines.size());
      if (score.lines >= frame.edge.min_lines) {
        std::tie(score.slope_px, score.slope_standard_error_px) = PolaritySlope(lines);
        std::vector<double> offsets;
        for (const PolarLine& line : lines) offsets.push_back(line.mean_px);
        score.spread_standard_error_px = BootstrapStandardError(offsets, options.bootstrap_samples);
        score.spread_px = InterquartileRange(&offsets);
      }
    }
  });
  const ResponseScore& first = estimate.scores.front();
  if (!std::isfinite(first.slope_px)) {
    return Status::InvalidInput(fmt::format(
        "the image response cannot be estimated: fewer than {} edge lines with a contrast "
        "decoded with the default response ({})",
        problem.options().edge.min_lines, first.response.Name()));
  }
  const int polarity = PolarityChoice(estimate.scores, options);
  estimate.response =
      estimate.scores[polarity > 0 ? polarity : ConsistencyChoice(estimate.scores, options)]
          .response;
  return estimate;
}

}  // namespace bcot

#include "bcot/optim/response_estimation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "bcot/optim/edge_lines.h"
#include "bcot/optim/silhouette.h"
#include "violations.h"

namespace bcot {
namespace {

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

// The offsets μ of `problem`'s edge lines in every view at `rig_from_objcentre`.
std::vector<double> EdgeOffsets(const FrameProblem& problem, const std::vector<FrameView>& views,
                                const Eigen::Isometry3d& rig_from_objcentre) {
  // Model points are read from the contour only (as the edge stage does).
  constexpr int kPointStridePx = 64;
  const RayCaster& caster = problem.caster();
  const Eigen::Isometry3d objcentre_from_template = caster.mesh().objcentre_from_template();
  std::vector<double> offsets;
  for (const FrameView& view : views) {
    if (view.weight == 0.0) continue;
    const Silhouette silhouette = RenderSilhouette(
        caster, *view.camera, view.cam_from_rig * rig_from_objcentre * objcentre_from_template,
        problem.options().region.contour, kPointStridePx);
    const StatusOr<CorrespondenceLines> measured =
        BuildEdgeLines(caster, *view.camera, view.cam_from_rig, rig_from_objcentre, *view.image,
                       silhouette, problem.options().edge.lines);
    BCOT_CHECK(measured.ok());  // validated with the problem's options
    for (const CorrespondenceLine& line : measured->lines) offsets.push_back(line.mean_px);
  }
  return offsets;
}

}  // namespace

std::vector<ImageResponse> DefaultResponseCandidates() {
  std::vector<ImageResponse> candidates = {ImageResponse()};
  for (int tenths = 10; tenths <= 30; tenths += 4) {
    candidates.push_back(ImageResponse::Gamma(tenths / 10.0));
  }
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
  if (!(min_improvement_z >= 0.0) || !std::isfinite(min_improvement_z)) {
    violations.push_back(
        fmt::format("min_improvement_z = {}, must be finite and >= 0", min_improvement_z));
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
  int best = -1;
  for (const ImageResponse& response : options.candidates) {
    FrameProblemOptions frame = problem.options();
    frame.edge.lines.response = response;
    frame.edge.rounds = options.edge_rounds;
    const FrameProblem candidate(problem.caster(), frame);
    Eigen::Isometry3d solved = rig_from_objcentre;
    ResponseScore score;
    score.response = response;
    score.spread_px = std::numeric_limits<double>::quiet_NaN();
    score.standard_error_px = std::numeric_limits<double>::quiet_NaN();
    if (candidate.SolveEdges(views, &solved)) {
      std::vector<double> offsets = EdgeOffsets(candidate, views, solved);
      score.lines = static_cast<int>(offsets.size());
      if (score.lines >= frame.edge.min_lines) {
        score.standard_error_px = BootstrapStandardError(offsets, options.bootstrap_samples);
        score.spread_px = InterquartileRange(&offsets);
      }
    }
    estimate.scores.push_back(score);
    const int index = static_cast<int>(estimate.scores.size()) - 1;
    if (score.spread_px <
        (best < 0 ? std::numeric_limits<double>::infinity() : estimate.scores[best].spread_px)) {
      best = index;
    }
  }
  if (best < 0) {
    return Status::InvalidInput(fmt::format(
        "the image response cannot be estimated: no candidate response left {} edge lines",
        problem.options().edge.min_lines));
  }
  // The default unless the best candidate is clearly better (see the header).
  const ResponseScore& first = estimate.scores.front();
  const ResponseScore& winner = estimate.scores[best];
  const double difference_se = std::hypot(first.standard_error_px, winner.standard_error_px);
  const bool clearly_better =
      !std::isfinite(first.spread_px) ||
      first.spread_px - winner.spread_px > options.min_improvement_z * difference_se;
  estimate.response = clearly_better ? winner.response : first.response;
  return estimate;
}

}  // namespace bcot

// The cameras' response (linear_rgb.h) estimated from the object's own edges in one frame.
//
// Why. The edge stage locates each edge as the centre of a blurred step in linear light. Codes
// decoded with the wrong response bend every step, and its centre moves towards one side by an
// amount that depends on the two colours: towards the bright side for a linear camera decoded
// as sRGB (on a Cycles render re-encoded linearly, 0.2 mm of vertical bias and twice the
// rotation error: docs/notes/issue12_response.md). Rims brighter and darker than their
// background then move in opposite directions, which no rigid pose can follow.
//
// Estimate. For each candidate response: the edge stage (FrameProblem::SolveEdges) from the
// given pose with the edges decoded by it, then the edge lines measured again at its result;
// their offsets μ from the solved contour are what the pose could not explain. The candidate
// with the smallest robust spread of μ (interquartile range over all views' lines) is the
// estimate: under the right response one rigid pose explains the edges best; but the first
// candidate (the default, sRGB) is kept unless the best one's spread is smaller by more than
// min_improvement_z standard errors of the difference (each spread's standard error from a
// bootstrap over its lines). On one frame of a Cycles render, sRGB-encoded, the spreads of
// sRGB and γ 1.6–2.2 differ by about their noise (±0.02 px of ~0.65); picking γ 2.0 there
// costs 0.02 mm of bias, so a near tie must not move the response. A linear camera's frame
// separates by ~10 standard errors. One response is estimated for all views (a rig of cameras
// of one kind and setting).
//
// Units: px (spread). Thread safety: pure function.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "bcot/core/linear_rgb.h"
#include "bcot/core/status.h"
#include "bcot/optim/frame_problem.h"

namespace bcot {

// sRGB and the power laws γ = 1.0, 1.4, ..., 3.0 (seven edge solves: ~0.5 s for two 640×512
// views, ~1.5 s for two 960×768 ones).
std::vector<ImageResponse> DefaultResponseCandidates();

struct ResponseScore {
  ImageResponse response;
  double spread_px = 0.0;  // interquartile range of the lines' μ at the solved pose; NaN: failed
  double standard_error_px = 0.0;  // of spread_px, bootstrap over the lines
  int lines = 0;                   // edge lines measured there (all views)
};

struct ResponseEstimationOptions {
  // Tried in order; the first is the default kept on a near tie. Non-empty, each valid and
  // resolved. Default: DefaultResponseCandidates().
  std::vector<ImageResponse> candidates = DefaultResponseCandidates();
  // Smallest improvement over the first candidate, in standard errors of the difference of
  // the two spreads, for another candidate to be chosen; >= 0.
  double min_improvement_z = 2.0;
  // Bootstrap resamples of the lines per candidate (fixed seed: deterministic); >= 10.
  int bootstrap_samples = 200;
  // Edge solves per candidate (edge.rounds replaced); >= 1. The pose of a solved frame moves
  // by hundredths of a pixel between candidates, so one re-rendered solve suffices.
  int edge_rounds = 1;
  Status Validate() const;
};

struct ResponseEstimate {
  ImageResponse response;             // the best candidate
  std::vector<ResponseScore> scores;  // every candidate, in the order given
};

// Scores the candidates on the views of one frame at `rig_from_objcentre` (a solved pose: the
// edge stage searches ±edge.lines.search_px around its contour) with the edge stage of
// `problem`'s options. Errors: invalid options (kInvalidConfig); no candidate left at least
// edge.min_lines lines (kInvalidInput).
StatusOr<ResponseEstimate> EstimateImageResponse(const FrameProblem& problem,
                                                 const std::vector<FrameView>& views,
                                                 const Eigen::Isometry3d& rig_from_objcentre,
                                                 const ResponseEstimationOptions& options = {});

}  // namespace bcot

// The cameras' response (linear_rgb.h) estimated from the object's own edges in one frame.
//
// Why. The edge stage locates each edge as the centre of a blurred step in linear light. Codes
// decoded with the wrong response bend every step, and its centre moves towards one side by an
// amount that depends on the two levels: towards the bright side for a linear camera decoded as
// sRGB (on a Cycles render re-encoded linearly, 0.2 mm of vertical bias and twice the rotation
// error: docs/notes/issue12_response.md), towards the dark side for Blender's Filmic view
// decoded as sRGB (0.3 mm). With light from above, the upper rim is brighter than what lies
// behind it and the lower rim darker: both move the same way in the image, and the pose follows
// them as a bias. Nothing in the spread of the edges shows it (the pose absorbs it); what does
// is that, across all lines, an edge's offset depends on which of its sides is brighter. Under
// the right response it does not: a symmetric blur keeps the centre of any step in place.
//
// Model (docs/method.md, "Camera response"). Decoding off by a power κ (the values raised to κ)
// moves the centre of a step of blur width w between linear levels 1 and ρ > 1 towards its bright
// side by (κ − 1)·w·D(ρ) to first order (D: PowerShiftRate). Per line the polarity feature
//   f = Σ_k d_k²·(±D(ρ_k)) / Σ_k d_k²,  + when channel k is brighter outside,
// over the unclipped channels (d_k their contrast, ρ_k the ratio of their side levels) is the
// outward move of its edge per unit of (κ − 1)·w.
//
// Estimate. For each candidate response: the edge stage (FrameProblem::SolveEdges) from the
// given pose with the edges decoded by it and the edge lines measured again at its result. Two
// tests, each of which leaves the default (the first candidate, sRGB) only on clear evidence:
//   1. Polarity: the slope β of the lines' offsets μ on f, weighted (1/σ²) least squares with
//      outliers beyond 3 robust standard deviations left out and a sandwich standard error.
//      β ≈ (κ − 1)·w: positive when the decoding is too heavy (a linear camera read as sRGB:
//      β ≈ +0.2 px on a Cycles render), negative when too light (Filmic read as sRGB: ≈ −0.25
//      px), zero under the right response. β is measured after the pose has absorbed what a
//      rigid motion can; the rest still crosses zero at the right response. But the scene
//      moves edges with their polarity too (shaded rims, reflections: β from −0.15 to +0.24 px
//      on our Cycles scenes decoded right, +0.2 to +0.4 px under every candidate alike on a
//      glossy synthetic spool). So the candidate with the smallest |β| is chosen only if the
//      default's |β| exceeds min_slope_z standard errors and the candidate's |β| is smaller by
//      min_slope_z standard errors of the difference: the response must explain the polarity
//      dependence, not merely be nearest to zero.
//   2. Consistency, when the first finds nothing: under the right response one rigid pose
//      explains the edges best, so the candidate whose μ spread least (interquartile range) is
//      chosen if its spread is smaller than the default's by min_spread_z standard errors of
//      the difference (bootstrap over the lines). This sees what the pose cannot absorb; on
//      sharp images (blur ≲ 0.5 px), where β is small, it still recognises a linear camera.
// One response is estimated for all views (a rig of cameras of one kind and setting).
//
// Units: px (β per unit of the feature, spreads). Thread safety: pure functions.
#pragma once

#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "bcot/core/linear_rgb.h"
#include "bcot/core/status.h"
#include "bcot/optim/frame_problem.h"

namespace bcot {

// sRGB, the power laws γ = 1.0, 1.4, ..., 3.0 and the log encodings of 8, 10 and 12 stops
// (ten edge solves of one frame: under 1 s of CPU for two views of 640×512 or 960×768,
// docs/notes/issue12_response.md).
std::vector<ImageResponse> DefaultResponseCandidates();

// Level ratios above this count as this (a side at code 0 is black).
inline constexpr double kMaxLevelRatio = 1e6;

// D(ρ) of the model above: the first-order rate dΦ⁻¹(F)/dκ at κ = 1 of the centre of a
// Gaussian-blurred step between linear levels 1 and ρ decoded with its values raised to κ, in
// blur widths, towards the bright side. The level halfway between the decoded sides, mapped
// back, lies at the fraction F(κ) = (((1 + ρ^κ)/2)^(1/κ) − 1)/(ρ − 1) of the step, and
//   dF/dκ = ((1 + ρ)/2)·(ρ·ln ρ/(1 + ρ) − ln((1 + ρ)/2))/(ρ − 1),   dΦ⁻¹/dF = √(2π) at F = ½.
// 0 for ρ <= 1, rising to √(2π)·ln(2)/2 ≈ 0.87 as ρ → ∞ (ρ is capped at kMaxLevelRatio).
double PowerShiftRate(double rho);

struct ResponseScore {
  ImageResponse response;
  // At this candidate's solved pose, NaN when the solve failed or left fewer than
  // edge.min_lines lines: the polarity slope β and its standard error (test 1), the
  // interquartile range of the lines' μ and its bootstrap standard error (test 2).
  double slope_px = 0.0;
  double slope_standard_error_px = 0.0;
  double spread_px = 0.0;
  double spread_standard_error_px = 0.0;
  int lines = 0;  // edge lines measured (all views)
};

struct ResponseEstimationOptions {
  // Tried in order; the first is the default, kept unless a test finds clear evidence.
  // Non-empty, each valid and resolved. Default: DefaultResponseCandidates().
  std::vector<ImageResponse> candidates = DefaultResponseCandidates();
  // Evidence the polarity test needs, in standard errors (see above); >= 0. On the 48 test
  // frames of docs/notes/issue12_response.md a wrong response (linear or Filmic images read as
  // sRGB) gives 6–9 for its first condition and 3.6–6.7 for its second; the right one up to 6.3
  // for the first (scene effects) and 2.8 for the second, 3.2 on two frames of a glossy
  // synthetic spool (the known failure).
  double min_slope_z = 3.0;
  // Evidence the consistency test needs, in standard errors of the difference; >= 0.
  double min_spread_z = 2.0;
  // Bootstrap resamples of the lines per candidate (fixed seed: deterministic); >= 10.
  int bootstrap_samples = 200;
  // Edge solves per candidate (edge.rounds replaced, no redescending rounds); >= 1. The pose of a
  // solved frame moves by hundredths of a pixel between candidates, so one re-rendered solve
  // suffices.
  int edge_rounds = 1;
  Status Validate() const;
};

struct ResponseEstimate {
  ImageResponse response;             // the best candidate
  std::vector<ResponseScore> scores;  // every candidate, in the order given
};

// Scores the candidates on the views of one frame at `rig_from_objcentre` (a solved pose: the
// edge stage searches ±edge.lines.search_px around its contour) with the edge stage of
// `problem`'s options. Errors: invalid options (kInvalidConfig); the first candidate left fewer
// than edge.min_lines lines (kInvalidInput).
StatusOr<ResponseEstimate> EstimateImageResponse(const FrameProblem& problem,
                                                 const std::vector<FrameView>& views,
                                                 const Eigen::Isometry3d& rig_from_objcentre,
                                                 const ResponseEstimationOptions& options = {});

}  // namespace bcot

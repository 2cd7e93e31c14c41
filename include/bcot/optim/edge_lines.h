// Edge lines: the image's own object edge along the contour normals, the measurement of the
// final edge-alignment stage of a frame solve (frame_problem.h, `edge`).
//
// Why. A region energy places the contour where the foreground and background colour
// posteriors cross. Where the object's rim is shaded (the surface turns away from the light
// towards the silhouette) its colour near the edge moves towards the background's, the
// crossing moves inward on that side and the pose is biased away from the dark rim (measured
// with scripts/bench_bias.sh: a key light from above puts the solved object higher than the
// truth). The edge itself does not move: the optics blur the radiance step with a symmetric
// PSF, so the centre of the blurred step (its inflection) stays at the geometric contour for
// any pair of colours on its two sides.
//
// Measurement, per line (centre c = contour point at T0, outward unit normal n, model point X):
//   profile   I(s) = linear RGB (the codes decoded by the camera's `response`: the blur acts on
//             radiance, and the inflection of a step decoded with the wrong response moves
//             towards one of its sides) at c + s·n, bilinear,
//             s = k·step_px over [−window_px, +window_px];
//   scalar    p(s) = d̂·I(s) with d the mean colour over s ∈ [−window, −1] minus that over
//             s ∈ [1, window] (the direction of largest contrast across this line), without
//             the channels that are clipped somewhere on the line (below);
//   start     μ0 = the largest |dp/ds| within |s| <= search_px;
//   fit       p(s) ≈ a + g·(s − μ0) + b·Φ(z) + k·w·(z·Φ(z) + φ(z)), z = (s − μ)/w, over
//             |s − μ0| <= fit_half_px by Levenberg-Marquardt on (a, g, b, μ, w, k): a step
//             between two linear trends with different slopes (the shaded rim inside, the
//             background outside), blurred by a Gaussian of width w (Φ, φ the normal CDF and
//             density): exact for piecewise-linear sides, so a shading ramp up to the edge does
//             not move μ (the model, its Jacobian and normal equations: edge_step_model.h);
//   variance  σ_μ² = (RSS / (m − 6))·[(JᵀJ)⁻¹]_μμ, floored at min_sigma_px².
//
// Clipping. A camera's optics blur the light before its pixels saturate, so where a channel
// of a bright surface is beyond full scale the recorded blurred step is cut off at its top
// and its centre moves towards the darker side (a lit, saturated rim is found 0.2–0.4 px
// outside the object, pulling the pose towards the light; FitEdgeAcrossTest). A channel
// whose linear value reaches clip_level at any pixel the line's samples are interpolated from
// is therefore left out of d (its step cannot be located); the line is ambiguous when the
// remaining channels have less than min_contrast.
//
// Subsampled chroma. In a JPEG with 4:2:0 or 4:2:2 chroma (chroma_sampling.h) the decoded edge
// is a sharp luma step plus a blurred chroma step whose shape depends on where the edge falls in
// the codec's 2×2 blocks; its fitted centre moves (on average 0.08–0.17 px outward on oblique
// edges between colours that differ more in hue than in brightness, up to ±0.7 px along a pixel
// axis: docs/notes/issue12_jpeg_chroma.md). The move is predicted and taken off
// (ChromaSubsamplingShift): an ideal edge (a Gaussian-blurred step between two linear colours)
// is drawn as codes on the pixel grid around the line (through the inverse response), passed
// through the codec's chroma path (SimulateChromaSubsampling) and fitted as an image line; its
// centre, width and colours beyond ±1.5 px are adjusted until its decoded fit matches the
// observed one (indirect inference: μ by secant steps, the rest by fixed-point steps, three
// simulations). The shift is its decoded fit's μ minus the same fit's μ on the drawing without
// the codec; σ_μ is divided by the decoded centre's sensitivity to the edge's position.
// Quantisation is left as noise.
//   A channel clipped on the object's side of the line (see "Clipping") is left out of the fit
// but not out of the codec: its clipped step enters the other channels through the chroma they
// share, and its shape depends on how far above full scale the light is (a lit orange surface
// with its red at 1.6× full scale, drawn at full scale, was found 0.2 px outside). On such a line
// the ideal edge is found by analysis by synthesis instead: its centre, width and the clipped
// channels' inside levels L (in [1, 16] full scales; drawn, blurred, then clipped) by
// Levenberg-Marquardt on the observed minus the decoded drawing's samples, all three channels
// within fit_half_px (forward-difference Jacobian, two rounds of at most three steps, the colours
// beyond ±1.5 px updated between them). The shift is taken as above from that edge, σ_μ left as
// fitted. A background clipped in a channel is drawn at full scale as before (modelled, it moved
// a glossy object's edges outward: edge_lines.cc, SaturatedInsideChannels).
//
// The line becomes a CorrespondenceLine with mean_px = μ and sigma_px = σ_μ, so the pose stage
// reuses CorrespondenceLineCostFunction: r = (n·(x_X(T) − x0) − μ)/σ.
//
// Rejection (counts in CorrespondenceLines::rejected_*):
//   short      the rendered mask at T0 is not inside over [−window, −1] and outside over
//              [1, window] along the line (thin part, another contour nearby);
//   off image  the window or its bilinear neighbours leave the image, or X is behind the camera;
//   ambiguous  contrast |d| below min_contrast (linear units), the fit did not converge, |μ| >
//              search_px, w outside [min_width_px, max_width_px], or the step is below
//              min_snr times the fit's residual standard deviation.
//
// Frames and units as correspondence_lines.h. Thread safety: pure functions.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/chroma_restoration.h"
#include "bcot/core/chroma_sampling.h"
#include "bcot/core/linear_rgb.h"
#include "bcot/core/status.h"
#include "bcot/optim/correspondence_lines.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/crease_contour.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct EdgeLineOptions {
  // Lines per view: one per line_spacing_px of traced contour, evenly spaced along it, at
  // most num_lines. The image carries edge evidence at every contour pixel; lines much closer
  // than a pixel share their samples through the blur and add little. spacing > 0,
  // num_lines >= 1.
  double line_spacing_px = 1.0;
  int num_lines = 1000;
  // Profile half-length (px) and sample spacing (px); window > search + fit_half is not
  // required (the fit window is clipped to the profile), step > 0, window >= 2.
  double window_px = 4.0;
  double step_px = 0.25;
  // The edge is looked for within ±search_px of the contour at T0; > 0.
  double search_px = 2.0;
  // Half-width (px) of the fit window around the start μ0; > step_px.
  double fit_half_px = 2.5;
  // Accepted range of the fitted blur width w (px); 0 < min < max.
  double min_width_px = 0.15;
  double max_width_px = 2.5;
  // Smallest colour contrast |d| across the line (linear RGB, 1 = full scale); >= 0.
  double min_contrast = 0.01;
  // Smallest step |b| in units of the fit's residual standard deviation; >= 0.
  double min_snr = 4.0;
  // Floor of σ_μ (px): model errors (mesh facets, the contour's linearisation) are not in
  // the fit's noise; > 0.
  double min_sigma_px = 0.1;
  // Linear level (1 = full scale) at or above which a channel's sample counts as clipped by
  // the sensor (see "Clipping" above); > 1 = never.
  double clip_level = 0.95;
  // With subsampled chroma, fit the level above full scale of a channel clipped on the object's
  // side, which the codec's simulation then draws, blurs and clips ("Subsampled chroma" above);
  // off: it is drawn at full scale (JPEG 4:2:0 Cycles plastic bunny, bias y cam0 / cam1 −0.072 /
  // −0.081 → −0.048 / −0.060 mm, z cam0 −0.117 → −0.070 mm; docs/notes/issue12_jpeg_chroma.md).
  bool saturated_level_fit = true;
  // How the images' 8-bit codes map to linear light: the camera's response (linear_rgb.h).
  ImageResponse response;
  // Also measure the edges along the occlusion contours inside the silhouette
  // (occlusion_contour.h), at most num_lines of them, whose window lies on the object.
  bool occlusion_contours = false;
  // Also measure the edges along the mesh's creases inside the silhouette
  // (crease_contour.h), at most num_lines of them: edges whose two faces meet at more than
  // crease_min_angle_deg (in (0, 180)), both facing the camera, with nothing else within the
  // window. On: a machined part's creases locate it better than its silhouette alone (Cycles
  // pinion with sharp edges: rotation 0.170° → 0.127°), a smooth object has few or none
  // (docs/notes/issue12_crease_contours.md).
  bool crease_contours = true;
  double crease_min_angle_deg = 60.0;  // CreaseContourOptions::min_angle_deg
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// Length (px) of the traced contours: the sum of the steps between consecutive samples of the
// same contour.
double TracedContourLengthPx(const std::vector<ContourPoint>& contour);
// The number of lines BuildEdgeLines places along `contour` (see line_spacing_px).
int NumEdgeLines(const std::vector<ContourPoint>& contour, const EdgeLineOptions& options);

// The fitted step of one profile (exposed for tests).
struct EdgeFit {
  double mean_px = 0.0;   // μ
  double sigma_px = 0.0;  // σ_μ (unfloored)
  double width_px = 0.0;  // w
  double step = 0.0;      // b
};

// Fits the blurred step to a scalar profile `values[k]` at offsets first_offset_px + k·step_px,
// in at most `max_iterations` Levenberg-Marquardt steps. Returns false when a rejection rule
// above (contrast excepted) applies or the fit has not converged.
constexpr int kEdgeFitIterations = 30;
bool FitEdgeProfile(const std::vector<double>& values, double first_offset_px,
                    const EdgeLineOptions& options, EdgeFit* fit,
                    int max_iterations = kEdgeFitIterations);

// The linear-RGB samples of one line across an edge: colors[k] at centre + (k − half)·step_px·
// normal (half = ⌊window_px / step_px⌋), the mean colours over s ∈ [−window, −1] (inside) and
// [1, window] (outside), and per channel the largest value a sample rests on (PeakLinearRgb),
// which tells a clipped channel (see "Clipping" above).
struct EdgeLineSamples {
  std::vector<Eigen::Vector3d> colors;
  Eigen::Vector3d inside = Eigen::Vector3d::Zero();
  Eigen::Vector3d outside = Eigen::Vector3d::Zero();
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
};

// The line's contrast d = inside − outside with its clipped channels (peak >= clip_level) set
// to 0: what the fit measures the edge on (see "Clipping" above).
Eigen::Vector3d UnclippedContrast(const EdgeLineSamples& samples, const EdgeLineOptions& options);

// Samples the line through `centre` along the unit `normal` of `image` (codes decoded by
// `table`); false when the window or its bilinear neighbours leave the image.
bool SampleEdgeLine(const cv::Mat3b& image, const LinearTable& table, const Eigen::Vector2d& centre,
                    const Eigen::Vector2d& normal, const EdgeLineOptions& options,
                    EdgeLineSamples* samples);

// The edge across one line (the profile, contrast direction and fit above) through `centre`
// along the unit `normal` (inside → outside) of `image` (BGR, its codes decoded by `table`, built
// from options.response by the caller once for many lines; its chroma stored with `sampling`,
// corrected for as above when subsampled): kFound and `fit` (offsets along the normal from
// centre, σ unfloored), or why not.
enum class EdgeAcross { kFound, kOffImage, kAmbiguous };
EdgeAcross FitEdgeAcross(const cv::Mat3b& image, const LinearTable& table,
                         const Eigen::Vector2d& centre, const Eigen::Vector2d& normal,
                         const EdgeLineOptions& options, EdgeFit* fit,
                         const ChromaSampling& sampling = ChromaSampling());

// What the codec's chroma sampling does to one line's fitted edge ("Subsampled chroma" above).
struct ChromaShift {
  // The decoded edge's centre minus the edge's (px): subtracted from the fitted μ.
  double shift_px = 0.0;
  // dμ_decoded / dμ_edge at the edge, in [kMinSensitivity, kMaxSensitivity]: where the edge's
  // position in the codec's blocks makes the decoded centre move slower than the edge, the
  // fitted μ says less about the edge; σ_μ is divided by it.
  double sensitivity = 1.0;
};
constexpr double kMinSensitivity = 0.25;
constexpr double kMaxSensitivity = 4.0;

// The ChromaShift of the line through `centre` along `normal` whose `samples` (SampleEdgeLine)
// were fitted as `fit`, for chroma stored with `sampling`. False when a simulated fit fails or
// the sampling is not simulated.
bool ChromaSubsamplingShift(const EdgeLineSamples& samples, const EdgeFit& fit,
                            const LinearTable& table, const Eigen::Vector2d& centre,
                            const Eigen::Vector2d& normal, const EdgeLineOptions& options,
                            const ChromaSampling& sampling, ChromaShift* shift);

// Builds the edge lines of one view at T0 (rig_from_objcentre). `silhouette` must be
// RenderSilhouette at cam_from_rig · T0 · objcentre_from_template; `sampling` is how `image`'s
// chroma was stored; `creases` (with options.crease_contours): FindCreases(caster.mesh(),
// options.crease_min_angle_deg), found here when null. Errors as BuildCorrespondenceLines.
StatusOr<CorrespondenceLines> BuildEdgeLines(const RayCaster& caster, const Camera& camera,
                                             const Eigen::Isometry3d& cam_from_rig,
                                             const Eigen::Isometry3d& rig_from_objcentre,
                                             const cv::Mat3b& image, const Silhouette& silhouette,
                                             const EdgeLineOptions& options = {},
                                             const ChromaSampling& sampling = ChromaSampling(),
                                             const std::vector<Crease>* creases = nullptr);

// The image a view's edge lines are measured on and how its chroma is to be read there.
struct EdgeImage {
  cv::Mat3b image;
  ChromaSampling sampling;
};
// With `restoration` on and `sampling` subsampled as the codec path is simulated, `image` with
// its chroma restored (RestoreSubsampledChroma) over the box of `silhouette`'s contour grown by
// the lines' window, and read as 4:4:4 there; otherwise `image` as is (not copied), its lines
// corrected for `sampling`.
EdgeImage EdgeImageOf(const cv::Mat3b& image, const ChromaSampling& sampling,
                      const ChromaRestorationOptions& restoration, const Silhouette& silhouette,
                      const EdgeLineOptions& options);

}  // namespace bcot

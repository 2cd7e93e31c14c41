// Step 3 of the quality measurement (bcot/quality/quality_report.h): the object boundary along
// each contour normal, from a foreground posterior image (and optionally the image edges).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "bcot/core/linear_rgb.h"
#include "bcot/quality/quality_options.h"
#include "bcot/render/interior_edges.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

// Boundary offsets of one contour against a P_f image. `posterior` is P_f on `roi` (image
// coordinates of its top-left pixel centre = roi.tl()); `colour` (optional, used when
// options.edge_weight > 0) the image channels on the same roi, in [0, 1]. Returns one entry
// per contour point: the signed offset t* along the outward normal (px), or NaN when no
// boundary was found.
std::vector<double> BoundaryOffsets(const std::vector<ContourPoint>& contour,
                                    const cv::Mat1f& posterior, const cv::Rect& roi,
                                    const QualityOptions& options,
                                    const std::vector<cv::Mat1f>& colour = {});

// Step 3b (options.refine_on_edges): moves each boundary found above to the centre of the
// image's own blurred step near it and gives it a standard deviation. Along the normal, the
// linear-RGB profile around the found boundary t is projected on its contrast direction (mean
// colour over [t − W, t − 1] minus that over [t + 1, t + W]) and the blurred step of
// FitEdgeProfile (bcot/optim/edge_lines.h) is fitted within ±edge_search_px of t: a colour
// posterior puts the boundary where the two sides' likelihoods cross, which a shaded rim, a
// highlight or similar colours move by a pixel or more, while the centre of the blurred step
// stays at the geometric edge. A point whose profile holds no such step (no contrast, no
// convergence, a step below edge_min_snr times the fit's noise, blur outside [0.15, 2.5] px,
// the window off the image) becomes NaN: the boundary is not visible there.
struct RefinedOffsets {
  std::vector<double> offsets;    // px, NaN where none
  std::vector<double> sigmas_px;  // standard deviation of each finite offset (px)
  int ambiguous = 0;              // points found in step 3 that the refinement discarded
};
// `linear` decodes the image's codes (the camera's response).
RefinedOffsets RefineOffsetsOnEdges(const std::vector<ContourPoint>& contour,
                                    const std::vector<double>& offsets, const cv::Mat3b& image,
                                    const LinearTable& linear, const QualityOptions& options);

// Exposure: how many of `contour`'s points show their boundary only in saturated channels. A
// channel is saturated at a point when it reaches EdgeLineOptions::clip_level (linear, `linear`
// decoding the codes) at any pixel the edge refinement of step 3b would read across the contour
// there (±(edge_search_px + EdgeLineOptions::fit_half_px) along the normal, bilinear footprints);
// the edge fits leave such a channel out. A point counts when the colour contrast across it
// reaches EdgeLineOptions::min_contrast but what the other channels keep of it does not: it has
// no measurable edge, and the pose leans on the other rims. A point whose window leaves the image
// is not counted.
int CountClippedPoints(const std::vector<ContourPoint>& contour, const cv::Mat3b& image,
                       const LinearTable& linear, const QualityOptions& options);

// Step 4b (options.interior_edges): sets to NaN each finite offset whose boundary (contour
// point + offset · normal) `interior` claims (InteriorEdges::Claims: within its tolerance of one
// of the model's interior edges projected at the same pose, and nearer to it than to the
// contour point); returns how many. Such a step is more likely that edge than the silhouette.
int DropInteriorEdgeMatches(const std::vector<ContourPoint>& contour, const InteriorEdges& interior,
                            std::vector<double>* offsets);

// Median and 90th percentile of |values| ignoring NaN; NaN when none is finite.
double AbsPercentile(const std::vector<double>& values, double fraction);

}  // namespace bcot

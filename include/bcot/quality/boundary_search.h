// Step 3 of the quality measurement (bcot/quality/quality_report.h): the object boundary along
// each contour normal, from a foreground posterior image (and optionally the image edges).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "bcot/quality/quality_options.h"
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

// Median and 90th percentile of |values| ignoring NaN; NaN when none is finite.
double AbsPercentile(const std::vector<double>& values, double fraction);

}  // namespace bcot

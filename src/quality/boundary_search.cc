#include "bcot/quality/boundary_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bcot/optim/edge_lines.h"

namespace bcot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

constexpr double kProfileStepPx = 0.25;

// Bilinear P_f at image position `p`; positions beyond the roi clamp to its border.
double SamplePosterior(const cv::Mat1f& posterior, const cv::Rect& roi, const Eigen::Vector2d& p) {
  const double x = std::clamp(p.x() - roi.x, 0.0, posterior.cols - 1.0);
  const double y = std::clamp(p.y() - roi.y, 0.0, posterior.rows - 1.0);
  const int x0 = std::min(static_cast<int>(x), posterior.cols - 2 < 0 ? 0 : posterior.cols - 2);
  const int y0 = std::min(static_cast<int>(y), posterior.rows - 2 < 0 ? 0 : posterior.rows - 2);
  const int x1 = std::min(x0 + 1, posterior.cols - 1);
  const int y1 = std::min(y0 + 1, posterior.rows - 1);
  const double ax = x - x0;
  const double ay = y - y0;
  return (1 - ay) * ((1 - ax) * posterior(y0, x0) + ax * posterior(y0, x1)) +
         ay * ((1 - ax) * posterior(y1, x0) + ax * posterior(y1, x1));
}

}  // namespace

std::vector<double> BoundaryOffsets(const std::vector<ContourPoint>& contour,
                                    const cv::Mat1f& posterior, const cv::Rect& roi,
                                    const QualityOptions& options,
                                    const std::vector<cv::Mat1f>& colour) {
  std::vector<double> offsets(contour.size(), kNaN);
  if (posterior.empty()) return offsets;
  const bool use_edges = options.edge_weight > 0 && !colour.empty();
  const int window =
      std::max(1, static_cast<int>(std::lround(options.step_window_px / kProfileStepPx)));
  const int radius = static_cast<int>(std::ceil(options.search_radius_px / kProfileStepPx));
  const int half = radius + window;
  // cumulative[c][k] = sum over the profile samples j < k at t_j = (j − half)·step of channel
  // c (0 = P_f, then the colour channels).
  const size_t channels = 1 + (use_edges ? colour.size() : 0);
  std::vector<std::vector<double>> cumulative(channels, std::vector<double>(2 * half + 2));
  std::vector<double> score(2 * radius + 1);
  for (size_t i = 0; i < contour.size(); ++i) {
    const ContourPoint& point = contour[i];
    for (size_t c = 0; c < channels; ++c) {
      const cv::Mat1f& channel = c == 0 ? posterior : colour[c - 1];
      cumulative[c][0] = 0.0;
      for (int j = 0; j <= 2 * half; ++j) {
        const double t = (j - half) * kProfileStepPx;
        cumulative[c][j + 1] =
            cumulative[c][j] + SamplePosterior(channel, roi, point.pixel + t * point.normal);
      }
    }
    int best = -1;
    for (int k = 0; k <= 2 * radius; ++k) {
      const int j = k + window;  // profile index of t_k = (k − radius)·step
      auto step = [&](size_t c) {
        const double inside = (cumulative[c][j + 1] - cumulative[c][j + 1 - window]) / window;
        const double outside = (cumulative[c][j + 1 + window] - cumulative[c][j + 1]) / window;
        return inside - outside;
      };
      score[k] = step(0);
      if (use_edges) {
        double edge = 0.0;
        for (size_t c = 1; c < channels; ++c) edge += step(c) * step(c);
        score[k] += options.edge_weight * std::sqrt(edge / (channels - 1));
      }
      if (best < 0 || score[k] > score[best]) best = k;
    }
    if (score[best] < options.min_contrast) continue;
    double refine = 0.0;
    if (best > 0 && best < 2 * radius) {
      const double a = score[best - 1], b = score[best], c = score[best + 1];
      const double denominator = a - 2 * b + c;
      if (denominator < 0) refine = std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
    }
    // The step between the sample at t_k and the next one sits half a step further out.
    offsets[i] = (best - radius + refine + 0.5) * kProfileStepPx;
  }
  return offsets;
}

namespace {

// The edge-line options of step 3b; window_px: its profile's reach from the boundary.
EdgeLineOptions RefinementEdgeOptions(const QualityOptions& options) {
  EdgeLineOptions edge;
  edge.search_px = options.edge_search_px;
  edge.min_snr = options.edge_min_snr;
  edge.window_px = edge.search_px + edge.fit_half_px;
  return edge;
}

}  // namespace

int CountClippedPoints(const std::vector<ContourPoint>& contour, const cv::Mat3b& image,
                       const LinearTable& linear, const QualityOptions& options) {
  const EdgeLineOptions edge = RefinementEdgeOptions(options);
  int clipped = 0;
  EdgeLineSamples samples;
  for (const ContourPoint& point : contour) {
    if (!SampleEdgeLine(image, linear, point.pixel, point.normal, edge, &samples)) continue;
    // A contrast across the contour that the edge fits lose to clipped channels.
    if ((samples.inside - samples.outside).norm() >= edge.min_contrast &&
        UnclippedContrast(samples, edge).norm() < edge.min_contrast) {
      ++clipped;
    }
  }
  return clipped;
}

RefinedOffsets RefineOffsetsOnEdges(const std::vector<ContourPoint>& contour,
                                    const std::vector<double>& offsets, const cv::Mat3b& image,
                                    const LinearTable& linear, const QualityOptions& options) {
  BCOT_CHECK(contour.size() == offsets.size());
  RefinedOffsets result;
  result.offsets.assign(contour.size(), kNaN);
  result.sigmas_px.assign(contour.size(), kNaN);
  const EdgeLineOptions edge = RefinementEdgeOptions(options);
  for (size_t i = 0; i < contour.size(); ++i) {
    if (!std::isfinite(offsets[i])) continue;
    const Eigen::Vector2d centre = contour[i].pixel + offsets[i] * contour[i].normal;
    EdgeFit fit;
    if (FitEdgeAcross(image, linear, centre, contour[i].normal, edge, &fit) != EdgeAcross::kFound) {
      ++result.ambiguous;
      continue;
    }
    result.offsets[i] = offsets[i] + fit.mean_px;
    result.sigmas_px[i] = fit.sigma_px;
  }
  return result;
}

int DropInteriorEdgeMatches(const std::vector<ContourPoint>& contour, const InteriorEdges& interior,
                            std::vector<double>* offsets) {
  BCOT_CHECK(offsets != nullptr && offsets->size() == contour.size());
  int dropped = 0;
  for (size_t i = 0; i < contour.size(); ++i) {
    const double offset = (*offsets)[i];
    if (!std::isfinite(offset)) continue;
    if (interior.Claims(contour[i].pixel, contour[i].pixel + offset * contour[i].normal)) {
      (*offsets)[i] = kNaN;
      ++dropped;
    }
  }
  return dropped;
}

double AbsPercentile(const std::vector<double>& values, double fraction) {
  std::vector<double> finite;
  for (double value : values) {
    if (std::isfinite(value)) finite.push_back(std::abs(value));
  }
  if (finite.empty()) return kNaN;
  std::sort(finite.begin(), finite.end());
  const double position = fraction * (finite.size() - 1);
  const size_t lower = static_cast<size_t>(std::floor(position));
  const size_t upper = std::min(lower + 1, finite.size() - 1);
  return finite[lower] + (position - lower) * (finite[upper] - finite[lower]);
}

}  // namespace bcot

#include "bcot/quality/quality_report.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/image_cache.h"
#include "bcot/optim/silhouette.h"
#include "bcot/quality/boundary_search.h"
#include "bcot/quality/rigid_motion_fit.h"
#include "bcot/render/crease_contour.h"
#include "bcot/render/interior_edges.h"
#include "bcot/render/mesh.h"

namespace bcot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Camera indices of `view_names` in the rig (all cameras when empty).
StatusOr<std::vector<int>> ViewIndices(const Rig& rig, const std::vector<std::string>& names) {
  std::vector<int> indices;
  if (names.empty()) {
    for (int i = 0; i < rig.size(); ++i) indices.push_back(i);
    return indices;
  }
  for (const std::string& name : names) {
    const int index = rig.Find(name);
    if (index < 0) return Status::InvalidConfig(fmt::format("no camera '{}' in the rig", name));
    indices.push_back(index);
  }
  return indices;
}

// A frame-view has a measurement when its statistic exists and enough contour points found a
// usable boundary (see "unverifiable" in the header).
bool IsMeasured(const ViewFrameQuality& quality, const QualityOptions& options) {
  return std::isfinite(quality.Statistic(options.statistic)) &&
         quality.found >= options.min_found_fraction * quality.points;
}

}  // namespace

std::vector<std::string> SaturationWarnings(const QualityReport& report) {
  std::vector<std::string> warnings;
  for (const ViewQualitySummary& view : report.views) {
    if (view.clipped_fraction < kSaturatedContourWarningFraction) continue;
    warnings.push_back(fmt::format(
        "{}: on {:.0f}% of the object's contour the image is saturated in every colour channel "
        "that shows the boundary, so no edge can be measured there and the poses rest on the "
        "other rims (on our renders, 28-55% of a view's contour saturated came with a bias of "
        "0.04-0.21 mm: the object off the truth the same way on every frame); lower the exposure, "
        "the gain or the light until the object and what it mirrors stay below full scale (the "
        "`clipped` column of quality.csv counts such contour points per frame; README, "
        "\"Calibrating and recording a rig\")",
        view.name, 100.0 * view.clipped_fraction));
  }
  return warnings;
}

ViewFrameQuality MeasureFrameView(const RayCaster& caster, const Camera& camera,
                                  const Eigen::Isometry3d& cam_from_object, const cv::Mat3b& image,
                                  const QualityOptions& options, const LinearTable& linear,
                                  const std::vector<Crease>& creases, uint32_t seed) {
  BCOT_CHECK(image.cols == camera.width && image.rows == camera.height);
  const Eigen::Vector3d object_centre = caster.mesh().bbox_center();
  const double object_diameter_mm = caster.mesh().diameter();
  ViewFrameQuality quality;
  const Silhouette silhouette =
      RenderSilhouetteContour(caster, camera, cam_from_object, QualityContourOptions(options));
  quality.points = static_cast<int>(silhouette.contour.size());
  if (silhouette.contour.empty()) {
    quality.median_px = quality.p90_px = quality.raw_median_px = quality.raw_p90_px = kNaN;
    quality.statistic_sigma_px = kNaN;
    quality.verifiable = false;
    return quality;
  }
  quality.clipped = CountClippedPoints(silhouette.contour, image, linear, options);
  ColorModelOptions color;
  color.bins_per_channel = options.bins_per_channel;
  color.sample_margin_px = options.color_margin_px;
  color.kind = options.color_kind;
  const std::unique_ptr<ColorModel> model = MakeColorModel(color, object_diameter_mm);
  model->Update(image, silhouette);

  double min_x = camera.width, min_y = camera.height, max_x = 0, max_y = 0;
  for (const ContourPoint& point : silhouette.contour) {
    min_x = std::min(min_x, point.pixel.x());
    min_y = std::min(min_y, point.pixel.y());
    max_x = std::max(max_x, point.pixel.x());
    max_y = std::max(max_y, point.pixel.y());
  }
  const int grow =
      static_cast<int>(std::ceil(options.search_radius_px + options.step_window_px)) + 2;
  const cv::Rect roi = cv::Rect(cv::Point(static_cast<int>(std::floor(min_x)) - grow,
                                          static_cast<int>(std::floor(min_y)) - grow),
                                cv::Point(static_cast<int>(std::ceil(max_x)) + grow + 1,
                                          static_cast<int>(std::ceil(max_y)) + grow + 1)) &
                       cv::Rect(0, 0, camera.width, camera.height);
  // The boundary search reads P_f bilinearly at positions within search_radius + step_window
  // + ⅜ px of a contour point (clamped to the roi), so from pixels within grow − 2 + ⅜ + √2 of
  // it: P_f is computed within grow + 1 of the rounded contour points only (elsewhere 0, never
  // read).
  cv::Mat1b needed = cv::Mat1b::zeros(roi.size());
  for (const ContourPoint& point : silhouette.contour) {
    cv::circle(needed,
               cv::Point(static_cast<int>(std::lround(point.pixel.x())) - roi.x,
                         static_cast<int>(std::lround(point.pixel.y())) - roi.y),
               grow + 1, cv::Scalar(255), cv::FILLED);
  }
  std::vector<Eigen::Vector2i> pixels;
  pixels.reserve(static_cast<size_t>(cv::countNonZero(needed)));
  for (int r = 0; r < roi.height; ++r) {
    for (int c = 0; c < roi.width; ++c) {
      if (needed(r, c) != 0) pixels.emplace_back(roi.x + c, roi.y + r);
    }
  }
  const std::vector<double> posteriors = model->ForegroundPosteriors(image, pixels);
  cv::Mat1f posterior = cv::Mat1f::zeros(roi.height, roi.width);
  for (size_t i = 0; i < posteriors.size(); ++i) {
    posterior(pixels[i].y() - roi.y, pixels[i].x() - roi.x) = static_cast<float>(posteriors[i]);
  }
  std::vector<cv::Mat1f> colour;
  if (options.edge_weight > 0) {
    cv::Mat colour_roi;
    image(roi).convertTo(colour_roi, CV_32FC3, 1.0 / 255.0);
    cv::split(colour_roi, colour);
  }
  std::vector<double> offsets =
      BoundaryOffsets(silhouette.contour, posterior, roi, options, colour);
  std::vector<double> sigmas;
  if (options.refine_on_edges) {
    RefinedOffsets refined =
        RefineOffsetsOnEdges(silhouette.contour, offsets, image, linear, options);
    offsets = std::move(refined.offsets);
    sigmas = std::move(refined.sigmas_px);
    quality.ambiguous = refined.ambiguous;
  }
  // The interior edges (a depth render and ray casts) only matter where a boundary was found.
  if (options.interior_edges &&
      std::any_of(offsets.begin(), offsets.end(), [](double o) { return std::isfinite(o); })) {
    const InteriorEdges interior =
        ProjectInteriorEdges(caster, camera, cam_from_object, creases, options.crease_min_angle_deg,
                             /*occlusion_contours=*/true, options.interior_edge_px);
    quality.ambiguous += DropInteriorEdgeMatches(silhouette.contour, interior, &offsets);
  }
  for (double offset : offsets) quality.found += std::isfinite(offset) ? 1 : 0;
  quality.raw_median_px = AbsPercentile(offsets, 0.5);
  quality.raw_p90_px = AbsPercentile(offsets, 0.9);
  const double fraction = options.statistic == QualityStatistic::kMedian ? 0.5 : 0.9;
  quality.statistic_sigma_px = kNaN;
  if (options.fit_rigid_motion) {
    const RigidMotionFitter fitter(silhouette.contour, camera, cam_from_object, object_centre);
    std::vector<double> weights;
    const std::vector<double> fitted =
        fitter.Fit(offsets, sigmas, options.fit_scale_px, /*multiplicity=*/{}, &weights);
    quality.median_px = AbsPercentile(fitted, 0.5);
    quality.p90_px = AbsPercentile(fitted, 0.9);
    // σ of the judged statistic: the spread of the usable points' own fit (bootstrap) and what
    // they cannot tell about the rest of the contour (prediction σ), added in quadrature. The
    // two overlap where the usable points observe every motion; there the prediction σ is
    // small beside the bootstrap's (docs/quality.md, "Small objects").
    const double prediction = fitter.PredictionSigmaPercentile(weights, fraction);
    const double bootstrap =
        options.bootstrap_resamples > 0
            ? fitter.BootstrapPercentileSigma(offsets, sigmas, options.fit_scale_px, fraction,
                                              options.bootstrap_resamples, seed)
            : 0.0;
    if (std::isfinite(prediction) && std::isfinite(bootstrap)) {
      quality.statistic_sigma_px = std::hypot(bootstrap, prediction);
    }
  } else {
    quality.median_px = quality.raw_median_px;
    quality.p90_px = quality.raw_p90_px;
  }
  // Verdict of the frame-view: a hypothesis test with the measurement's own uncertainty.
  const double statistic = quality.Statistic(options.statistic);
  const double margin =
      options.confidence_z *
      (std::isfinite(quality.statistic_sigma_px) ? quality.statistic_sigma_px : 0.0);
  const bool measurable = IsMeasured(quality, options);
  quality.bad = measurable && statistic - margin > options.threshold_px;
  quality.verifiable = measurable && (quality.bad || statistic + margin <= options.threshold_px);
  return quality;
}

namespace {

void Summarize(QualityReport* report) {
  const QualityOptions& options = report->options;
  const int num_frames = static_cast<int>(report->frames.size());
  report->views.clear();
  report->reasons.clear();
  for (size_t v = 0; v < report->view_names.size(); ++v) {
    ViewQualitySummary summary;
    summary.name = report->view_names[v];
    std::vector<double> medians;
    std::vector<std::pair<double, int>> ranked;
    int points = 0, clipped = 0;
    for (int f = 0; f < num_frames; ++f) {
      const ViewFrameQuality& q = report->frames[f][v];
      points += q.points;
      clipped += q.clipped;
      if (q.bad) ++summary.bad_frames;
      medians.push_back(q.median_px);
      if (!q.verifiable) ++summary.unverified_frames;
      // Frames without a measurement rank first among the worst (they need a look).
      if (!IsMeasured(q, options)) {
        ranked.push_back({std::numeric_limits<double>::infinity(), f});
      } else {
        const double statistic = q.Statistic(options.statistic);
        ranked.push_back({statistic, f});
        summary.worst_px = std::max(summary.worst_px, statistic);
      }
    }
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (int i = 0; i < std::min<int>(options.worst_frames, static_cast<int>(ranked.size())); ++i) {
      summary.worst_frames.push_back(ranked[i].second);
    }
    summary.median_of_medians_px = AbsPercentile(medians, 0.5);
    if (points > 0) summary.clipped_fraction = static_cast<double>(clipped) / points;
    if (num_frames > 0) {
      summary.bad_fraction = double(summary.bad_frames) / num_frames;
      summary.unverified_fraction = double(summary.unverified_frames) / num_frames;
    }
    if (summary.bad_fraction > options.allowed_bad_fraction) {
      report->reasons.push_back(fmt::format(
          "view {}: {} of {} frames ({:.0f}%) bad, {:.0f}% allowed; worst {} {:.2f} px > {} px",
          summary.name, summary.bad_frames, num_frames, 100.0 * summary.bad_fraction,
          100.0 * options.allowed_bad_fraction, QualityStatisticName(options.statistic),
          summary.worst_px, options.threshold_px));
    }
    if (summary.unverified_fraction > options.allowed_unverified_fraction) {
      const std::string coverage =
          options.min_found_fraction > 0.0
              ? fmt::format("fewer than {:.0f}% of its contour with a visible boundary, ",
                            100.0 * options.min_found_fraction)
              : "";
      report->reasons.push_back(fmt::format(
          "view {}: cannot tell on {} of {} frames ({:.0f}%, {:.0f}% allowed): object not in "
          "view, {}or {} within {}σ of {} px",
          summary.name, summary.unverified_frames, num_frames, 100.0 * summary.unverified_fraction,
          100.0 * options.allowed_unverified_fraction, coverage,
          QualityStatisticName(options.statistic), options.confidence_z, options.threshold_px));
    }
    report->views.push_back(summary);
  }
  report->accepted = report->reasons.empty();
}

}  // namespace

StatusOr<QualityReport> MeasureQuality(const Sequence& sequence,
                                       const std::vector<Eigen::Isometry3d>& rig_from_object,
                                       const std::vector<std::string>& view_names,
                                       const QualityOptions& options,
                                       const ImageResponse& response) {
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  return MeasureQuality(sequence, RayCaster(mesh), rig_from_object, view_names, options, response);
}

StatusOr<QualityReport> MeasureQuality(const Sequence& sequence, const RayCaster& caster,
                                       const std::vector<Eigen::Isometry3d>& rig_from_object,
                                       const std::vector<std::string>& view_names,
                                       const QualityOptions& options, const ImageResponse& response,
                                       DecodedImageCache* images) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  if (!response.IsValid()) {
    return Status::InvalidConfig(fmt::format("image response {} is invalid", response.Name()));
  }
  const LinearTable linear(response);
  if (static_cast<int>(rig_from_object.size()) != sequence.num_frames) {
    return Status::InvalidInput(fmt::format("{}: {} poses for {} frames", sequence.dir,
                                            rig_from_object.size(), sequence.num_frames));
  }
  BCOT_ASSIGN_OR_RETURN(const std::vector<int> indices, ViewIndices(sequence.rig, view_names));
  const Mesh& mesh = caster.mesh();
  const std::vector<Crease> creases = options.interior_edges
                                          ? FindCreases(mesh, options.crease_min_angle_deg)
                                          : std::vector<Crease>();
  QualityReport report;
  report.sequence_dir = sequence.dir;
  report.options = options;
  for (int index : indices) report.view_names.push_back(sequence.rig[index].camera.name);
  report.frames.assign(sequence.num_frames, std::vector<ViewFrameQuality>(indices.size()));
  std::vector<Status> errors(sequence.num_frames * indices.size());
  tbb::parallel_for(0, static_cast<int>(errors.size()), [&](int job) {
    const int frame = job / static_cast<int>(indices.size());
    const int view = job % static_cast<int>(indices.size());
    const RigCamera& camera = sequence.rig[indices[view]];
    const StatusOr<cv::Mat3b> image =
        ReadCameraImage(sequence.image_paths[indices[view]][frame], camera.camera, images);
    if (!image.ok()) {
      errors[job] = image.status();
      return;
    }
    report.frames[frame][view] =
        MeasureFrameView(caster, camera.camera, camera.cam_from_rig * rig_from_object[frame],
                         *image, options, linear, creases, static_cast<uint32_t>(job + 1));
  });
  for (const Status& error : errors) BCOT_RETURN_IF_ERROR(error);
  Summarize(&report);
  return report;
}

}  // namespace bcot

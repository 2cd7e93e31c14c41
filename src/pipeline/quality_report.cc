#include "bcot/pipeline/quality_report.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/html.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/yaml_util.h"
#include "bcot/optim/color_model.h"
#include "bcot/optim/silhouette.h"
#include "bcot/pipeline/annotate_options.h"
#include "bcot/render/mesh.h"

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

std::string Base64(const std::vector<unsigned char>& bytes) {
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t chunk = (uint32_t{bytes[i]} << 16) |
                           (i + 1 < bytes.size() ? uint32_t{bytes[i + 1]} << 8 : 0) |
                           (i + 2 < bytes.size() ? uint32_t{bytes[i + 2]} : 0);
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

std::string JsonNumber(double value) {
  return std::isfinite(value) ? fmt::format("{:.4f}", value) : "";
}

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

ContourOptions QualityContourOptions(const QualityOptions& options) {
  ContourOptions contour;
  contour.sample_spacing_px = options.sample_spacing_px;
  return contour;
}

// Measures one frame-view.
StatusOr<ViewFrameQuality> MeasureView(const RayCaster& caster, const Camera& camera,
                                       const Eigen::Isometry3d& cam_from_object,
                                       const std::string& image_path,
                                       const Eigen::Vector3d& object_centre,
                                       double object_diameter_mm, const QualityOptions& options) {
  const cv::Mat image = cv::imread(image_path, cv::IMREAD_COLOR);
  if (image.empty()) return Status::InvalidInput(image_path + ": cannot read the image");
  if (image.cols != camera.width || image.rows != camera.height) {
    return Status::InvalidInput(fmt::format("{}: image is {}x{}, rig.yaml says {}x{}", image_path,
                                            image.cols, image.rows, camera.width, camera.height));
  }
  ViewFrameQuality quality;
  const Silhouette silhouette =
      RenderSilhouette(caster, camera, cam_from_object, QualityContourOptions(options));
  quality.points = static_cast<int>(silhouette.contour.size());
  if (silhouette.contour.empty()) {
    quality.median_px = quality.p90_px = quality.raw_median_px = quality.raw_p90_px = kNaN;
    quality.bad = true;
    return quality;
  }
  ColorModelOptions color;
  color.bins_per_channel = options.bins_per_channel;
  color.sample_margin_px = options.color_margin_px;
  color.kind = options.color_kind;
  const std::unique_ptr<ColorModel> model = MakeColorModel(color, object_diameter_mm);
  const cv::Mat3b image3(image);
  model->Update(image3, silhouette);

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
  std::vector<Eigen::Vector2i> pixels;
  pixels.reserve(static_cast<size_t>(roi.area()));
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    for (int x = roi.x; x < roi.x + roi.width; ++x) pixels.emplace_back(x, y);
  }
  const std::vector<double> posteriors = model->ForegroundPosteriors(image3, pixels);
  cv::Mat1f posterior(roi.height, roi.width);
  for (size_t i = 0; i < posteriors.size(); ++i) {
    posterior(static_cast<int>(i) / roi.width, static_cast<int>(i) % roi.width) =
        static_cast<float>(posteriors[i]);
  }
  std::vector<cv::Mat1f> colour;
  if (options.edge_weight > 0) {
    cv::Mat colour_roi;
    image(roi).convertTo(colour_roi, CV_32FC3, 1.0 / 255.0);
    cv::split(colour_roi, colour);
  }
  const std::vector<double> offsets =
      BoundaryOffsets(silhouette.contour, posterior, roi, options, colour);
  for (double offset : offsets) quality.found += std::isfinite(offset) ? 1 : 0;
  quality.raw_median_px = AbsPercentile(offsets, 0.5);
  quality.raw_p90_px = AbsPercentile(offsets, 0.9);
  if (options.fit_rigid_motion) {
    const std::vector<double> fitted = FitRigidMotionOffsets(
        silhouette.contour, offsets, camera, cam_from_object, object_centre, options.fit_scale_px);
    quality.median_px = AbsPercentile(fitted, 0.5);
    quality.p90_px = AbsPercentile(fitted, 0.9);
  } else {
    quality.median_px = quality.raw_median_px;
    quality.p90_px = quality.raw_p90_px;
  }
  const double statistic = quality.Statistic(options.statistic);
  quality.bad = !std::isfinite(statistic) || statistic > options.threshold_px ||
                quality.found < options.min_found_fraction * quality.points;
  return quality;
}

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
    int unverifiable = 0;
    for (int f = 0; f < num_frames; ++f) {
      const ViewFrameQuality& q = report->frames[f][v];
      if (q.bad) ++summary.bad_frames;
      medians.push_back(q.median_px);
      const double statistic = q.Statistic(options.statistic);
      if (!std::isfinite(statistic) || q.found < options.min_found_fraction * q.points) {
        ++unverifiable;
        ranked.push_back({std::numeric_limits<double>::infinity(), f});
      } else {
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
    summary.bad_fraction = num_frames > 0 ? double(summary.bad_frames) / num_frames : 0.0;
    if (summary.bad_fraction > options.allowed_bad_fraction) {
      std::string reason =
          fmt::format("view {}: {} of {} frames ({:.0f}%) bad, {:.0f}% allowed", summary.name,
                      summary.bad_frames, num_frames, 100.0 * summary.bad_fraction,
                      100.0 * options.allowed_bad_fraction);
      if (summary.bad_frames > unverifiable) {
        reason +=
            fmt::format("; worst {} {:.2f} px > {} px", QualityStatisticName(options.statistic),
                        summary.worst_px, options.threshold_px);
      }
      if (unverifiable > 0) {
        reason += fmt::format("; {} frames without a visible boundary", unverifiable);
      }
      report->reasons.push_back(reason);
    }
    report->views.push_back(summary);
  }
  report->accepted = report->reasons.empty();
}

// The SVG plot of one view's median and p90 over time, with the threshold line.
std::string ViewPlot(const QualityReport& report, size_t v) {
  const int width = 760, height = 180, left = 40, bottom = 20;
  const int num_frames = static_cast<int>(report.frames.size());
  double y_max = report.options.threshold_px * 1.5;
  for (const auto& frame : report.frames) {
    if (std::isfinite(frame[v].p90_px)) y_max = std::max(y_max, frame[v].p90_px * 1.05);
  }
  auto x_of = [&](int f) {
    return left + (width - left - 10) * (num_frames > 1 ? double(f) / (num_frames - 1) : 0.5);
  };
  auto y_of = [&](double value) { return (height - bottom) * (1.0 - value / y_max) + 5; };
  auto polyline = [&](bool p90, const char* color) {
    std::string points;
    for (int f = 0; f < num_frames; ++f) {
      const double value = p90 ? report.frames[f][v].p90_px : report.frames[f][v].median_px;
      if (std::isfinite(value)) points += fmt::format("{:.1f},{:.1f} ", x_of(f), y_of(value));
    }
    return fmt::format("<polyline fill='none' stroke='{}' stroke-width='1.5' points='{}'/>", color,
                       points);
  };
  std::string svg = fmt::format(
      "<svg xmlns='http://www.w3.org/2000/svg' width='{}' height='{}' class='plot'>"
      "<rect x='{}' y='5' width='{}' height='{}' fill='#fafafa' stroke='#ccc'/>",
      width, height + 10, left, width - left - 10, height - bottom);
  for (double tick : {0.0, report.options.threshold_px, y_max}) {
    svg += fmt::format("<text x='2' y='{:.1f}' font-size='10'>{:.1f}</text>", y_of(tick) + 3, tick);
  }
  svg += fmt::format(
      "<line x1='{}' x2='{}' y1='{:.1f}' y2='{:.1f}' stroke='#d33' stroke-dasharray='4 3'/>", left,
      width - 10, y_of(report.options.threshold_px), y_of(report.options.threshold_px));
  for (int f = 0; f < num_frames; ++f) {
    if (report.frames[f][v].bad) {
      svg += fmt::format("<rect x='{:.1f}' y='5' width='2' height='{}' fill='#f4b4b4'/>",
                         x_of(f) - 1, height - bottom);
    }
  }
  svg += polyline(false, "#2a6");
  svg += polyline(true, "#36c");
  svg += fmt::format("<text x='{}' y='{}' font-size='10'>frame 0</text>", left, height + 8);
  svg += fmt::format("<text x='{}' y='{}' font-size='10' text-anchor='end'>frame {}</text>",
                     width - 10, height + 8, std::max(0, num_frames - 1));
  return svg + "</svg>";
}

// A PNG thumbnail (base64) of one frame-view with the annotated contour drawn.
StatusOr<std::string> Thumbnail(const RayCaster& caster, const Camera& camera,
                                const Eigen::Isometry3d& cam_from_object,
                                const std::string& image_path, const QualityOptions& options) {
  cv::Mat image = cv::imread(image_path, cv::IMREAD_COLOR);
  if (image.empty()) return Status::InvalidInput(image_path + ": cannot read the image");
  const std::vector<ContourPoint> contour =
      caster.ExtractContour(camera, cam_from_object, QualityContourOptions(options));
  cv::Rect box(0, 0, image.cols, image.rows);
  if (!contour.empty()) {
    cv::Rect2d bounds(contour[0].pixel.x(), contour[0].pixel.y(), 0, 0);
    for (const ContourPoint& point : contour) {
      bounds |= cv::Rect2d(point.pixel.x(), point.pixel.y(), 1, 1);
    }
    const double margin = 0.15 * std::max(bounds.width, bounds.height) + 8;
    box = cv::Rect(cv::Point(int(bounds.x - margin), int(bounds.y - margin)),
                   cv::Point(int(bounds.br().x + margin), int(bounds.br().y + margin))) &
          cv::Rect(0, 0, image.cols, image.rows);
  }
  const double scale =
      std::min(4.0, double(options.thumbnail_px) / std::max(box.width, box.height));
  cv::Mat crop;
  cv::resize(image(box), crop, cv::Size(), scale, scale, cv::INTER_AREA);
  constexpr int kShift = 4;  // fixed-point bits for sub-pixel drawing
  std::vector<std::vector<cv::Point>> polylines;
  int current = -1;
  for (const ContourPoint& point : contour) {
    if (point.contour_id != current) {
      polylines.emplace_back();
      current = point.contour_id;
    }
    const Eigen::Vector2d p = (point.pixel - Eigen::Vector2d(box.x, box.y)) * scale;
    polylines.back().emplace_back(int(std::lround(p.x() * (1 << kShift))),
                                  int(std::lround(p.y() * (1 << kShift))));
  }
  cv::polylines(crop, polylines, true, cv::Scalar(0, 255, 0), 1, cv::LINE_AA, kShift);
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", crop, png)) return Status::Internal("cannot encode a PNG thumbnail");
  return Base64(png);
}

}  // namespace

const char* QualityStatisticName(QualityStatistic statistic) {
  return statistic == QualityStatistic::kMedian ? "median" : "p90";
}

Status QualityOptions::Validate() const {
  std::vector<std::string> violations;
  auto require = [&](bool ok, const std::string& field, double value, const char* rule) {
    if (!ok) violations.push_back(fmt::format("{} = {}, {}", field, value, rule));
  };
  require(threshold_px > 0, "threshold_px", threshold_px, "must be > 0");
  require(allowed_bad_fraction >= 0 && allowed_bad_fraction <= 1, "allowed_bad_fraction",
          allowed_bad_fraction, "must be in [0, 1]");
  require(search_radius_px > 0, "search_radius_px", search_radius_px, "must be > 0");
  require(step_window_px > 0, "step_window_px", step_window_px, "must be > 0");
  require(edge_weight >= 0 && edge_weight <= 10, "edge_weight", edge_weight, "must be in [0, 10]");
  require(min_contrast > 0 && min_contrast < 1 + edge_weight, "min_contrast", min_contrast,
          "must be in (0, 1 + edge_weight)");
  require(min_found_fraction >= 0 && min_found_fraction <= 1, "min_found_fraction",
          min_found_fraction, "must be in [0, 1]");
  require(sample_spacing_px > 0, "sample_spacing_px", sample_spacing_px, "must be > 0");
  require(bins_per_channel >= 1 && bins_per_channel <= 256 && 256 % bins_per_channel == 0,
          "bins_per_channel", bins_per_channel, "must divide 256");
  require(color_margin_px >= 0 && color_margin_px < search_radius_px, "color_margin_px",
          color_margin_px, "must be in [0, search_radius_px)");
  require(fit_scale_px > 0, "fit_scale_px", fit_scale_px, "must be > 0");
  require(worst_frames >= 0, "worst_frames", worst_frames, "must be >= 0");
  require(thumbnail_px >= 32, "thumbnail_px", thumbnail_px, "must be >= 32");
  if (violations.empty()) return Status::Ok();
  std::string message = "quality: " + violations[0];
  for (size_t i = 1; i < violations.size(); ++i) message += "; " + violations[i];
  return Status::InvalidConfig(message);
}

Status ParseQualityOptions(const YAML::Node& node, const std::string& source_name,
                           QualityOptions* options) {
  if (!node.IsDefined() || node.IsNull()) return Status::Ok();
  YamlMap map(node, source_name, "quality", StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(map.Check());
  QualityOptions& o = *options;
  BCOT_RETURN_IF_ERROR(map.GetOptional("threshold_px", &o.threshold_px));
  int statistic = o.statistic == QualityStatistic::kMedian ? 0 : 1;
  BCOT_RETURN_IF_ERROR(map.GetOptionalChoice("statistic", {"median", "p90"}, &statistic));
  o.statistic = statistic == 0 ? QualityStatistic::kMedian : QualityStatistic::kP90;
  BCOT_RETURN_IF_ERROR(map.GetOptional("allowed_bad_fraction", &o.allowed_bad_fraction));
  BCOT_RETURN_IF_ERROR(map.GetOptional("search_radius_px", &o.search_radius_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("step_window_px", &o.step_window_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("edge_weight", &o.edge_weight));
  BCOT_RETURN_IF_ERROR(map.GetOptional("min_contrast", &o.min_contrast));
  BCOT_RETURN_IF_ERROR(map.GetOptional("min_found_fraction", &o.min_found_fraction));
  BCOT_RETURN_IF_ERROR(map.GetOptional("sample_spacing_px", &o.sample_spacing_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("bins_per_channel", &o.bins_per_channel));
  int color_kind = o.color_kind == ColorModelKind::kGlobal ? 0 : 1;
  BCOT_RETURN_IF_ERROR(map.GetOptionalChoice("color_kind", {"global", "local"}, &color_kind));
  o.color_kind = color_kind == 0 ? ColorModelKind::kGlobal : ColorModelKind::kLocal;
  BCOT_RETURN_IF_ERROR(map.GetOptional("color_margin_px", &o.color_margin_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("fit_rigid_motion", &o.fit_rigid_motion));
  BCOT_RETURN_IF_ERROR(map.GetOptional("fit_scale_px", &o.fit_scale_px));
  BCOT_RETURN_IF_ERROR(map.GetOptional("worst_frames", &o.worst_frames));
  BCOT_RETURN_IF_ERROR(map.GetOptional("thumbnail_px", &o.thumbnail_px));
  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());
  const Status status = o.Validate();
  if (status.ok()) return status;
  // Name the line of the first offending key: "file:line: quality.key = value, rule; ...".
  std::string message;
  std::string rest = status.message().substr(std::string("quality: ").size());
  while (!rest.empty()) {
    const size_t end = rest.find("; ");
    const std::string piece = rest.substr(0, end);
    rest = end == std::string::npos ? "" : rest.substr(end + 2);
    const std::string key = piece.substr(0, piece.find(" = "));
    message +=
        (message.empty() ? "" : "; ") + fmt::format("{}: quality.{}", map.Location(key), piece);
  }
  return Status::InvalidConfig(message);
}

std::string FormatQualityOptions(const QualityOptions& o) {
  std::string y = "quality:\n";
  auto line = [&y](const char* key, const std::string& value) {
    y += fmt::format("  {}: {}\n", key, value);
  };
  line("threshold_px", fmt::format("{}", o.threshold_px));
  line("statistic", QualityStatisticName(o.statistic));
  line("allowed_bad_fraction", fmt::format("{}", o.allowed_bad_fraction));
  line("search_radius_px", fmt::format("{}", o.search_radius_px));
  line("step_window_px", fmt::format("{}", o.step_window_px));
  line("edge_weight", fmt::format("{}", o.edge_weight));
  line("min_contrast", fmt::format("{}", o.min_contrast));
  line("min_found_fraction", fmt::format("{}", o.min_found_fraction));
  line("sample_spacing_px", fmt::format("{}", o.sample_spacing_px));
  line("bins_per_channel", fmt::format("{}", o.bins_per_channel));
  line("color_kind", o.color_kind == ColorModelKind::kLocal ? "local" : "global");
  line("color_margin_px", fmt::format("{}", o.color_margin_px));
  line("fit_rigid_motion", o.fit_rigid_motion ? "true" : "false");
  line("fit_scale_px", fmt::format("{}", o.fit_scale_px));
  line("worst_frames", fmt::format("{}", o.worst_frames));
  line("thumbnail_px", fmt::format("{}", o.thumbnail_px));
  return y;
}

std::vector<double> FitRigidMotionOffsets(const std::vector<ContourPoint>& contour,
                                          const std::vector<double>& offsets, const Camera& camera,
                                          const Eigen::Isometry3d& cam_from_object,
                                          const Eigen::Vector3d& object_centre, double scale_px) {
  BCOT_CHECK(contour.size() == offsets.size());
  BCOT_CHECK(scale_px > 0.0);
  // Row i of A: ∂(n_i · x_i)/∂δ for δ = (ω, v), the motion X ↦ X + ω × (X − c) + v of the
  // camera-frame points about the object centre c (rotation about c keeps ω and v apart).
  const Eigen::Vector3d centre = cam_from_object * object_centre;
  Eigen::Matrix<double, Eigen::Dynamic, 6> rows(contour.size(), 6);
  for (size_t i = 0; i < contour.size(); ++i) {
    const Eigen::Vector3d point = cam_from_object * contour[i].point_in_object;
    Eigen::Matrix<double, 2, 3> d_pixel_d_point;
    camera.Project(point, &d_pixel_d_point);
    const Eigen::RowVector3d n_d = contour[i].normal.transpose() * d_pixel_d_point;
    rows.block<1, 3>(i, 0) = (point - centre).cross(n_d.transpose()).transpose();  // n_dᵀ(ω × r)
    rows.block<1, 3>(i, 3) = n_d;
  }
  // IRLS: Huber weights (convex, so the start does not matter), then Tukey's biweight, which
  // gives outliers (clutter edges, blur, highlights found instead of the boundary) no weight.
  Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
  int used = 0;
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    used = 0;
    for (size_t i = 0; i < contour.size(); ++i) {
      if (!std::isfinite(offsets[i])) continue;
      const double residual = std::abs(offsets[i] - rows.row(i).dot(delta));
      double weight;
      if (iteration < 5) {
        weight = residual <= scale_px ? 1.0 : scale_px / residual;
      } else {
        const double u = residual / (3.0 * scale_px);
        weight = u < 1.0 ? (1 - u * u) * (1 - u * u) : 0.0;
      }
      if (weight <= 0) continue;
      normal += weight * rows.row(i).transpose() * rows.row(i);
      rhs += weight * offsets[i] * rows.row(i).transpose();
      ++used;
    }
    if (used < 6) break;
    // Directions the contour does not observe (depth, rotations that slide the contour along
    // itself) are damped to zero; they move no contour point, so the fitted offsets ignore them.
    normal.diagonal().array() += 1e-9 * normal.trace() + 1e-12;
    delta = normal.ldlt().solve(rhs);
  }
  std::vector<double> fitted(contour.size(), kNaN);
  if (used < 6) return fitted;
  for (size_t i = 0; i < contour.size(); ++i) fitted[i] = rows.row(i).dot(delta);
  return fitted;
}

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

StatusOr<QualityReport> MeasureQuality(const Sequence& sequence,
                                       const std::vector<Eigen::Isometry3d>& rig_from_object,
                                       const std::vector<std::string>& view_names,
                                       const QualityOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  if (static_cast<int>(rig_from_object.size()) != sequence.num_frames) {
    return Status::InvalidInput(fmt::format("{}: {} poses for {} frames", sequence.dir,
                                            rig_from_object.size(), sequence.num_frames));
  }
  BCOT_ASSIGN_OR_RETURN(const std::vector<int> indices, ViewIndices(sequence.rig, view_names));
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  const RayCaster caster(mesh);
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
    StatusOr<ViewFrameQuality> quality = MeasureView(
        caster, camera.camera, camera.cam_from_rig * rig_from_object[frame],
        sequence.image_paths[indices[view]][frame], mesh.bbox_center(), mesh.diameter(), options);
    if (quality.ok()) {
      report.frames[frame][view] = *quality;
    } else {
      errors[job] = quality.status();
    }
  });
  for (const Status& error : errors) BCOT_RETURN_IF_ERROR(error);
  Summarize(&report);
  return report;
}

std::string QualityJson(const QualityReport& report) {
  nlohmann::ordered_json json;
  json["sequence"] = report.sequence_dir;
  json["verdict"] = report.accepted ? "accepted" : "rejected";
  json["reasons"] = report.reasons;
  json["options"] = {{"threshold_px", report.options.threshold_px},
                     {"statistic", QualityStatisticName(report.options.statistic)},
                     {"allowed_bad_fraction", report.options.allowed_bad_fraction},
                     {"search_radius_px", report.options.search_radius_px},
                     {"fit_rigid_motion", report.options.fit_rigid_motion}};
  json["num_frames"] = report.frames.size();
  double worst = 0.0;
  for (const ViewQualitySummary& view : report.views) {
    worst = std::max(worst, view.worst_px);
    json["views"].push_back({{"name", view.name},
                             {"bad_frames", view.bad_frames},
                             {"bad_fraction", view.bad_fraction},
                             {"median_of_medians_px", view.median_of_medians_px},
                             {"worst_px", view.worst_px},
                             {"worst_frames", view.worst_frames}});
  }
  json["worst_px"] = worst;
  for (size_t f = 0; f < report.frames.size(); ++f) {
    nlohmann::ordered_json frame = {{"frame", f}};
    for (size_t v = 0; v < report.view_names.size(); ++v) {
      const ViewFrameQuality& q = report.frames[f][v];
      frame["views"].push_back({{"median_px", q.median_px},
                                {"p90_px", q.p90_px},
                                {"raw_median_px", q.raw_median_px},
                                {"raw_p90_px", q.raw_p90_px},
                                {"points", q.points},
                                {"found", q.found},
                                {"bad", q.bad}});
    }
    json["frames"].push_back(frame);
  }
  return json.dump(1) + "\n";
}

std::string QualityCsv(const QualityReport& report) {
  std::string csv = "frame,view,median_px,p90_px,raw_median_px,raw_p90_px,points,found,bad\n";
  for (size_t f = 0; f < report.frames.size(); ++f) {
    for (size_t v = 0; v < report.view_names.size(); ++v) {
      const ViewFrameQuality& q = report.frames[f][v];
      csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", f, report.view_names[v],
                         JsonNumber(q.median_px), JsonNumber(q.p90_px), JsonNumber(q.raw_median_px),
                         JsonNumber(q.raw_p90_px), q.points, q.found, q.bad ? 1 : 0);
    }
  }
  return csv;
}

StatusOr<std::string> QualityHtml(const QualityReport& report, const Sequence& sequence,
                                  const std::vector<Eigen::Isometry3d>& rig_from_object) {
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  const RayCaster caster(mesh);
  std::string html = fmt::format(
      "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
      "<title>bcot quality: {0}</title><style>"
      "body{{font-family:sans-serif;margin:20px;color:#222}}"
      ".accepted{{background:#dfd;border:1px solid #6a6}}.rejected{{background:#fdd;"
      "border:1px solid #c66}}.verdict{{padding:10px;margin:10px 0}}"
      "figure{{display:inline-block;margin:6px}}figcaption{{font-size:12px}}"
      "table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:3px 8px}}"
      "</style></head><body>\n<h1>Quality report</h1><p>Sequence: <code>{0}</code>, {1} frames, "
      "views: {2}</p>\n",
      HtmlEscape(report.sequence_dir), report.frames.size(), report.view_names.size());
  html += fmt::format("<div class='verdict {0}' id='verdict'><b>{0}</b>",
                      report.accepted ? "accepted" : "rejected");
  html += fmt::format(
      " — a frame-view is bad when its {} reprojection error exceeds {} px (or its boundary "
      "is not visible on {:.0f}% of the contour); a view may be bad on {:.0f}% of frames.",
      QualityStatisticName(report.options.statistic), report.options.threshold_px,
      100.0 * (1.0 - report.options.min_found_fraction),
      100.0 * report.options.allowed_bad_fraction);
  if (report.options.fit_rigid_motion) {
    html +=
        " The reprojection error of a contour point is the offset that the rigid motion fitted "
        "(robustly) to all boundary offsets of the frame-view produces there, so boundaries found "
        "on clutter, highlights or blurred edges at single points do not count as pose error.";
  }
  if (!report.reasons.empty()) {
    html += "<ul>";
    for (const std::string& reason : report.reasons) html += "<li>" + HtmlEscape(reason) + "</li>";
    html += "</ul>";
  }
  html +=
      "</div>\n<table><tr><th>view</th><th>bad frames</th><th>median of medians (px)</th>"
      "<th>worst (px)</th></tr>";
  for (const ViewQualitySummary& view : report.views) {
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{:.2f}</td><td>{:.2f}</td></tr>",
                        HtmlEscape(view.name), view.bad_frames, view.median_of_medians_px,
                        view.worst_px);
  }
  html += "</table>\n";
  for (size_t v = 0; v < report.view_names.size(); ++v) {
    const int rig_index = sequence.rig.Find(report.view_names[v]);
    if (rig_index < 0) {
      return Status::InvalidInput(
          fmt::format("{}: no camera '{}' in the rig", sequence.dir, report.view_names[v]));
    }
    const RigCamera& camera = sequence.rig[rig_index];
    html += fmt::format(
        "<h2>View {}</h2><p>Reprojection error over time: <span style='color:#2a6'>median</span>, "
        "<span style='color:#36c'>p90</span>, threshold dashed, bad frames shaded.</p>\n{}\n"
        "<div class='worst'>",
        HtmlEscape(report.view_names[v]), ViewPlot(report, v));
    for (int frame : report.views[v].worst_frames) {
      BCOT_ASSIGN_OR_RETURN(
          const std::string png,
          Thumbnail(caster, camera.camera, camera.cam_from_rig * rig_from_object[frame],
                    sequence.image_paths[rig_index][frame], report.options));
      const ViewFrameQuality& q = report.frames[frame][v];
      const std::string raw =
          report.options.fit_rigid_motion
              ? fmt::format(" (raw boundary offsets: median {:.2f} px, p90 {:.2f} px)",
                            q.raw_median_px, q.raw_p90_px)
              : "";
      html += fmt::format(
          "<figure><img alt='frame {0}' src='data:image/png;base64,{1}'><figcaption>frame {0}: "
          "median {2:.2f} px, p90 {3:.2f} px{4}, boundary found on {5}/{6}{7}</figcaption>"
          "</figure>",
          frame, png, q.median_px, q.p90_px, raw, q.found, q.points, q.bad ? " — bad" : "");
    }
    html += "</div>\n";
  }
  html +=
      "<script>document.body.setAttribute('data-report-ready', 'yes');</script>\n</body></html>\n";
  return html;
}

StatusOr<QualityReport> WriteQualityReport(const std::string& out_dir, const Sequence& sequence,
                                           const std::vector<Eigen::Isometry3d>& rig_from_object,
                                           const std::vector<std::string>& view_names,
                                           const QualityOptions& options) {
  BCOT_ASSIGN_OR_RETURN(QualityReport report,
                        MeasureQuality(sequence, rig_from_object, view_names, options));
  BCOT_ASSIGN_OR_RETURN(const std::string html, QualityHtml(report, sequence, rig_from_object));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(out_dir + "/quality.json", QualityJson(report)));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(out_dir + "/quality.csv", QualityCsv(report)));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(out_dir + "/report.html", html));
  return report;
}

StatusOr<QualityReport> RegenerateQualityReport(const std::string& annotation_dir,
                                                const std::string& sequence_dir,
                                                const std::vector<std::string>& overrides) {
  const std::string config_path = annotation_dir + "/config.resolved.yaml";
  BCOT_ASSIGN_OR_RETURN(const std::string config_text, ReadTextFile(config_path));
  std::string recorded_dir;
  for (const std::string& line : SplitLines(config_text)) {
    if (line.rfind("# sequence: ", 0) == 0) recorded_dir = line.substr(12);
  }
  const std::string dir = sequence_dir.empty() ? recorded_dir : sequence_dir;
  if (dir.empty()) {
    return Status::InvalidInput(config_path + ": no '# sequence:' line; pass --sequence");
  }
  BCOT_ASSIGN_OR_RETURN(const AnnotateOptions options, ReadAnnotateOptions(config_path, overrides));
  BCOT_ASSIGN_OR_RETURN(const Sequence sequence, LoadSequence(dir, /*require_init_pose=*/false));
  BCOT_ASSIGN_OR_RETURN(const std::vector<Eigen::Isometry3d> rig_from_object,
                        ReadPoseFile(annotation_dir + "/rig_from_object.txt"));
  return WriteQualityReport(annotation_dir, sequence, rig_from_object, options.views.cameras,
                            options.quality);
}

StatusOr<QualityVerdict> ReadQualityVerdict(const std::string& annotation_dir) {
  const std::string path = annotation_dir + "/quality.json";
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded() || !json.is_object() || !json.contains("verdict")) {
    return Status::InvalidInput(path + ": not a bcot quality.json");
  }
  QualityVerdict verdict;
  verdict.accepted = json.value("verdict", "") == "accepted";
  if (json.contains("reasons") && json["reasons"].is_array()) {
    for (const auto& reason : json["reasons"]) {
      if (reason.is_string()) verdict.reasons.push_back(reason.get<std::string>());
    }
  }
  verdict.worst_px = json.value("worst_px", 0.0);
  verdict.frames = json.value("num_frames", 0);
  return verdict;
}

}  // namespace bcot

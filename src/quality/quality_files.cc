#include "bcot/quality/quality_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/html.h"
#include "bcot/core/image_io.h"
#include "bcot/render/contour_drawing.h"
#include "bcot/render/mesh.h"

namespace bcot {
namespace {

std::string JsonNumber(double value) {
  return std::isfinite(value) ? fmt::format("{:.4f}", value) : "";
}

// The SVG plot of one view's median and p90 over time, with the threshold line.
// The step between labelled frame ticks: 1, 2 or 5 × 10^k, the smallest giving at most ten.
int FrameTickStep(int num_frames) {
  for (int scale = 1;; scale *= 10) {
    for (int factor : {1, 2, 5}) {
      if (num_frames <= 10 * factor * scale) return factor * scale;
    }
  }
}

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
    const ViewFrameQuality& q = report.frames[f][v];
    if (q.bad || !q.verifiable) {
      svg += fmt::format(
          "<rect x='{:.1f}' y='5' width='2' height='{}' fill='{}'><title>frame {}: "
          "{}</title></rect>",
          x_of(f) - 1, height - bottom, q.bad ? "#f4b4b4" : "#c8c8c8", f,
          q.bad ? fmt::format("bad, p90 {:.2f} px", q.p90_px) : std::string("cannot tell"));
    }
  }
  svg += polyline(false, "#2a6");
  svg += polyline(true, "#36c");
  // Frame ticks at a round step (1, 2 or 5 × 10^k, about ten of them), labelled by frame index.
  const int step = FrameTickStep(num_frames);
  for (int f = 0; f < num_frames; f += step) {
    svg += fmt::format(
        "<line x1='{0:.1f}' x2='{0:.1f}' y1='{1}' y2='{2}' stroke='#888'/>"
        "<text x='{0:.1f}' y='{3}' font-size='10' text-anchor='middle'>{4}</text>",
        x_of(f), height - bottom + 5, height - bottom + 9, height + 8, f);
  }
  svg += fmt::format("<text x='{}' y='{}' font-size='10' text-anchor='end'>frame</text>", left - 4,
                     height + 8);
  return svg + "</svg>";
}

// "3, 7–9, 12": frame indices (sorted) as ranges.
std::string FrameRanges(const std::vector<int>& frames) {
  std::string text;
  for (size_t i = 0; i < frames.size();) {
    size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    text += (text.empty() ? "" : ", ") +
            (j == i ? std::to_string(frames[i]) : fmt::format("{}–{}", frames[i], frames[j]));
    i = j + 1;
  }
  return text;
}

// `path` as one shell word: as it is when it holds only safe characters, else single-quoted.
std::string ShellWord(const std::string& path) {
  const bool safe = !path.empty() && std::all_of(path.begin(), path.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("_./+-=:,@%", c) != nullptr;
  });
  if (safe) return path;
  std::string quoted = "'";
  for (char c : path) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// The command that opens the annotation in `bcot review` at its first bad frame (else frame 0).
std::string ReviewCommand(const QualityReport& report, const std::string& annotation_dir) {
  int first_bad = -1;
  for (size_t f = 0; f < report.frames.size() && first_bad < 0; ++f) {
    for (const ViewFrameQuality& q : report.frames[f]) {
      if (q.bad) first_bad = static_cast<int>(f);
    }
  }
  const std::string command =
      fmt::format("bcot review {} --annotation {} --frame {}", ShellWord(report.sequence_dir),
                  ShellWord(std::filesystem::absolute(annotation_dir).lexically_normal().string()),
                  std::max(first_bad, 0));
  return fmt::format(
      "<p class='review-command'>Every view side by side at any frame, with the contour, zoom and "
      "the error timeline (<code>--frame N</code> opens frame N{}):<br><code>{}</code></p>\n",
      first_bad >= 0 ? "; this command opens the first bad frame" : "", HtmlEscape(command));
}

// The frames of view `v` that are bad, and those that cannot be told, as lines for the report.
std::string BadFrameList(const QualityReport& report, size_t v) {
  std::vector<int> bad, unverified;
  for (size_t f = 0; f < report.frames.size(); ++f) {
    const ViewFrameQuality& q = report.frames[f][v];
    if (q.bad) bad.push_back(static_cast<int>(f));
    if (!q.bad && !q.verifiable) unverified.push_back(static_cast<int>(f));
  }
  return fmt::format("<p class='bad-frames'>Bad frames ({}): {}<br>Cannot tell ({}): {}</p>\n",
                     bad.size(), bad.empty() ? "none" : FrameRanges(bad), unverified.size(),
                     unverified.empty() ? "none" : FrameRanges(unverified));
}

// A PNG thumbnail (base64) of one frame-view with the annotated contour drawn.
StatusOr<std::string> Thumbnail(const RayCaster& caster, const Camera& camera,
                                const Eigen::Isometry3d& cam_from_object,
                                const std::string& image_path, const QualityOptions& options) {
  BCOT_ASSIGN_OR_RETURN(const cv::Mat3b image, ReadCameraImage(image_path, camera));
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
  DrawContour(contour, cv::Scalar(0, 255, 0), &crop, Eigen::Vector2d(box.x, box.y), scale);
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", crop, png)) return Status::Internal("cannot encode a PNG thumbnail");
  return Base64(png);
}

}  // namespace

std::string QualityJson(const QualityReport& report) {
  nlohmann::ordered_json json;
  json["bcot_version"] = report.provenance.bcot_version;
  json["created_utc"] = report.provenance.created_utc;
  json["config_hash"] = report.provenance.config_hash;
  json["sequence"] = report.sequence_dir;
  json["verdict"] = report.accepted ? "accepted" : "rejected";
  json["reasons"] = report.reasons;
  json["options"] = {{"threshold_px", report.options.threshold_px},
                     {"statistic", QualityStatisticName(report.options.statistic)},
                     {"allowed_bad_fraction", report.options.allowed_bad_fraction},
                     {"min_found_fraction", report.options.min_found_fraction},
                     {"allowed_unverified_fraction", report.options.allowed_unverified_fraction},
                     {"search_radius_px", report.options.search_radius_px},
                     {"refine_on_edges", report.options.refine_on_edges},
                     {"fit_rigid_motion", report.options.fit_rigid_motion}};
  json["num_frames"] = report.frames.size();
  for (const ViewQualitySummary& view : report.views) {
    json["views"].push_back({{"name", view.name},
                             {"bad_frames", view.bad_frames},
                             {"bad_fraction", view.bad_fraction},
                             {"unverified_frames", view.unverified_frames},
                             {"unverified_fraction", view.unverified_fraction},
                             {"median_of_medians_px", view.median_of_medians_px},
                             {"worst_px", view.worst_px},
                             {"worst_frames", view.worst_frames},
                             {"clipped_fraction", view.clipped_fraction}});
  }
  const QualityVerdict verdict = VerdictOf(report);
  json["worst_px"] = verdict.worst_px;
  json["bad_frame_views"] = verdict.bad_frame_views;
  json["unverified_frame_views"] = verdict.unverified_frame_views;
  for (size_t f = 0; f < report.frames.size(); ++f) {
    nlohmann::ordered_json frame = {{"frame", f}};
    for (size_t v = 0; v < report.view_names.size(); ++v) {
      const ViewFrameQuality& q = report.frames[f][v];
      frame["views"].push_back({{"median_px", q.median_px},
                                {"p90_px", q.p90_px},
                                {"raw_median_px", q.raw_median_px},
                                {"raw_p90_px", q.raw_p90_px},
                                {"statistic_sigma_px", q.statistic_sigma_px},
                                {"points", q.points},
                                {"found", q.found},
                                {"ambiguous", q.ambiguous},
                                {"clipped", q.clipped},
                                {"verifiable", q.verifiable},
                                {"bad", q.bad}});
    }
    json["frames"].push_back(frame);
  }
  return json.dump(1) + "\n";
}

std::string QualityCsv(const QualityReport& report) {
  std::string csv =
      "frame,view,median_px,p90_px,raw_median_px,raw_p90_px,points,found,bad,statistic_sigma_px,"
      "ambiguous,verifiable,clipped\n";
  for (size_t f = 0; f < report.frames.size(); ++f) {
    for (size_t v = 0; v < report.view_names.size(); ++v) {
      const ViewFrameQuality& q = report.frames[f][v];
      csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", f, report.view_names[v],
                         JsonNumber(q.median_px), JsonNumber(q.p90_px), JsonNumber(q.raw_median_px),
                         JsonNumber(q.raw_p90_px), q.points, q.found, q.bad ? 1 : 0,
                         JsonNumber(q.statistic_sigma_px), q.ambiguous, q.verifiable ? 1 : 0,
                         q.clipped);
    }
  }
  return csv;
}

StatusOr<std::string> QualityHtml(const QualityReport& report, const Sequence& sequence,
                                  const RayCaster& caster,
                                  const std::vector<Eigen::Isometry3d>& rig_from_object,
                                  const std::string& annotation_dir) {
  std::string html = fmt::format(
      "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
      "<title>bcot quality: {0}</title><style>"
      "body{{font-family:sans-serif;margin:20px;color:#222}}"
      ".accepted{{background:#dfd;border:1px solid #6a6}}.rejected{{background:#fdd;"
      "border:1px solid #c66}}.verdict{{padding:10px;margin:10px 0}}"
      "figure{{display:inline-block;margin:6px}}figcaption{{font-size:12px}}"
      "table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:3px 8px}}"
      "</style></head><body>\n<h1>Quality report</h1><p>Sequence: <code>{0}</code>, {1} frames, "
      "views: {2}</p>\n<p class='provenance'><small>{3}</small></p>\n",
      HtmlEscape(report.sequence_dir), report.frames.size(), report.view_names.size(),
      HtmlEscape(FormatProvenance(report.provenance)));
  html += fmt::format("<div class='verdict {0}' id='verdict'><b>{0}</b>",
                      report.accepted ? "accepted" : "rejected");
  const std::string coverage =
      report.options.min_found_fraction > 0.0
          ? fmt::format(", its boundary is not visible on more than {:.0f}% of the contour",
                        100.0 * (1.0 - report.options.min_found_fraction))
          : "";
  html += fmt::format(
      " — a frame-view is bad when its {0} reprojection error exceeds {1} px by more than "
      "{2}σ, and cannot be told (grey) when the object is not in view{3} or the {0} is within "
      "{2}σ of {1} px (σ: the spread of the boundary offsets, and what the visible boundary "
      "leaves unconstrained of the rest of the contour); a view may be bad on {4:.0f}% and "
      "unverifiable on {5:.0f}% of frames.",
      QualityStatisticName(report.options.statistic), report.options.threshold_px,
      report.options.confidence_z, coverage, 100.0 * report.options.allowed_bad_fraction,
      100.0 * report.options.allowed_unverified_fraction);
  if (report.options.refine_on_edges) {
    html +=
        " Each boundary is the centre of the image's blurred step near the colour posterior's "
        "boundary; points without a clean step are not used.";
  }
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
      "</div>\n<table><tr><th>view</th><th>bad frames</th><th>cannot tell</th>"
      "<th>median of medians (px)</th><th>worst (px)</th><th>contour saturated</th></tr>";
  for (const ViewQualitySummary& view : report.views) {
    html += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.2f}</td><td>{:.2f}</td><td>{:.0f}%</td></tr>",
        HtmlEscape(view.name), view.bad_frames, view.unverified_frames, view.median_of_medians_px,
        view.worst_px, 100.0 * view.clipped_fraction);
  }
  html += "</table>\n";
  const std::vector<std::string> saturation = SaturationWarnings(report);
  if (!saturation.empty()) {
    html += "<ul class='saturation'>";
    for (const std::string& warning : saturation) html += "<li>" + HtmlEscape(warning) + "</li>";
    html += "</ul>\n";
  }
  html += ReviewCommand(report, annotation_dir);
  for (size_t v = 0; v < report.view_names.size(); ++v) {
    const int rig_index = sequence.rig.Find(report.view_names[v]);
    if (rig_index < 0) {
      return Status::InvalidInput(
          fmt::format("{}: no camera '{}' in the rig", sequence.dir, report.view_names[v]));
    }
    const RigCamera& camera = sequence.rig[rig_index];
    html += fmt::format(
        "<h2>View {}</h2><p>Reprojection error over time: <span style='color:#2a6'>median</span>, "
        "<span style='color:#36c'>p90</span>, threshold dashed, bad frames shaded red, frames "
        "that cannot be told grey (hover for the frame).</p>\n{}\n{}<div class='worst'>",
        HtmlEscape(report.view_names[v]), ViewPlot(report, v), BadFrameList(report, v));
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
          "median {2:.2f} px, p90 {3:.2f} px{4}{5}, boundary found on {6}/{7}{8}</figcaption>"
          "</figure>",
          frame, png, q.median_px, q.p90_px,
          std::isfinite(q.statistic_sigma_px) ? fmt::format(" (± {:.2f} px)", q.statistic_sigma_px)
                                              : "",
          raw, q.found, q.points, q.bad ? " — bad" : (!q.verifiable ? " — cannot tell" : ""));
    }
    html += "</div>\n";
  }
  html +=
      "<script>document.body.setAttribute('data-report-ready', 'yes');</script>\n</body></html>\n";
  return html;
}

Status WriteQualityFiles(const std::string& out_dir, const QualityReport& report,
                         const Sequence& sequence, const RayCaster& caster,
                         const std::vector<Eigen::Isometry3d>& rig_from_object) {
  BCOT_ASSIGN_OR_RETURN(const std::string html,
                        QualityHtml(report, sequence, caster, rig_from_object, out_dir));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(out_dir + "/quality.json", QualityJson(report)));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(out_dir + "/quality.csv", QualityCsv(report)));
  return WriteFileAtomic(out_dir + "/report.html", html);
}

QualityVerdict VerdictOf(const QualityReport& report) {
  QualityVerdict verdict;
  verdict.accepted = report.accepted;
  verdict.reasons = report.reasons;
  for (const ViewQualitySummary& view : report.views) {
    verdict.worst_px = std::max(verdict.worst_px, view.worst_px);
    verdict.bad_frame_views += view.bad_frames;
    verdict.unverified_frame_views += view.unverified_frames;
  }
  verdict.frames = static_cast<int>(report.frames.size());
  return verdict;
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
  verdict.bad_frame_views = json.value("bad_frame_views", 0);
  verdict.unverified_frame_views = json.value("unverified_frame_views", 0);
  return verdict;
}

}  // namespace bcot

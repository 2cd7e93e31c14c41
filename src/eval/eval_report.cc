#include "bcot/eval/eval_report.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/html.h"
#include "bcot/core/version.h"

namespace bcot {
namespace {

EvalGroup MakeGroup(const std::string& name, const std::vector<const SequenceResult*>& results,
                    const CurveOptions& curve) {
  EvalGroup group;
  group.name = name;
  group.num_sequences = static_cast<int>(results.size());
  std::vector<ScoredFrame> frames;
  for (const SequenceResult* result : results) {
    frames.insert(frames.end(), result->frames.begin(), result->frames.end());
  }
  group.summary = Summarize(frames, curve);
  return group;
}

std::vector<EvalGroup> GroupBy(const std::vector<SequenceResult>& results, bool by_scene,
                               const CurveOptions& curve) {
  std::map<std::string, std::vector<const SequenceResult*>> groups;
  for (const SequenceResult& result : results) {
    groups[by_scene ? result.scene : result.object].push_back(&result);
  }
  std::vector<EvalGroup> out;
  for (const auto& [name, members] : groups) out.push_back(MakeGroup(name, members, curve));
  return out;
}

std::string Fixed1(double value) {
  return std::isfinite(value) ? fmt::format("{:.1f}", value) : "–";
}
std::string Full(double value) { return std::isfinite(value) ? fmt::format("{}", value) : ""; }

// Markdown table cells must not break the table.
std::string MarkdownCell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += "\\";
    out += c;
  }
  return out;
}

std::string CsvCell(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

nlohmann::json Number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json GroupJson(const EvalGroup& group) {
  const MetricSummary& s = group.summary;
  nlohmann::json metrics = nlohmann::json::object();
  for (int i = 0; i < kNumMetricColumns; ++i) metrics[kMetricColumnNames[i]] = Number(s.columns[i]);
  nlohmann::json curve_success = nlohmann::json::array();
  for (double v : s.curve_success_percent) curve_success.push_back(Number(v));
  return {
      {"name", group.name},
      {"sequences", group.num_sequences},
      {"frames", s.num_frames},
      {"lost", s.num_lost},
      {"metrics", metrics},
      {"add_auc", Number(s.add_auc)},
      {"add_curve", {{"threshold_d", s.curve_thresholds_d}, {"success_percent", curve_success}}}};
}

void AppendMarkdownTable(const std::string& heading, const std::vector<const EvalGroup*>& groups,
                         std::string* out) {
  *out += "\n## " + heading + "\n\n| " + heading.substr(heading.rfind(' ') + 1) + " |";
  for (const char* name : kMetricColumnNames) *out += fmt::format(" {} |", name);
  *out += " ADD AUC | Frames | Lost |\n|---|";
  for (int i = 0; i < kNumMetricColumns + 3; ++i) *out += "---|";
  *out += "\n";
  for (const EvalGroup* group : groups) {
    const MetricSummary& s = group->summary;
    *out += "| " + MarkdownCell(group->name) + " |";
    for (double value : s.columns) *out += " " + Fixed1(value) + " |";
    *out += fmt::format(" {} | {} | {} |\n", Fixed1(s.add_auc), s.num_frames, s.num_lost);
  }
}

std::vector<const EvalGroup*> Pointers(const std::vector<EvalGroup>& groups) {
  std::vector<const EvalGroup*> out;
  for (const EvalGroup& group : groups) out.push_back(&group);
  return out;
}

}  // namespace

EvalReport BuildEvalReport(const std::vector<SequenceResult>& results, const std::string& mode,
                           const CurveOptions& curve) {
  EvalReport report;
  report.mode = mode;
  std::vector<const SequenceResult*> all;
  for (const SequenceResult& result : results) all.push_back(&result);
  report.overall = MakeGroup("all", all, curve);
  report.per_scene = GroupBy(results, /*by_scene=*/true, curve);
  report.per_object = GroupBy(results, /*by_scene=*/false, curve);
  return report;
}

std::string FormatReportMarkdown(const EvalReport& report) {
  const MetricSummary& s = report.overall.summary;
  std::string out = fmt::format(
      "# bcot eval ({}): {} sequences, {} scored frames, {} lost (5°/5 cm)\n\n"
      "Success rates in % of frames (a frame fails a threshold when its error is greater); "
      "d = longest bounding-box side; ADD AUC over thresholds 0..{}d.\n",
      report.mode, report.overall.num_sequences, s.num_frames, s.num_lost,
      s.curve_thresholds_d.empty() ? 0.0 : s.curve_thresholds_d.back());
  AppendMarkdownTable("All", {&report.overall}, &out);
  AppendMarkdownTable("Per scene", Pointers(report.per_scene), &out);
  AppendMarkdownTable("Per object", Pointers(report.per_object), &out);
  return out;
}

std::string FormatReportCsv(const EvalReport& report) {
  std::string out = "kind,name,sequences,frames,lost";
  for (const char* name : kMetricColumnNames) out += std::string(",") + name;
  out += ",ADD AUC\n";
  auto row = [&out](const std::string& kind, const EvalGroup& group) {
    const MetricSummary& s = group.summary;
    out += fmt::format("{},{},{},{},{}", kind, CsvCell(group.name), group.num_sequences,
                       s.num_frames, s.num_lost);
    for (double value : s.columns) out += "," + Full(value);
    out += "," + Full(s.add_auc) + "\n";
  };
  row("all", report.overall);
  for (const EvalGroup& group : report.per_scene) row("scene", group);
  for (const EvalGroup& group : report.per_object) row("object", group);
  return out;
}

std::string FormatReportJson(const EvalReport& report) {
  nlohmann::json scenes = nlohmann::json::array();
  for (const EvalGroup& group : report.per_scene) scenes.push_back(GroupJson(group));
  nlohmann::json objects = nlohmann::json::array();
  for (const EvalGroup& group : report.per_object) objects.push_back(GroupJson(group));
  nlohmann::json root = {{"mode", report.mode},           {"bcot_version", BcotVersion()},
                         {"columns", kMetricColumnNames}, {"all", GroupJson(report.overall)},
                         {"per_scene", scenes},           {"per_object", objects}};
  return root.dump(2) + "\n";
}

std::string FormatSuccessCurveSvg(const EvalReport& report) {
  constexpr double kWidth = 640, kHeight = 420;
  constexpr double kLeft = 60, kRight = 200, kTop = 30, kBottom = 50;
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  const std::vector<double>& thresholds = report.overall.summary.curve_thresholds_d;
  const double x_max = thresholds.empty() || thresholds.back() <= 0 ? 1.0 : thresholds.back();
  auto x_of = [&](double t) { return kLeft + plot_w * t / x_max; };
  auto y_of = [&](double percent) { return kTop + plot_h * (1.0 - percent / 100.0); };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"12\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"18\" font-size=\"14\">ADD success rate ({3})</text>\n",
      kWidth, kHeight, kLeft, HtmlEscape(report.mode));
  for (int i = 0; i <= 5; ++i) {  // grid and tick labels
    const double t = x_max * i / 5.0, p = 20.0 * i;
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
        "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:g}</text>\n",
        x_of(t), kTop, kTop + plot_h, kTop + plot_h + 16, t);
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>\n",
        kLeft, y_of(p), kLeft + plot_w, kLeft - 6, y_of(p) + 4, p);
  }
  svg += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n"
      "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">ADD threshold (× d)</text>\n"
      "<text x=\"16\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {})\">"
      "success rate (%)</text>\n",
      kLeft, kTop, plot_w, plot_h, kLeft + plot_w / 2, kHeight - 12, kTop + plot_h / 2,
      kTop + plot_h / 2);

  static constexpr const char* kColors[] = {"#000000", "#1f77b4", "#ff7f0e", "#2ca02c",
                                            "#d62728", "#9467bd", "#8c564b", "#e377c2",
                                            "#7f7f7f", "#bcbd22", "#17becf"};
  std::vector<const EvalGroup*> curves = {&report.overall};
  for (const EvalGroup& group : report.per_object) curves.push_back(&group);
  for (size_t c = 0; c < curves.size(); ++c) {
    const MetricSummary& s = curves[c]->summary;
    const char* color = kColors[c % (sizeof(kColors) / sizeof(kColors[0]))];
    std::string points;
    for (size_t k = 0; k < s.curve_thresholds_d.size(); ++k) {
      if (!std::isfinite(s.curve_success_percent[k])) continue;
      points += fmt::format("{:.2f},{:.2f} ", x_of(s.curve_thresholds_d[k]),
                            y_of(s.curve_success_percent[k]));
    }
    svg +=
        fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" points=\"{}\"/>\n",
                    color, c == 0 ? 2.5 : 1.2, points);
    const double legend_y = kTop + 10 + 16.0 * c;
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"{3}\" "
        "stroke-width=\"2\"/><text x=\"{4}\" y=\"{5:.1f}\">{6} (AUC {7})</text>\n",
        kLeft + plot_w + 10, legend_y, kLeft + plot_w + 30, color, kLeft + plot_w + 36,
        legend_y + 4, HtmlEscape(curves[c]->name), Fixed1(s.add_auc));
  }
  svg += "</svg>\n";
  return svg;
}

Status WriteEvalReport(const EvalReport& report, const std::string& out_dir) {
  const std::filesystem::path dir(out_dir);
  BCOT_RETURN_IF_ERROR(WriteFileAtomic((dir / "eval.md").string(), FormatReportMarkdown(report)));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic((dir / "eval.csv").string(), FormatReportCsv(report)));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic((dir / "eval.json").string(), FormatReportJson(report)));
  return WriteFileAtomic((dir / "add_curve.svg").string(), FormatSuccessCurveSvg(report));
}

}  // namespace bcot

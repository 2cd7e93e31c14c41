// The report of `bcot eval`: pooled metrics (metrics.h) over all sequences, per-scene and
// per-object breakdowns, and their renderings: a Markdown table in the column order of the
// paper's Table 6, CSV, JSON and the ADD success curves as a self-contained SVG plot.
#pragma once

#include <string>
#include <vector>

#include "bcot/core/status.h"
#include "bcot/eval/evaluator.h"
#include "bcot/eval/metrics.h"

namespace bcot {

struct EvalGroup {
  std::string name;  // scene or object name; "all" for the pooled row
  int num_sequences = 0;
  MetricSummary summary;
};

struct EvalReport {
  std::string mode;  // "offline" or "online"
  EvalGroup overall;
  std::vector<EvalGroup> per_scene;   // sorted by name
  std::vector<EvalGroup> per_object;  // sorted by name
};

EvalReport BuildEvalReport(const std::vector<SequenceResult>& results, const std::string& mode,
                           const CurveOptions& curve = {});

// Percentages with one decimal as in the paper, times with one decimal, "–" for unknown.
std::string FormatReportMarkdown(const EvalReport& report);
// One row per group: kind (all/scene/object), name, sequences, frames, lost, the ten Table 6
// columns, ADD AUC; full precision, empty cell for unknown values.
std::string FormatReportCsv(const EvalReport& report);
// Everything including the curves; unknown values are null.
std::string FormatReportJson(const EvalReport& report);
// ADD success rate (%) over the threshold (in units of d): the pooled curve and one per
// object, legend with each AUC.
std::string FormatSuccessCurveSvg(const EvalReport& report);

// Writes eval.md, eval.csv, eval.json and add_curve.svg into `out_dir` (atomically).
Status WriteEvalReport(const EvalReport& report, const std::string& out_dir);

}  // namespace bcot

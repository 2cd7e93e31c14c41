// The report files of a quality measurement (quality.json, quality.csv, report.html; see
// bcot/quality/quality_report.h) and the verdict read back from quality.json.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/quality/quality_report.h"

namespace bcot {

std::string QualityJson(const QualityReport& report);
std::string QualityCsv(const QualityReport& report);
// report.html; reads the worst frames' images and draws the contour of the annotated pose.
StatusOr<std::string> QualityHtml(const QualityReport& report, const Sequence& sequence,
                                  const std::vector<Eigen::Isometry3d>& rig_from_object);

// Measures and writes quality.json, quality.csv and report.html into `out_dir`.
StatusOr<QualityReport> WriteQualityReport(const std::string& out_dir, const Sequence& sequence,
                                           const std::vector<Eigen::Isometry3d>& rig_from_object,
                                           const std::vector<std::string>& view_names,
                                           const QualityOptions& options);

// The verdict stored in `<annotation dir>/quality.json`: "accepted" / "rejected", the reasons
// and the worst statistic; for summaries over a batch.
struct QualityVerdict {
  bool accepted = false;
  std::vector<std::string> reasons;
  double worst_px = 0.0;
  int frames = 0;
};
StatusOr<QualityVerdict> ReadQualityVerdict(const std::string& annotation_dir);

}  // namespace bcot

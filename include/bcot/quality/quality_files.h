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
// report.html; reads the worst frames' images and draws the contour of the annotated pose
// (`caster` holds the sequence's mesh). `annotation_dir` is where the report is written: the
// page gives the `bcot review` command that opens this annotation at a frame.
StatusOr<std::string> QualityHtml(const QualityReport& report, const Sequence& sequence,
                                  const RayCaster& caster,
                                  const std::vector<Eigen::Isometry3d>& rig_from_object,
                                  const std::string& annotation_dir);

// Writes quality.json, quality.csv and report.html of `report` into `out_dir`, atomically.
Status WriteQualityFiles(const std::string& out_dir, const QualityReport& report,
                         const Sequence& sequence, const RayCaster& caster,
                         const std::vector<Eigen::Isometry3d>& rig_from_object);

// The verdict of a sequence: accepted or rejected, the reasons and the worst statistic; for
// the command line and summaries over a batch.
struct QualityVerdict {
  bool accepted = false;
  std::vector<std::string> reasons;
  double worst_px = 0.0;
  int frames = 0;
  int bad_frame_views = 0;         // frame-views measured above the threshold
  int unverified_frame_views = 0;  // frame-views that cannot be told (see quality_report.h)
};
// The verdict of a measurement in memory.
QualityVerdict VerdictOf(const QualityReport& report);
// The verdict stored in quality.json (for annotations a run did not redo).
StatusOr<QualityVerdict> ReadQualityVerdict(const std::string& annotation_dir);

}  // namespace bcot

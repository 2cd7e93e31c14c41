// The files of one annotation directory that `bcot review` shows (annotator.h lists them):
// rig_from_object.txt (the poses, required), quality.json (the reprojection-error timeline,
// optional) and frames.csv (the solver's diagnostics per frame, optional). Everything is read
// and validated once, at start-up; the server only looks things up afterwards.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "bcot/core/status.h"

namespace bcot {

// The reprojection error per view and frame of quality.json.
struct QualityTimeline {
  double threshold_px = 0.0;
  std::string statistic;  // "median" or "p90": the statistic judged against threshold_px
  std::vector<std::string> view_names;
  // [view][frame]: the judged statistic (px; NaN when it could not be measured), whether the
  // frame-view is bad, and whether it could be told at all.
  std::vector<std::vector<double>> error_px;
  std::vector<std::vector<bool>> bad;
  std::vector<std::vector<bool>> verifiable;

  // Frames that are bad in at least one view, ascending.
  std::vector<int> BadFrames() const;
};

// frames.csv as a table of strings: one row per frame, in frame order.
struct FrameDiagnostics {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
};

struct ReviewAnnotation {
  std::string dir;
  std::vector<Eigen::Isometry3d> rig_from_object;  // one per frame of the sequence
  std::optional<QualityTimeline> quality;          // absent without quality.json
  std::optional<FrameDiagnostics> diagnostics;     // absent without frames.csv
};

// `json` is the text of quality.json (`path` names it in errors); it must cover `num_frames`.
StatusOr<QualityTimeline> ParseQualityTimeline(const std::string& json, const std::string& path,
                                               int num_frames);
// `csv` is the text of frames.csv: a header with a `frame` column first, then the rows of frames
// 0..num_frames-1 in order, each as wide as the header.
StatusOr<FrameDiagnostics> ParseFrameDiagnostics(const std::string& csv, const std::string& path,
                                                 int num_frames);
// Reads the annotation in `dir` of a sequence of `num_frames` frames.
StatusOr<ReviewAnnotation> LoadReviewAnnotation(const std::string& dir, int num_frames);

}  // namespace bcot

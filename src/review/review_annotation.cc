#include "bcot/review/review_annotation.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"

namespace bcot {
namespace {

using nlohmann::json;

// Splits one CSV line at commas (frames.csv has no quoted fields).
std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> fields(1);
  for (char c : line) {
    if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// One view of one frame of quality.json into `timeline` at [v][f].
void ReadFrameView(const json& view, const std::string& statistic_key, size_t v, size_t f,
                   QualityTimeline* timeline) {
  const json& value = view.at(statistic_key);
  timeline->error_px[v][f] =
      value.is_number() ? value.get<double>() : std::numeric_limits<double>::quiet_NaN();
  timeline->bad[v][f] = view.at("bad").get<bool>();
  timeline->verifiable[v][f] = view.at("verifiable").get<bool>();
}

StatusOr<QualityTimeline> TimelineOf(const json& root, const std::string& path, int num_frames) {
  QualityTimeline timeline;
  timeline.threshold_px = root.at("options").at("threshold_px").get<double>();
  timeline.statistic = root.at("options").at("statistic").get<std::string>();
  if (timeline.statistic != "median" && timeline.statistic != "p90") {
    return Status::InvalidInput(fmt::format("{}: options.statistic = '{}', must be median or p90",
                                            path, timeline.statistic));
  }
  for (const json& view : root.at("views")) {
    timeline.view_names.push_back(view.at("name").get<std::string>());
  }
  const json& frames = root.at("frames");
  if (!frames.is_array() || static_cast<int>(frames.size()) != num_frames) {
    return Status::InvalidInput(fmt::format("{}: {} frames, the sequence has {}", path,
                                            frames.is_array() ? frames.size() : 0, num_frames));
  }
  const size_t num_views = timeline.view_names.size();
  timeline.error_px.assign(num_views, std::vector<double>(num_frames));
  timeline.bad.assign(num_views, std::vector<bool>(num_frames));
  timeline.verifiable.assign(num_views, std::vector<bool>(num_frames));
  const std::string key = timeline.statistic + "_px";
  for (size_t f = 0; f < frames.size(); ++f) {
    const json& views = frames[f].at("views");
    if (views.size() != num_views) {
      return Status::InvalidInput(
          fmt::format("{}: frame {} has {} views, expected {}", path, f, views.size(), num_views));
    }
    for (size_t v = 0; v < num_views; ++v) {
      ReadFrameView(views[v], key, v, f, &timeline);
    }
  }
  return timeline;
}

}  // namespace

std::vector<int> QualityTimeline::BadFrames() const {
  std::vector<int> frames;
  const size_t num_frames = bad.empty() ? 0 : bad[0].size();
  for (size_t f = 0; f < num_frames; ++f) {
    for (const std::vector<bool>& view : bad) {
      if (view[f]) {
        frames.push_back(static_cast<int>(f));
        break;
      }
    }
  }
  return frames;
}

StatusOr<QualityTimeline> ParseQualityTimeline(const std::string& text, const std::string& path,
                                               int num_frames) {
  const json root = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded()) return Status::InvalidInput(path + ": not valid JSON");
  try {
    return TimelineOf(root, path, num_frames);
  } catch (const json::exception& error) {
    return Status::InvalidInput(
        fmt::format("{}: not a bcot quality.json ({})", path, error.what()));
  }
}

StatusOr<FrameDiagnostics> ParseFrameDiagnostics(const std::string& csv, const std::string& path,
                                                 int num_frames) {
  const std::vector<std::string> lines = SplitLines(csv);
  if (lines.empty()) return Status::InvalidInput(path + ": empty, a header line expected");
  FrameDiagnostics diagnostics;
  diagnostics.columns = SplitCsvLine(lines[0]);
  if (diagnostics.columns[0] != "frame") {
    return Status::InvalidInput(path + ":1: the first column must be 'frame'");
  }
  if (static_cast<int>(lines.size()) - 1 != num_frames) {
    return Status::InvalidInput(fmt::format("{}: {} frame rows, the sequence has {} frames", path,
                                            lines.size() - 1, num_frames));
  }
  for (size_t i = 1; i < lines.size(); ++i) {
    std::vector<std::string> row = SplitCsvLine(lines[i]);
    if (row.size() != diagnostics.columns.size() || row[0] != std::to_string(i - 1)) {
      return Status::InvalidInput(fmt::format("{}:{}: expected frame {} with {} fields", path,
                                              i + 1, i - 1, diagnostics.columns.size()));
    }
    diagnostics.rows.push_back(std::move(row));
  }
  return diagnostics;
}

StatusOr<ReviewAnnotation> LoadReviewAnnotation(const std::string& dir, int num_frames) {
  ReviewAnnotation annotation;
  annotation.dir = dir;
  const std::string poses_path = dir + "/rig_from_object.txt";
  BCOT_ASSIGN_OR_RETURN(annotation.rig_from_object, ReadPoseFile(poses_path));
  if (static_cast<int>(annotation.rig_from_object.size()) != num_frames) {
    return Status::InvalidInput(fmt::format("{}: {} poses, the sequence has {} frames", poses_path,
                                            annotation.rig_from_object.size(), num_frames));
  }
  const std::string quality_path = dir + "/quality.json";
  if (std::filesystem::exists(quality_path)) {
    BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(quality_path));
    BCOT_ASSIGN_OR_RETURN(annotation.quality, ParseQualityTimeline(text, quality_path, num_frames));
  }
  const std::string frames_path = dir + "/frames.csv";
  if (std::filesystem::exists(frames_path)) {
    BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(frames_path));
    BCOT_ASSIGN_OR_RETURN(annotation.diagnostics,
                          ParseFrameDiagnostics(text, frames_path, num_frames));
  }
  return annotation;
}

}  // namespace bcot

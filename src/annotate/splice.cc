#include "bcot/annotate/splice.h"

#include <fmt/format.h>

#include <filesystem>
#include <vector>

#include "bcot/annotate/done_file.h"
#include "bcot/core/annotation_poses.h"
#include "bcot/core/file_util.h"
#include "bcot/core/image_cache.h"
#include "bcot/quality/quality_files.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"

namespace bcot {
namespace {

// frames.csv as its header and one row per frame; trailing blank lines dropped.
std::vector<std::string> CsvLines(const std::string& text) {
  std::vector<std::string> lines = SplitLines(text);
  while (!lines.empty() && TrimWhitespace(lines.back()).empty()) lines.pop_back();
  return lines;
}

// Frames whose row's termination (second column) is not a usable one.
int FailedFrames(const std::vector<std::string>& csv_lines) {
  int failed = 0;
  for (size_t i = 1; i < csv_lines.size(); ++i) {
    const std::vector<std::string> fields = SplitTokens(csv_lines[i], ",");
    const bool usable =
        fields.size() > 1 && (fields[1] == FrameTerminationName(FrameTermination::kConverged) ||
                              fields[1] == FrameTerminationName(FrameTermination::kMaxRounds));
    if (!usable) ++failed;
  }
  return failed;
}

}  // namespace

StatusOr<FrameSpan> ParseFrameRange(const std::string& text, int num_frames) {
  const size_t colon = text.find(':');
  int64_t first = 0;
  int64_t last = 0;
  if (colon == std::string::npos || !ParseInt64(text.substr(0, colon), &first) ||
      !ParseInt64(text.substr(colon + 1), &last)) {
    return Status::InvalidConfig(
        fmt::format("--frames {}: expected A:B, two frame indices (inclusive)", text));
  }
  if (first < 0 || last < first || last >= num_frames) {
    return Status::InvalidConfig(
        fmt::format("--frames {}: must satisfy 0 <= A <= B <= {} (the sequence's last frame)", text,
                    num_frames - 1));
  }
  FrameSpan span;
  span.first = static_cast<int>(first);
  span.end = static_cast<int>(last) + 1;
  return span;
}

StatusOr<AnnotationOutcome> SpliceFrames(const std::string& sequence_dir,
                                         const std::string& out_dir, const AnnotateOptions& options,
                                         const AnnotateInputs& inputs,
                                         const AnnotateProgress& progress) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_ASSIGN_OR_RETURN(
      const Sequence sequence,
      LoadSequenceToAnnotate(std::filesystem::absolute(sequence_dir).lexically_normal().string(),
                             inputs, /*require_anchor=*/false));
  BCOT_ASSIGN_OR_RETURN(FrameSpan span, ParseFrameRange(inputs.frames, sequence.num_frames));
  const StatusOr<DoneRecord> done = ReadDoneFile(out_dir);
  if (!done.ok()) {
    return Status::NotFound(fmt::format(
        "{}: --frames re-annotates frames of a finished annotation (one holding DONE): {}", out_dir,
        done.status().message()));
  }
  const std::string config_hash = AnnotateConfigHash(options);
  if (done->config_hash != config_hash) {
    return Status::InvalidConfig(fmt::format(
        "{}/DONE: made with other options (config hash {}, these give {}); --frames needs the "
        "options of its config.resolved.yaml (pass it with --config)",
        out_dir, done->config_hash, config_hash));
  }
  BCOT_ASSIGN_OR_RETURN(span.existing_rig_from_object, ReadAnnotationPoses(out_dir));
  if (static_cast<int>(span.existing_rig_from_object.size()) != sequence.num_frames) {
    return Status::InvalidInput(
        fmt::format("{}/{}: {} poses for the {} frames of {}", out_dir, kRigFromObjectFileName,
                    span.existing_rig_from_object.size(), sequence.num_frames, sequence.dir));
  }
  const std::string csv_path = out_dir + "/frames.csv";
  BCOT_ASSIGN_OR_RETURN(const std::string old_csv, ReadTextFile(csv_path));
  std::vector<std::string> csv_lines = CsvLines(old_csv);
  if (static_cast<int>(csv_lines.size()) != sequence.num_frames + 1) {
    return Status::InvalidInput(fmt::format("{}: {} rows for {} frames", csv_path,
                                            csv_lines.size() - 1, sequence.num_frames));
  }
  BCOT_ASSIGN_OR_RETURN(const std::string input_hash, SequenceInputHash(sequence));
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  const RayCaster caster(mesh);
  // The frames are decoded with the response of the run being spliced into.
  BCOT_ASSIGN_OR_RETURN(const ImageResponseRecord image_response,
                        RecordedImageResponse(out_dir, options.tracker.frame.edge.lines.response));
  AnnotateOptions resolved = options;
  resolved.tracker.frame.edge.lines.response = image_response.response;
  // The quality check reads the range's frames again (and the others once).
  DecodedImageCache images(inputs.image_cache_bytes());
  BCOT_ASSIGN_OR_RETURN(const SequenceAnnotation range,
                        AnnotateFrames(sequence, caster, resolved, span, progress, {}, &images));

  // Splice in memory, measure, then replace the files with DONE last.
  std::vector<Eigen::Isometry3d> rig_from_object = span.existing_rig_from_object;
  const std::vector<std::string> range_csv = CsvLines(FormatFramesCsv(range));
  if (range_csv.front() != csv_lines.front()) {
    return Status::InvalidInput(fmt::format(
        "{}:1: the header differs from this run's ('{}'); the annotation used other cameras",
        csv_path, range_csv.front()));
  }
  for (int i = 0; i < span.end - span.first; ++i) {
    rig_from_object[span.first + i] = range.rig_from_object[i];
    csv_lines[1 + span.first + i] = range_csv[1 + i];
  }
  BCOT_ASSIGN_OR_RETURN(const QualityReport quality,
                        MeasureQuality(sequence, caster, rig_from_object, range.view_names,
                                       options.quality, image_response.response, &images));
  SequenceAnnotation whole;  // what WriteAnnotation needs besides frames.csv
  whole.rig_from_object = rig_from_object;
  whole.image_response = image_response;
  std::string csv;
  for (const std::string& line : csv_lines) csv += line + "\n";

  BCOT_RETURN_IF_ERROR(RemoveDoneFile(out_dir));
  BCOT_RETURN_IF_ERROR(WriteAnnotation(out_dir, sequence, options, input_hash, whole));
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(csv_path, csv));
  return FinishAnnotation(out_dir, sequence, caster, options, input_hash, rig_from_object, quality,
                          FailedFrames(csv_lines));
}

}  // namespace bcot

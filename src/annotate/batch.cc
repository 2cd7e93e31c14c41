#include "bcot/annotate/batch.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>

#include "bcot/annotate/annotator.h"
#include "bcot/annotate/done_file.h"
#include "bcot/annotate/regenerate_report.h"
#include "bcot/core/file_util.h"
#include "bcot/core/html.h"
#include "bcot/core/sequence.h"
#include "bcot/quality/quality_files.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

// Appends time-stamped lines to <annotation dir>/batch.log. Logs are diagnostics, not
// outputs: they are appended, not written atomically.
class SequenceLog {
 public:
  explicit SequenceLog(const std::string& path) {
    std::error_code error;
    fs::create_directories(fs::path(path).parent_path(), error);
    file_.open(path, std::ios::app);
  }
  void Line(const std::string& text) {
    if (!file_) return;
    const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    char stamp[32];
    std::tm local{};
    localtime_r(&now, &local);  // thread-safe: logs are written from parallel workers
    std::strftime(stamp, sizeof(stamp), "%Y-%m-%d %H:%M:%S", &local);
    file_ << stamp << "  " << text << '\n';
    file_.flush();
  }

 private:
  std::ofstream file_;
};

void FillVerdict(const StatusOr<QualityVerdict>& verdict, BatchSequenceResult* result) {
  if (!verdict.ok()) {
    result->accepted = false;
    result->reasons = {verdict.status().message()};
    return;
  }
  result->accepted = verdict->accepted;
  result->worst_px = verdict->worst_px;
  result->bad_frame_views = verdict->bad_frame_views;
  result->unverified_frame_views = verdict->unverified_frame_views;
  result->reasons = verdict->reasons;
}

// Removes the temporary files WriteFileAtomic leaves behind when a process is killed mid-write
// (".<name>.tmp.<hex>"), in `dir` and, when `recursive`, below it.
void RemoveStaleTempFiles(const std::string& dir, bool recursive) {
  std::error_code error;
  auto remove_if_temp = [&](const fs::directory_entry& entry) {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name[0] == '.' && name.find(".tmp.") != std::string::npos &&
        entry.is_regular_file(error)) {
      fs::remove(entry.path(), error);
    }
  };
  if (recursive) {
    for (fs::recursive_directory_iterator it(dir, error), end; !error && it != end;
         it.increment(error)) {
      remove_if_temp(*it);
    }
  } else {
    for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) {
      remove_if_temp(*it);
    }
  }
}

struct PendingSequence {
  size_t result_index = 0;
  std::string sequence_dir;
  std::string annotation_dir;
  int frames = 0;
};

}  // namespace

Status BatchOptions::Validate() const {
  std::vector<std::string> violations;
  const Status annotate_status = annotate.Validate();
  if (!annotate_status.ok()) violations.push_back(annotate_status.message());
  if (jobs < 0) violations.push_back(fmt::format("jobs = {}, must be >= 0", jobs));
  if (shard_count < 1 || shard_index < 0 || shard_index >= shard_count) {
    violations.push_back(
        fmt::format("shard = {}/{}, must be k/N with 0 <= k < N", shard_index, shard_count));
  }
  if (violations.empty()) return Status::Ok();
  std::string message = violations[0];
  for (size_t i = 1; i < violations.size(); ++i) message += "; " + violations[i];
  return Status::InvalidConfig(message);
}

Status ParseShard(const std::string& text, BatchOptions* options) {
  const size_t slash = text.find('/');
  int64_t index = -1, count = 0;
  if (slash == std::string::npos || !ParseInt64(text.substr(0, slash), &index) ||
      !ParseInt64(text.substr(slash + 1), &count) || count < 1 || index < 0 || index >= count ||
      count > 1000000) {
    return Status::InvalidConfig(
        fmt::format("--shard {}: expected k/N with 0 <= k < N (e.g. 0/4)", text));
  }
  options->shard_index = static_cast<int>(index);
  options->shard_count = static_cast<int>(count);
  return Status::Ok();
}

StatusOr<std::vector<std::string>> FindSequences(const std::string& root,
                                                 std::vector<std::string>* nested) {
  std::error_code error;
  if (!fs::is_directory(root, error)) {
    return Status::NotFound(root + ": not a directory");
  }
  // Symbolic links to folders are followed (a corpus assembled from links is common); the
  // relative paths stay those of the links, so outputs mirror the tree as the user sees it.
  // A link back to a folder already visited is not entered again.
  std::vector<std::string> all;
  std::set<fs::path> visited;
  visited.insert(fs::canonical(root, error));
  if (fs::exists(fs::path(root) / "rig.yaml", error)) all.push_back(".");
  fs::recursive_directory_iterator it(root,
                                      fs::directory_options::skip_permission_denied |
                                          fs::directory_options::follow_directory_symlink,
                                      error);
  if (error) return Status::IoError(root + ": " + error.message());
  for (; it != fs::recursive_directory_iterator(); it.increment(error)) {
    if (error) return Status::IoError(root + ": " + error.message());
    if (!it->is_directory(error)) continue;
    if (!visited.insert(fs::canonical(it->path(), error)).second) {
      it.disable_recursion_pending();
      continue;
    }
    if (fs::exists(it->path() / "rig.yaml", error)) {
      all.push_back(it->path().lexically_relative(root).generic_string());
    }
  }
  std::sort(all.begin(), all.end());
  // A folder holding rig.yaml inside another sequence's folder is not annotated (its outputs
  // would mix with the enclosing sequence's); the caller names it.
  std::vector<std::string> sequences;
  for (const std::string& path : all) {
    const bool inside = std::any_of(sequences.begin(), sequences.end(), [&](const auto& outer) {
      return outer == "." || path.rfind(outer + "/", 0) == 0;
    });
    if (!inside) {
      sequences.push_back(path);
    } else if (nested != nullptr) {
      nested->push_back(path);
    }
  }
  return sequences;
}

Status CheckOutputOutsideSequences(const std::string& root, const std::string& out_dir,
                                   const std::vector<std::string>& sequences) {
  std::error_code error;
  const fs::path out = fs::weakly_canonical(fs::absolute(out_dir), error);
  for (const std::string& relative : sequences) {
    const fs::path sequence = fs::weakly_canonical(fs::absolute(fs::path(root) / relative), error);
    const fs::path annotation = fs::weakly_canonical(out / relative, error);
    // The annotation inside (or equal to) its own sequence folder would write among the
    // input files; `out` inside any sequence folder would put outputs into the input tree.
    for (const fs::path& inside : {annotation, out}) {
      const std::string rel = inside.lexically_relative(sequence).generic_string();
      if (!rel.empty() && rel != ".." && rel.rfind("../", 0) != 0) {
        return Status::InvalidConfig(fmt::format(
            "--out {}: the annotation of sequence '{}' would be written inside the sequence "
            "folder {} (choose an output folder outside the input tree)",
            out_dir, relative, sequence.string()));
      }
    }
  }
  return Status::Ok();
}

std::vector<std::string> SelectShard(const std::vector<std::string>& sequences, int index,
                                     int count) {
  BCOT_CHECK(count >= 1 && index >= 0 && index < count);
  std::vector<std::string> selected;
  for (size_t i = 0; i < sequences.size(); ++i) {
    if (static_cast<int>(i % count) == index) selected.push_back(sequences[i]);
  }
  return selected;
}

const char* BatchOutcomeName(BatchOutcome outcome) {
  switch (outcome) {
    case BatchOutcome::kAnnotated:
      return "annotated";
    case BatchOutcome::kSkipped:
      return "skipped";
    case BatchOutcome::kFailed:
      return "failed";
    case BatchOutcome::kReported:
      return "report regenerated";
  }
  return "?";
}

int BatchResult::num_failed() const {
  return static_cast<int>(std::count_if(sequences.begin(), sequences.end(), [](const auto& s) {
    return s.outcome == BatchOutcome::kFailed;
  }));
}

int BatchResult::ExitCode() const {
  if (num_failed() > 0) return 1;
  const bool any_rejected =
      std::any_of(sequences.begin(), sequences.end(), [](const auto& s) { return !s.accepted; });
  return any_rejected ? kExitRejected : 0;
}

StatusOr<BatchResult> RunBatch(const std::string& root, const std::string& out_dir,
                               const BatchOptions& options, const BatchProgressCallback& progress) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  std::vector<std::string> nested;
  BCOT_ASSIGN_OR_RETURN(const std::vector<std::string> all, FindSequences(root, &nested));
  const std::vector<std::string> selected =
      SelectShard(all, options.shard_index, options.shard_count);
  BCOT_RETURN_IF_ERROR(CheckOutputOutsideSequences(root, out_dir, selected));
  BCOT_RETURN_IF_ERROR(CreateDirectories(out_dir));
  RemoveStaleTempFiles(out_dir, /*recursive=*/false);
  const auto start = std::chrono::steady_clock::now();
  const std::string config_hash = AnnotateConfigHash(options.annotate);

  BatchResult result;
  result.provenance = CurrentProvenance(config_hash);
  std::vector<PendingSequence> pending;
  BatchProgress state;
  state.sequences_total = static_cast<int>(selected.size());
  // Serial pre-pass: load each sequence, decide skip / redo, count the frames to do.
  for (const std::string& relative : selected) {
    BatchSequenceResult entry;
    entry.relative_path = relative;
    const std::string sequence_dir =
        (fs::absolute(root) / relative).lexically_normal().generic_string();
    const std::string annotation_dir = (fs::path(out_dir) / relative).lexically_normal().string();
    StatusOr<Sequence> sequence = LoadSequenceToAnnotate(sequence_dir, AnnotateInputs());
    StatusOr<std::string> input_hash =
        sequence.ok() ? SequenceInputHash(*sequence) : StatusOr<std::string>(sequence.status());
    if (!input_hash.ok()) {
      entry.outcome = BatchOutcome::kFailed;
      entry.error = input_hash.status().message();
      SequenceLog(annotation_dir + "/batch.log").Line("failed: " + entry.error);
      ++state.sequences_done;
      ++state.sequences_failed;
      result.sequences.push_back(entry);
      continue;
    }
    entry.frames = sequence->num_frames;
    const StatusOr<DoneRecord> done = ReadDoneFile(annotation_dir);
    if (!options.force && done.ok() && done->config_hash == config_hash &&
        done->input_hash == *input_hash) {
      entry.outcome = BatchOutcome::kSkipped;
      FillVerdict(ReadQualityVerdict(annotation_dir), &entry);
      ++state.sequences_done;
      ++state.sequences_skipped;
      result.sequences.push_back(entry);
      continue;
    }
    pending.push_back({result.sequences.size(), sequence_dir, annotation_dir, entry.frames});
    state.frames_total += entry.frames;
    result.sequences.push_back(entry);
  }

  // Nested sequences are named once (by shard 0), as failures: they are not annotated.
  for (const std::string& relative :
       options.shard_index == 0 ? nested : std::vector<std::string>{}) {
    BatchSequenceResult entry;
    entry.relative_path = relative;
    entry.outcome = BatchOutcome::kFailed;
    entry.error =
        "nested inside another sequence folder (one holding rig.yaml): not annotated; move it "
        "out of that folder";
    ++state.sequences_done;
    ++state.sequences_failed;
    result.sequences.push_back(entry);
  }
  state.sequences_total += static_cast<int>(result.sequences.size() - selected.size());

  std::mutex mutex;  // guards `state` and the progress callback
  auto report = [&](const std::function<void(BatchProgress&)>& change) {
    std::lock_guard<std::mutex> lock(mutex);
    change(state);
    state.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress(state);
  };
  report([](BatchProgress&) {});

  const int jobs = options.jobs > 0 ? options.jobs : tbb::task_arena::automatic;
  AnnotateInputs inputs;
  inputs.image_cache_mb = options.image_cache_mb;
  tbb::task_arena arena(jobs);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, pending.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
          for (size_t i = r.begin(); i != r.end(); ++i) {
            const PendingSequence& job = pending[i];
            BatchSequenceResult& entry = result.sequences[job.result_index];
            SequenceLog log(job.annotation_dir + "/batch.log");
            log.Line(fmt::format("start: {} -> {} ({} frames, config {})", job.sequence_dir,
                                 job.annotation_dir, job.frames, config_hash));
            const auto sequence_start = std::chrono::steady_clock::now();
            int last_done = 0;
            const AnnotateProgress on_frame = [&](int done, int total) {
              const int delta = done - last_done;
              last_done = done;
              if (done % 10 == 0 || done == total) {
                log.Line(fmt::format("frame {}/{}", done, total));
              }
              report([delta](BatchProgress& s) { s.frames_done += delta; });
            };
            RemoveStaleTempFiles(job.annotation_dir, /*recursive=*/true);
            StatusOr<AnnotationOutcome> outcome = Status::Internal("not run");
            try {
              outcome = options.runner ? options.runner(job.sequence_dir, job.annotation_dir,
                                                        options.annotate, on_frame)
                                       : AnnotateSequenceDir(job.sequence_dir, job.annotation_dir,
                                                             options.annotate, inputs, on_frame);
            } catch (const std::exception& exception) {
              outcome = Status::Internal(fmt::format("unexpected exception: {}", exception.what()));
            }
            const Status status = outcome.status();
            entry.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - sequence_start)
                    .count();
            if (status.ok()) {
              entry.outcome = BatchOutcome::kAnnotated;
              FillVerdict(outcome->verdict, &entry);
              log.Line(fmt::format("done in {:.1f} s: {}", entry.seconds,
                                   entry.accepted ? "accepted" : "rejected"));
              for (const std::string& note : outcome->notes) log.Line("note: " + note);
            } else {
              entry.outcome = BatchOutcome::kFailed;
              entry.error = status.message();
              log.Line("failed: " + entry.error);
            }
            const int remaining = job.frames - last_done;
            const bool failed = !status.ok();
            report([remaining, failed](BatchProgress& s) {
              ++s.sequences_done;
              s.sequences_failed += failed ? 1 : 0;
              s.frames_done += remaining;  // a failed sequence's frames count as done
            });
          }
        });
  });

  BCOT_RETURN_IF_ERROR(WriteBatchSummary(
      out_dir, result,
      options.shard_count == 1
          ? "summary"
          : fmt::format("summary.shard{}of{}", options.shard_index, options.shard_count)));
  return result;
}

Status WriteBatchSummary(const std::string& out_dir, const BatchResult& result,
                         const std::string& name) {
  BCOT_RETURN_IF_ERROR(WriteFileAtomic(out_dir + "/" + name + ".json", BatchSummaryJson(result)));
  return WriteFileAtomic(out_dir + "/" + name + ".html", BatchSummaryHtml(result));
}

StatusOr<BatchResult> RegenerateBatchReports(const std::string& out_dir,
                                             const std::string& config_path,
                                             const std::vector<std::string>& overrides) {
  std::error_code error;
  if (!fs::is_directory(out_dir, error)) return Status::NotFound(out_dir + ": not a directory");
  std::vector<std::string> annotated;
  for (fs::recursive_directory_iterator it(out_dir, error), end; !error && it != end;
       it.increment(error)) {
    if (it->is_directory(error) && fs::exists(it->path() / "DONE", error)) {
      annotated.push_back(fs::relative(it->path(), out_dir).generic_string());
      it.disable_recursion_pending();
    }
  }
  if (error) return Status::IoError(out_dir + ": " + error.message());
  if (annotated.empty()) {
    return Status::NotFound(out_dir + ": no finished annotation (a folder holding DONE) below it");
  }
  std::sort(annotated.begin(), annotated.end());
  BatchResult result;
  for (const std::string& relative : annotated) {
    BatchSequenceResult entry;
    entry.relative_path = relative;
    const StatusOr<QualityReport> report = RegenerateQualityReport(
        (fs::path(out_dir) / relative).string(), "", config_path, overrides);
    if (!report.ok()) {
      entry.outcome = BatchOutcome::kFailed;
      entry.error = report.status().message();
    } else {
      entry.outcome = BatchOutcome::kReported;
      entry.frames = static_cast<int>(report->frames.size());
      FillVerdict(VerdictOf(*report), &entry);
    }
    result.sequences.push_back(entry);
  }
  result.provenance = CurrentProvenance("");
  BCOT_RETURN_IF_ERROR(WriteBatchSummary(out_dir, result, "summary"));
  return result;
}

std::string BatchSummaryJson(const BatchResult& result) {
  nlohmann::ordered_json json;
  int accepted = 0, rejected = 0;
  for (const BatchSequenceResult& s : result.sequences) {
    if (s.outcome != BatchOutcome::kFailed) (s.accepted ? accepted : rejected) += 1;
  }
  json["bcot_version"] = result.provenance.bcot_version;
  json["created_utc"] = result.provenance.created_utc;
  json["config_hash"] = result.provenance.config_hash;
  json["accepted"] = accepted;
  json["rejected"] = rejected;
  json["failed"] = result.num_failed();
  json["sequences"] = nlohmann::ordered_json::array();
  for (const BatchSequenceResult& s : result.sequences) {
    nlohmann::ordered_json entry = {{"sequence", s.relative_path},
                                    {"outcome", BatchOutcomeName(s.outcome)}};
    if (s.outcome == BatchOutcome::kFailed) {
      entry["verdict"] = "failed";
      entry["error"] = s.error;
    } else {
      entry["verdict"] = s.accepted ? "accepted" : "rejected";
      entry["reasons"] = s.reasons;
      entry["worst_px"] = s.worst_px;
      entry["bad_frame_views"] = s.bad_frame_views;
      entry["unverified_frame_views"] = s.unverified_frame_views;
      entry["report"] = s.relative_path + "/report.html";
    }
    entry["frames"] = s.frames;
    json["sequences"].push_back(entry);
  }
  return json.dump(1) + "\n";
}

std::string BatchSummaryHtml(const BatchResult& result) {
  int accepted = 0, rejected = 0;
  for (const BatchSequenceResult& s : result.sequences) {
    if (s.outcome != BatchOutcome::kFailed) (s.accepted ? accepted : rejected) += 1;
  }
  std::string rows;
  for (const BatchSequenceResult& s : result.sequences) {
    const bool failed = s.outcome == BatchOutcome::kFailed;
    const std::string verdict = failed ? "failed" : (s.accepted ? "accepted" : "rejected");
    std::string why = failed ? s.error : "";
    for (const std::string& reason : s.reasons) why += (why.empty() ? "" : "; ") + reason;
    const std::string name =
        failed ? HtmlEscape(s.relative_path)
               : fmt::format("<a href='{}/report.html'>{}</a>", HtmlEscape(s.relative_path),
                             HtmlEscape(s.relative_path));
    rows += fmt::format(
        "<tr class='{0}'><td>{1}</td><td>{0}</td><td>{2}</td><td data-v='{3}'>{4}</td>"
        "<td data-v='{5}'>{5}</td><td data-v='{6}'>{6}</td><td data-v='{7}'>{7}</td>"
        "<td>{8}</td></tr>\n",
        verdict, name, BatchOutcomeName(s.outcome), failed ? -1.0 : s.worst_px,
        failed ? "–" : fmt::format("{:.2f}", s.worst_px), s.frames, s.bad_frame_views,
        s.unverified_frame_views, HtmlEscape(why));
  }
  return fmt::format(
      "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>bcot batch "
      "summary</title><style>body{{font-family:sans-serif;margin:20px}}table{{border-collapse:"
      "collapse}}td,th{{border:1px solid #ccc;padding:3px 8px}}th{{cursor:pointer;background:"
      "#eee}}tr.accepted td:nth-child(2){{background:#dfd}}tr.rejected td:nth-child(2)"
      "{{background:#fdd}}tr.failed td:nth-child(2){{background:#fc9}}</style></head><body>\n"
      "<h1>bcot batch summary</h1><p class='provenance'><small>{}</small></p><p id='counts'>{} "
      "accepted, {} rejected, {} failed of {} "
      "sequences. Click a column header to sort.</p>\n<table id='summary'><thead><tr>"
      "<th>sequence</th><th>verdict</th><th>this run</th><th>worst error (px)</th><th>frames"
      "</th><th>bad frame-views</th><th>cannot "
      "tell</th><th>why</th></tr></thead><tbody>\n{}</tbody></table>\n<script>\n"
      "(function () {{\n"
      "  var table = document.getElementById('summary');\n"
      "  var headers = table.tHead.rows[0].cells;\n"
      "  function key(cell) {{\n"
      "    var v = cell.getAttribute('data-v');\n"
      "    return v === null ? cell.textContent.toLowerCase() : parseFloat(v);\n"
      "  }}\n"
      "  Array.prototype.forEach.call(headers, function (th, column) {{\n"
      "    th.addEventListener('click', function () {{\n"
      "      var ascending = th.getAttribute('data-order') !== 'asc';\n"
      "      th.setAttribute('data-order', ascending ? 'asc' : 'desc');\n"
      "      var body = table.tBodies[0];\n"
      "      var rows = Array.prototype.slice.call(body.rows);\n"
      "      rows.sort(function (a, b) {{\n"
      "        var x = key(a.cells[column]), y = key(b.cells[column]);\n"
      "        return (x < y ? -1 : x > y ? 1 : 0) * (ascending ? 1 : -1);\n"
      "      }});\n"
      "      rows.forEach(function (row) {{ body.appendChild(row); }});\n"
      "    }});\n"
      "  }});\n"
      "  document.body.setAttribute('data-report-ready', 'yes');\n"
      "}})();\n</script>\n</body></html>\n",
      HtmlEscape(FormatProvenance(result.provenance)), accepted, rejected, result.num_failed(),
      result.sequences.size(), rows);
}

}  // namespace bcot

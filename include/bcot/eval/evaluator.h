// Evaluation of monocular trackers on a benchmark (BCOT release or RBOT layout) with the
// protocol of the public BCOT/RBOT evaluators (paper §4.7, DESIGN.md):
//   - the tracker starts from the GT of frame 0; frames 1..N−1 are scored;
//   - a frame whose rotation error > reset_rotation_deg or translation error >
//     reset_translation_mm is *lost*: counted as a failure and the tracker is reset to that
//     frame's GT (the only reset);
//   - metrics (metrics.h) are pooled over all scored frames of all sequences.
// Offline mode scores pose files a tracker already wrote, with the same frame range; there
// "lost" counts the frames failing the reset test (the tracker's own resets are its business).
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

#include "bcot/core/status.h"
#include "bcot/eval/benchmark_sequence.h"
#include "bcot/eval/metrics.h"
#include "bcot/eval/monocular_tracker.h"
#include "bcot/render/mesh.h"

namespace bcot {

// YAML (configs/eval.yaml) mirrors the fields; `curve` is a section.
struct EvalOptions {
  // Dataset layout of --data: "bcot" (bcot_layout.h) or "rbot" (rbot_layout.h).
  std::string layout = "bcot";
  // RBOT only: image variant prefix (a_regular, b_dynamiclight, c_noisy, d_occlusion) and the
  // GT file relative to the dataset root.
  std::string rbot_variant = "a_regular";
  std::string rbot_poses = "poses_first.txt";
  // Reset test (deg, (0, 180]; mm, > 0): 5° / 5 cm in BCOT and RBOT.
  double reset_rotation_deg = 5.0;
  double reset_translation_mm = 50.0;
  CurveOptions curve;
  // Lists every violation of EvalOptionSchema()'s rules (kInvalidConfig).
  Status Validate() const;
};

// The declaration of every option above (configs/eval.yaml; `curve` is a section).
const OptionSchema<EvalOptions>& EvalOptionSchema();

// Strict YAML (unknown keys are errors naming file:line); `overrides` ("key=value",
// "curve.steps=50"; errors name `--set key`) are applied on top; an empty path = defaults +
// overrides. kInvalidConfig.
StatusOr<EvalOptions> ReadEvalOptions(const std::string& path,
                                      const std::vector<std::string>& overrides = {});
// Every field as YAML; reads back to the same options.
std::string FormatEvalOptions(const EvalOptions& options);

// Loads the sequences of `root` in the layout the options name.
StatusOr<std::vector<BenchmarkSequence>> LoadBenchmark(const std::string& root,
                                                       const EvalOptions& options);

// Scores of one sequence: frames 1..N−1 in order.
struct SequenceResult {
  std::string scene;
  std::string object;
  std::vector<ScoredFrame> frames;
  int num_resets = 0;  // online: resets after lost frames (the frame-0 initialisation excluded)
};

// Offline: `estimated_cam_from_object` holds N poses (frames 0..N−1; frame 0 is ignored) or
// N−1 poses (frames 1..N−1). `source` names the result file in messages. time_ms = NaN.
StatusOr<SequenceResult> ScoreSequence(
    const BenchmarkSequence& sequence, const Mesh& mesh,
    const std::vector<Eigen::Isometry3d>& estimated_cam_from_object, const std::string& source,
    const EvalOptions& options);

// Offline over a benchmark: results are read from <results_root>/<scene>/<object>/pose.txt
// (pose_io.h format, the BCOT layout); a missing file is kNotFound naming it.
StatusOr<std::vector<SequenceResult>> EvaluateOffline(
    const std::vector<BenchmarkSequence>& sequences, const std::string& results_root,
    const EvalOptions& options);

// Online protocol on one sequence with a freshly built `tracker`: Reset on frame 0 with its
// GT, then Track frames 1..N−1, resetting to GT after each lost frame. Reads the images
// (an unreadable image or a size change is kInvalidInput naming the file). time_ms = wall time
// of Track (the only use of a clock). `estimates` (optional) receives N poses: GT of frame 0,
// then the tracker's estimates as returned (before any reset; the previous entry where Track
// failed).
StatusOr<SequenceResult> RunTrackingProtocol(const BenchmarkSequence& sequence, const Mesh& mesh,
                                             MonocularTracker* tracker, const EvalOptions& options,
                                             std::vector<Eigen::Isometry3d>* estimates = nullptr);

// Called after each sequence: sequences done, total, the finished result.
using EvalProgress = std::function<void(int done, int total, const SequenceResult& result)>;

// Online over a benchmark: per sequence, reads frame 0 for the image size, builds a tracker
// with `factory` and runs the protocol. When `poses_out_root` is non-empty the estimates are
// written to <poses_out_root>/<scene>/<object>/pose.txt (re-scorable offline).
StatusOr<std::vector<SequenceResult>> EvaluateOnline(
    const std::vector<BenchmarkSequence>& sequences, const MonocularTrackerFactory& factory,
    const EvalOptions& options, const std::string& poses_out_root = "",
    const EvalProgress& progress = {});

}  // namespace bcot

// Options of `bcot annotate` (one sequence) and their YAML form. Each YAML section maps to one
// options struct; keys are spelled as the fields:
//
//   frame:   FrameProblemOptions      rounds, iterations, pyramid_levels, round_tolerance_deg,
//                                     round_tolerance_mm, num_threads
//   region:  RegionTemplateOptions    band_px, stride_px, contour_sample_spacing_px,
//                                     contour_precision_px, contour_coarse_step_px
//   cost:    RegionCostOptions        form (sqrt_energy | irls), heaviside_slope,
//                                     probability_floor; and energy (dense | sparse |
//                                     combined) = FrameProblemOptions::energy
//   lines:   CorrespondenceLineOptions num_lines, scale_px, half_length_px, min_side_px,
//                                     slope_px, amplitude, hypothesis_subdivisions,
//                                     min_sigma_px, max_sigma_px, weight
//   color:   ColorModelOptions        kind (global | local), refine_kind (same | global |
//                                     local), bins_per_channel,
//                                     learning_rate_foreground, learning_rate_background,
//                                     background_band_px, sample_margin_px,
//                                     local_region_radius_px, local_region_spacing_px,
//                                     local_anchor_fraction
//   tracker: MultiViewTrackerOptions  bootstrap_passes
//   views:   ViewSelection            cameras (names; empty = all), weights (one per camera)
//   quality: QualityOptions           threshold_px, statistic, allowed_bad_fraction, ...
//                                     (bcot/quality/quality_report.h)
//   symmetry: SymmetryHandling        detect, tolerance (render/symmetry_detection.h)
//   window:  WindowProblemOptions     enabled, size, overlap, iterations, prior (decoupled |
//                                     se3), rotation_sigma_deg
//                                     [x, y, z], translation_sigma_mm [x, y, z],
//                                     robust_translation_mm, robust_rotation_deg, num_threads
//
// Every option is declared once in AnnotateOptionSchema() (key, field, unit, rule, help; see
// bcot/core/option_schema.h): unknown keys, wrong types and out-of-range values are
// kInvalidConfig errors naming file:line: section.key (or `--set section.key`), and
// `bcot annotate --help` lists them. configs/annotate.yaml is the annotation setting (2 rounds ×
// 7 iterations, the edge stage, the window), configs/track.yaml the tracking setting (1 round).
// FormatAnnotateOptions writes every option; reading it back gives the same options.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "bcot/core/option_schema.h"
#include "bcot/core/status.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/optim/window_problem.h"
#include "bcot/quality/quality_options.h"
#include "bcot/render/symmetry_detection.h"

namespace bcot {

struct ViewSelection {
  // Names of the rig cameras to use, in this order; empty = every camera of the rig.
  std::vector<std::string> cameras;
  // One weight w_v >= 0 per selected camera (eq. 8); empty = all 1.
  std::vector<double> weights;
};

// How the frames store chroma, for the edge stage's correction of subsampled chroma
// (edge_lines.h): read from each camera's first frame (a JPEG's header; any other format is
// full), or set, e.g. for lossless frames transcoded from 4:2:0 JPEG.
enum class ChromaSamplingSetting { kAuto, kFull, kJpeg420, kJpeg422 };

// Bodies of revolution (docs/method.md, "Symmetric objects"): when the mesh is one, no image
// observes the angle about its axis, and every solve keeps it where tracking started.
struct SymmetryHandling {
  // Look for the symmetry in the mesh (render/symmetry_detection.h); false = treat every object
  // as asymmetric (e.g. a cylinder whose printed label the colour models could follow).
  bool detect = true;
  SymmetryDetectionOptions detection;
};

struct AnnotateOptions {
  // The optim layer's defaults, except the rounds: 2 per tracked frame (the edge stage then
  // places the contour) and 5 per bootstrap solve of frame 0 (docs/notes/issue19_speed.md),
  // and the image response: estimated (edge.response auto: docs/camera_response.md; a
  // machine-vision camera's linear codes decoded as sRGB move every edge towards its bright
  // side).
  AnnotateOptions();

  MultiViewTrackerOptions tracker;
  ViewSelection views;
  ChromaSamplingSetting chroma_sampling = ChromaSamplingSetting::kAuto;
  QualityOptions quality;
  SymmetryHandling symmetry;
  // The temporal smoothing window after the per-frame solves (off unless enabled).
  WindowProblemOptions window;
  // Lists every violation of the declared rules in one kInvalidConfig status, then the optim
  // layer's own checks.
  Status Validate() const;
};

// The declaration of every option above (sections as listed at the top). Built once.
const OptionSchema<AnnotateOptions>& AnnotateOptionSchema();

// Parses a YAML document (keys absent keep their defaults). `source_name` names the file in
// messages.
StatusOr<AnnotateOptions> ParseAnnotateOptions(const YAML::Node& root,
                                               const std::string& source_name);
// Reads `path` (empty = defaults), then applies `--set section.key=value` overrides on top.
StatusOr<AnnotateOptions> ReadAnnotateOptions(const std::string& path,
                                              const std::vector<std::string>& overrides);
// Every option as YAML (sections as above), readable by ParseAnnotateOptions.
std::string FormatAnnotateOptions(const AnnotateOptions& options);

}  // namespace bcot

// `bcot export`: an annotated sequence → a dataset layout. Two formats share everything up to
// the writing: which cameras and frames, reading the poses, undistorting and scaling the images
// (this file); the BCOT release layout is written here, the BOP layout by bop_writer.h.
// docs/export.md describes both for users.
//
// Inputs: the sequence directory (input contract: rig.yaml, object.yaml, frames) and its
// annotation directory (output contract: <camera>/pose.txt = cam_from_object per frame, or
// rig_from_object.txt from which cam_from_object = cam_from_rig · rig_from_object is formed).
// BCOT release layout (paper §4.1, DESIGN.md "Release export and evaluation"; bcot_layout.h),
// per exported camera:
//   <out>/models/<Object>.obj           the mesh as loaded (unit_to_mm applied: mm), template
//                                       frame O_t, i.e. the frame the poses refer to
//   <out>/<scene>/K.txt                 intrinsics of the exported images
//   <out>/<scene>/<Object>/%04d.png     the selected frames, renumbered 0, 1, …
//   <out>/<scene>/<Object>/pose.txt     cam_from_object of those frames (mm)
// Frames: first_frame, first_frame + s, … below end_frame (s = frame_step). By default every
// frame at full resolution; the preset "bcot-release" gives the paper's release (every 2nd
// frame, 60 → 30 fps; half resolution, 1280×1024 → 640×512).
// Images: exported images are UNDISTORTED. A camera with distortion is first resampled
// (cv::remap, bilinear) to the ideal pinhole camera with the same K: output pixel u takes the
// input at π_distorted(π⁻¹_ideal(u)); pixels that map outside the input are black. Then the image
// is downsampled by `image_scale` with area averaging (cv::INTER_AREA), and K follows
// Camera::Scaled (pixel centres at integers: c' = (c + ½)·s − ½, f' = f·s). Poses are
// unchanged by both steps. Every file is written atomically.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "bcot/core/option_schema.h"
#include "bcot/core/status.h"

namespace bcot {

enum class ExportFormat { kBcot, kBop };

// Options of the BOP layout only (bop_writer.h).
struct BopExportOptions {
  // Split folder: "test", "val", "train" or any of them with a "_TYPE" suffix; a folder name.
  std::string split = "test";
  // Scene id: the scene folder is <split>/<scene_id as 6 digits>; [0, 999999].
  int scene_id = 0;
  // Object id: models/obj_<obj_id as 6 digits>.ply and scene_gt's obj_id; [1, 999999].
  int obj_id = 1;
  // models_info.json lists the model's continuous symmetry ("symmetries_continuous": its axis
  // and a point on it) when the mesh is a body of revolution (render/symmetry_detection.h,
  // default tolerance); false = never (a cylinder whose texture shows its angle).
  bool symmetries_continuous = true;
};

// YAML (configs/export.yaml) keys are the field names ("bop.split" for the nested ones).
struct ExportOptions {
  ExportFormat format = ExportFormat::kBcot;
  // Keep every n-th frame (60 → 30 fps: 2); [1, 1000].
  int frame_step = 1;
  // First exported frame (0-based) and the frame after the last one (-1 = to the end);
  // first_frame >= 0, end_frame = -1 or > first_frame, both within the sequence.
  int first_frame = 0;
  int end_frame = -1;
  // Image scale factor (1280×1024 → 640×512: 0.5); (0, 1], and width·scale and height·scale
  // must be integers for every exported camera.
  double image_scale = 1.0;
  // Cameras to export, by rig.yaml name; empty = every camera of the rig (the BCOT release's
  // indoor scenes have one view: set [cam0]).
  std::vector<std::string> cameras;
  // BCOT: scene folder name; empty = the sequence folder's name. With more than one exported
  // camera each gets its own scene folder "<scene>_<camera>".
  std::string scene;
  // BCOT: object name (model file and folder); empty = object.yaml's name. May contain spaces,
  // not '/', not "." or "..".
  std::string object;
  // An existing non-empty output folder (BCOT: <scene>/<Object>, BOP: the scene folder) is an
  // error unless true; then it is removed first (so no stale frames survive).
  bool overwrite = false;
  BopExportOptions bop;
  // Lists every violation of ExportOptionSchema()'s rules (kInvalidConfig).
  Status Validate() const;
};

// Named starting points for the options (before --config and --set):
//   ""              the defaults above: every frame, full resolution
//   "bcot-release"  the BCOT release (paper §4.1): frame_step 2, image_scale 0.5
// kInvalidConfig naming the preset and the known ones otherwise.
StatusOr<ExportOptions> ExportPreset(const std::string& name);
const std::vector<std::string>& ExportPresetNames();

// The declaration of every option above (configs/export.yaml keys are the field names).
const OptionSchema<ExportOptions>& ExportOptionSchema();

// The config at `path` (empty = none) and `overrides` applied on top of `base` (a preset).
StatusOr<ExportOptions> ReadExportOptions(const std::string& path,
                                          const std::vector<std::string>& overrides = {},
                                          const ExportOptions& base = ExportOptions());
std::string FormatExportOptions(const ExportOptions& options);

struct ExportSummary {
  std::vector<std::string> scene_dirs;  // BCOT: one per exported camera; BOP: the scene folder
  std::string model_path;
  std::vector<std::string> cameras;  // exported cameras, by rig.yaml name
  int rig_cameras = 0;               // cameras in rig.yaml
  std::vector<int> frames;           // exported frames (sequence indices)
  int sequence_frames = 0;           // frames of the sequence
  int frame_step = 1;
  int width = 0, height = 0;                // of the exported images (first camera)
  int source_width = 0, source_height = 0;  // of the sequence's images (first camera)
  bool undistorted = false;                 // some exported camera had distortion
};

// The one line `bcot export` prints (without line end): format, frames and rate, cameras (of
// the rig's), resolution, undistortion and where, e.g.
// "bop format: 4 of 4 frames (0..3, step 1, full rate), cameras cam0,cam1 (2 of 2),
//  320x256 (full resolution, undistorted) -> out/test/000000".
std::string DescribeExport(const ExportSummary& summary, ExportFormat format);

// Writes the BCOT release layout (options.format is not consulted; ExportAnnotation dispatches).
// Errors: missing or inconsistent inputs (pose count ≠ frame count, unknown camera, image
// size ≠ rig.yaml) are kInvalidInput / kNotFound naming the file; option problems (including a
// non-integer scaled size, frames outside the sequence) kInvalidConfig; a scene whose existing
// K.txt differs from the one to be written is kInvalidInput (two cameras must not share a scene
// folder).
StatusOr<ExportSummary> ExportToBcot(const std::string& sequence_dir,
                                     const std::string& annotation_dir, const std::string& out_root,
                                     const ExportOptions& options);

// ExportToBcot or ExportToBop (bop_writer.h), by options.format.
StatusOr<ExportSummary> ExportAnnotation(const std::string& sequence_dir,
                                         const std::string& annotation_dir,
                                         const std::string& out_root, const ExportOptions& options);

}  // namespace bcot

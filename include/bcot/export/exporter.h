// `bcot export`: an annotated sequence → the BCOT release layout (paper §4.1, DESIGN.md
// "Release export and evaluation"; layout in bcot_layout.h).
//
// Inputs: the sequence directory (input contract: rig.yaml, object.yaml, frames) and its
// annotation directory (output contract: <camera>/pose.txt = cam_from_object per frame, or
// rig_from_object.txt from which cam_from_object = cam_from_rig · rig_from_object is formed).
// Per exported camera it writes
//   <out>/models/<Object>.obj           the mesh as loaded (unit_to_mm applied: mm), template
//                                       frame O_t, i.e. the frame the poses refer to
//   <out>/<scene>/K.txt                 intrinsics of the exported images
//   <out>/<scene>/<Object>/%04d.png     frames 0, s, 2s, ... (s = frame_step), renumbered 0, 1, …
//   <out>/<scene>/<Object>/pose.txt     cam_from_object of those frames (mm)
// Images: BCOT release images are UNDISTORTED. A camera with distortion is first resampled
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

// YAML (configs/export.yaml) keys are the field names.
struct ExportOptions {
  // Keep every n-th frame (60 → 30 fps: 2); [1, 1000].
  int frame_step = 2;
  // Image scale factor (1280×1024 → 640×512: 0.5); (0, 1], and width·scale and height·scale
  // must be integers for every exported camera.
  double image_scale = 0.5;
  // Cameras to export, by rig.yaml name; empty = the first camera only (BCOT indoor scenes).
  // Outdoor scenes export both views of the rig.
  std::vector<std::string> cameras;
  // Scene folder name; empty = the sequence folder's name. With more than one exported camera
  // each gets its own scene folder "<scene>_<camera>".
  std::string scene;
  // Object name (model file and folder); empty = object.yaml's name. May contain spaces, not
  // '/', not "." or "..".
  std::string object;
  // An existing non-empty <scene>/<Object> folder is an error unless true; then it is removed
  // first (so no stale frames survive).
  bool overwrite = false;
  // Lists every violation of ExportOptionSchema()'s rules (kInvalidConfig).
  Status Validate() const;
};

// The declaration of every option above (configs/export.yaml keys are the field names).
const OptionSchema<ExportOptions>& ExportOptionSchema();

StatusOr<ExportOptions> ReadExportOptions(const std::string& path,
                                          const std::vector<std::string>& overrides = {});
std::string FormatExportOptions(const ExportOptions& options);

struct ExportSummary {
  std::vector<std::string> scene_dirs;  // one per exported camera, "<out>/<scene>"
  std::string model_path;
  int frames_per_camera = 0;
  int width = 0, height = 0;  // of the exported images (first camera)
  bool undistorted = false;   // some exported camera had distortion
};

// Errors: missing or inconsistent inputs (pose count ≠ frame count, unknown camera, image
// size ≠ rig.yaml) are kInvalidInput / kNotFound naming the file; option problems (including a
// non-integer scaled size) kInvalidConfig; a scene whose existing K.txt differs from the one to
// be written is kInvalidInput (two cameras must not share a scene folder).
StatusOr<ExportSummary> ExportToBcot(const std::string& sequence_dir,
                                     const std::string& annotation_dir, const std::string& out_root,
                                     const ExportOptions& options);

}  // namespace bcot

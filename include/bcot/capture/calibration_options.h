// Options of `bcot calibrate`: per-camera intrinsics and `cam_from_rig` extrinsics from
// chessboard images (configs/calibrate.yaml documents every key).
//
// One struct per YAML section, YAML keys spelled as the fields. Input layout: for camera
// name N, either the folder `<images_dir>/N/` (every image in it; views are paired across
// cameras by file stem, e.g. left/007.png ↔ right/007.png) or, when that folder does not
// exist, the files `<images_dir>/N*.<ext>` (paired by the stem after the prefix, e.g.
// left07.jpg ↔ right07.jpg). Image extensions: png, jpg, jpeg, bmp, tif, tiff.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "bcot/core/option_schema.h"
#include "bcot/core/status.h"

namespace bcot {

struct CalibrationOptions {
  struct Board {
    // Inner corners of the chessboard per row and per column (a board of 10×7 squares has
    // 9×6 inner corners), each in [2, 100].
    int inner_corners_x = 9;
    int inner_corners_y = 6;
    // Side of one square (mm), > 0. Sets the unit of cam_from_rig: translations in mm.
    double square_size_mm = 25.0;
  } board;

  struct Input {
    // Folder holding the images (see the layout above). Relative to the config file.
    std::string images_dir;
    // Camera names, also the names written to rig.yaml; at least one, unique, usable as
    // folder names. The first camera defines the rig frame (cam_from_rig = identity).
    std::vector<std::string> cameras = {"left", "right"};
  } input;

  struct Detection {
    // Half size (px) of the cv::cornerSubPix search window, [1, 50] (5 → 11×11 window).
    int subpixel_half_window_px = 5;
    // cv::findChessboardCorners flags: adaptive threshold + image normalisation (robust to
    // uneven light), and the quick rejection check of images without a board.
    bool adaptive_threshold = true;
    bool fast_check = false;
  } detection;

  struct Model {
    // Distortion model: k1, k2, p1, p2, k3 (OpenCV). fix_k3 keeps k3 = 0 (recommended unless
    // the lens is wide-angle and the board covers the image corners); zero_tangential keeps
    // p1 = p2 = 0; fix_aspect_ratio forces fx = fy.
    bool fix_k3 = true;
    bool zero_tangential = false;
    bool fix_aspect_ratio = false;
  } model;

  struct Outliers {
    // An image (or a stereo view) whose reprojection RMS exceeds this (px) is listed as an
    // outlier, > 0.
    double max_rms_px = 1.0;
    // Calibrate once more without the outlier images (they stay listed in the report).
    bool drop = false;
  } outliers;

  // Lists every violation ("board.square_size_mm = 0, must be > 0"), kInvalidConfig: the
  // rules of CalibrationOptionSchema().
  Status Validate() const;
};

// The declaration of every option above (configs/calibrate.yaml). Built once.
const OptionSchema<CalibrationOptions>& CalibrationOptionSchema();

// Reads a config file strictly (unknown or duplicate keys are errors naming file:line:key),
// resolves input.images_dir against the config file's directory, applies `overrides`
// ("section.key=value"; errors name `--set key`) and validates. Empty `path` = defaults plus
// overrides.
StatusOr<CalibrationOptions> ReadCalibrationOptions(const std::string& path,
                                                    const std::vector<std::string>& overrides = {});

// Same from a parsed document; `source_name` prefixes messages, `base_dir` resolves paths.
StatusOr<CalibrationOptions> ParseCalibrationOptions(const YAML::Node& root,
                                                     const std::string& source_name,
                                                     const std::string& base_dir);

// Every option as YAML (reads back to the same options).
std::string FormatCalibrationOptions(const CalibrationOptions& options);

}  // namespace bcot

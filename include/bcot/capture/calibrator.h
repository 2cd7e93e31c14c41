// Chessboard calibration of a rig: intrinsics per camera (cv::calibrateCamera), then each
// camera's `cam_from_rig` from the views it shares with the first camera
// (cv::stereoCalibrate with those intrinsics fixed). The rig frame is the first camera's
// frame; translations are in mm because board points are placed at multiples of
// board.square_size_mm.
//
// Reprojection RMS: per image (one camera's view of the board, after its intrinsic
// calibration), per camera, per stereo view (both images of a shared view, after the stereo
// calibration) and per camera pair. Images and stereo views above outliers.max_rms_px are
// listed as outliers.
//
// Not thread-safe in any special way: Calibrate is a pure function of its options and the
// image files.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bcot/capture/calibration_options.h"
#include "bcot/core/rig.h"
#include "bcot/core/status.h"

namespace bcot {

struct CalibrationImage {
  std::string view;  // view key shared across cameras ("07" for left07.jpg)
  std::string path;
  bool board_found = false;
  bool used = false;     // board found and not dropped as an outlier
  double rms_px = -1.0;  // reprojection RMS after the camera's calibration; −1 when not used
  bool outlier = false;
};

struct CameraCalibration {
  std::string name;
  std::vector<CalibrationImage> images;  // sorted by view key
  double rms_px = 0.0;                   // over all used images
  int num_used = 0;
};

// Camera `camera_index` (≥ 1) against camera 0 over the views where both found the board.
struct PairCalibration {
  int camera_index = 0;
  std::vector<std::string> views;   // shared view keys used
  std::vector<double> view_rms_px;  // RMS over both images of each view
  std::vector<bool> view_outlier;
  double rms_px = 0.0;       // over all shared views
  double baseline_mm = 0.0;  // distance between the two camera centres
};

struct CalibrationResult {
  Rig rig;
  std::vector<CameraCalibration> cameras;  // in options.input.cameras order
  std::vector<PairCalibration> pairs;      // one per camera after the first
  std::vector<std::string> outliers;       // image paths and "view <key> (a+b)" entries
};

// Called after each image is searched for the board (done, total).
using CalibrationProgress = std::function<void(int done, int total)>;

// Errors (each names the file or camera): NotFound when the folder or a camera's images are
// missing; InvalidInput for an unreadable image, an image whose size differs from the
// camera's first image, a camera with fewer than 3 board detections (the message says when
// none was found: wrong inner-corner count?), or a camera sharing fewer than 3 views with the
// first camera.
StatusOr<CalibrationResult> Calibrate(const CalibrationOptions& options,
                                      const CalibrationProgress& progress = {});

// CSV, one row per image: camera,view,image,board_found,rms_px,outlier; then one row per
// stereo view: pair,view,,,rms_px,outlier (pair = "left+right").
std::string FormatCalibrationReport(const CalibrationResult& result);

// Human-readable multi-line summary: RMS per camera and pair, baselines, outliers.
std::string FormatCalibrationSummary(const CalibrationResult& result);

// Writes <out_dir>/rig.yaml, calibration_report.csv and calibrate.resolved.yaml (atomic).
Status WriteCalibration(const CalibrationResult& result, const CalibrationOptions& options,
                        const std::string& out_dir);

}  // namespace bcot

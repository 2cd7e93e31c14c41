#include "bcot/capture/calibration_options.h"

#include <fmt/format.h>

#include <string>
#include <vector>

#include "bcot/core/version.h"
#include "camera_names.h"

namespace bcot {
namespace {

using capture_internal::CameraNameRule;

OptionSchema<CalibrationOptions>* BuildCalibrationOptionSchema() {
  auto* s = new OptionSchema<CalibrationOptions>();
  s->Add(
       "board.inner_corners_x", [](auto& o) -> auto& { return o.board.inner_corners_x; }, "",
       "inner corners per row (a 10x7-square board has 9x6)")
      .Range(Closed(2, 100));
  s->Add(
       "board.inner_corners_y", [](auto& o) -> auto& { return o.board.inner_corners_y; }, "",
       "inner corners per column")
      .Range(Closed(2, 100));
  s->Add(
       "board.square_size_mm", [](auto& o) -> auto& { return o.board.square_size_mm; }, "mm",
       "side of one square: the unit of cam_from_rig")
      .Range(Positive());
  s->Add(
       "input.images_dir", [](auto& o) -> auto& { return o.input.images_dir; }, "",
       "folder of images (relative to the config file), N/<stem>.png or N<stem>.png per camera")
      .Path()
      .Check([](const CalibrationOptions& o) {
        return o.input.images_dir.empty() ? "must name a folder of images" : "";
      });
  s->Add(
       "input.cameras", [](auto& o) -> auto& { return o.input.cameras; }, "",
       "camera names (also in rig.yaml); the first defines the rig frame")
      .CheckEach(CameraNameRule)
      .Check([](const CalibrationOptions& o) {
        return o.input.cameras.empty() ? "must list at least one camera" : "";
      });
  s->Add(
       "detection.subpixel_half_window_px",
       [](auto& o) -> auto& { return o.detection.subpixel_half_window_px; }, "px",
       "cv::cornerSubPix half window (5 -> 11x11)")
      .Range(Closed(1, 50));
  s->Add(
      "detection.adaptive_threshold",
      [](auto& o) -> auto& { return o.detection.adaptive_threshold; }, "",
      "adaptive threshold + normalisation in the board search");
  s->Add(
      "detection.fast_check", [](auto& o) -> auto& { return o.detection.fast_check; }, "",
      "quick rejection of images without a board");
  s->Add(
      "model.fix_k3", [](auto& o) -> auto& { return o.model.fix_k3; }, "",
      "keep k3 = 0 (free it only for wide-angle lenses)");
  s->Add(
      "model.zero_tangential", [](auto& o) -> auto& { return o.model.zero_tangential; }, "",
      "keep p1 = p2 = 0");
  s->Add(
      "model.fix_aspect_ratio", [](auto& o) -> auto& { return o.model.fix_aspect_ratio; }, "",
      "force fx = fy");
  s->Add(
       "outliers.max_rms_px", [](auto& o) -> auto& { return o.outliers.max_rms_px; }, "px",
       "images / stereo views above this reprojection RMS are listed")
      .Range(Positive());
  s->Add(
      "outliers.drop", [](auto& o) -> auto& { return o.outliers.drop; }, "",
      "recalibrate once without the outlier images");
  return s;
}

}  // namespace

const OptionSchema<CalibrationOptions>& CalibrationOptionSchema() {
  static const OptionSchema<CalibrationOptions>* const schema = BuildCalibrationOptionSchema();
  return *schema;
}

Status CalibrationOptions::Validate() const {
  return CalibrationOptionSchema().Validate(*this, nullptr);
}

StatusOr<CalibrationOptions> ParseCalibrationOptions(const YAML::Node& root,
                                                     const std::string& source_name,
                                                     const std::string& base_dir) {
  CalibrationOptions options;
  OptionSources sources;
  const OptionSchema<CalibrationOptions>& schema = CalibrationOptionSchema();
  BCOT_RETURN_IF_ERROR(schema.Parse(root, source_name, base_dir, &options, &sources));
  BCOT_RETURN_IF_ERROR(schema.Validate(options, &sources));
  return options;
}

StatusOr<CalibrationOptions> ReadCalibrationOptions(const std::string& path,
                                                    const std::vector<std::string>& overrides) {
  return CalibrationOptionSchema().Read(path, overrides);
}

std::string FormatCalibrationOptions(const CalibrationOptions& options) {
  return CalibrationOptionSchema().Emit(
      options,
      {fmt::format("bcot {}: fully resolved options (bcot {})", "calibrate", BcotVersion())});
}

}  // namespace bcot

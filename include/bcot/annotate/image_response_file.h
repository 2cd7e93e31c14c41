// image_response.yaml of an annotation: the cameras' response its edges were decoded with
// (edge.response; with `auto` the estimate of optim/response_estimation.h and every candidate's
// score), so that re-annotating frames (--frames) and regenerating the report use the same
// response as the run that wrote it.
//
//   response: gamma          # srgb | gamma | log | table
//   gamma: 1                 # with response: gamma (log_stops: S with response: log,
//                            # table_file: FILE with response: table)
//   estimated: true          # false: as configured
//   candidates:              # with estimated: every candidate's score (ResponseScore)
//     - {response: srgb, slope_px: 0.2, slope_standard_error_px: 0.03, spread_px: 0.61,
//        spread_standard_error_px: 0.03, lines: 690}
#pragma once

#include <string>
#include <vector>

#include "bcot/core/linear_rgb.h"
#include "bcot/core/status.h"
#include "bcot/optim/response_estimation.h"

namespace bcot {

inline constexpr const char* kImageResponseFileName = "image_response.yaml";

struct ImageResponseRecord {
  ImageResponse response;             // resolved (never kAuto)
  bool estimated = false;             // from the images (edge.response: auto)
  std::vector<ResponseScore> scores;  // the candidates when estimated
  std::string estimate_error;         // why the estimate failed (sRGB used), else empty
};

std::string FormatImageResponseRecord(const ImageResponseRecord& record);
// Writes `annotation_dir`/image_response.yaml atomically.
Status WriteImageResponseFile(const std::string& annotation_dir, const ImageResponseRecord& record);
// Reads it back. Errors name the file and the field.
StatusOr<ImageResponseRecord> ReadImageResponseFile(const std::string& annotation_dir);

// The response an existing annotation's edges were decoded with under `configured` (its
// edge.response): `configured` itself unless it is kAuto, else its image_response.yaml.
StatusOr<ImageResponseRecord> RecordedImageResponse(const std::string& annotation_dir,
                                                    const ImageResponse& configured);

}  // namespace bcot

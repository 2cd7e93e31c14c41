// Reading the frames of a sequence: one place that decodes an image and checks it against the
// camera that took it.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "bcot/core/camera.h"
#include "bcot/core/chroma_sampling.h"
#include "bcot/core/status.h"

namespace bcot {

// The 8-bit BGR image at `path`. kInvalidInput naming the file when it does not decode, or when
// a .jpg/.jpeg or .png file is truncated (no end marker), which the decoders would otherwise
// fill with grey rows without an error.
StatusOr<cv::Mat3b> ReadColorImage(const std::string& path);

// The same, and kInvalidInput naming the file, both sizes and the camera when the image's size
// is not `camera`'s image_size in rig.yaml.
StatusOr<cv::Mat3b> ReadCameraImage(const std::string& path, const Camera& camera);

// The chroma sampling of the image file at `path`: from its JPEG frame header alone (no pixel
// is decoded), full for any other format. kInvalidInput naming the file when it cannot be read
// or its JPEG header is corrupt.
StatusOr<ChromaSampling> ReadChromaSampling(const std::string& path);

}  // namespace bcot

// Request validation of `bcot review`'s HTTP server. The server never turns request text into a
// path: a frame index and a camera name from the URL are looked up here against the loaded
// sequence, and only the sequence's own image paths are opened. Anything else is an error
// (HTTP 400/404), never a crash.
#pragma once

#include <string>

#include "bcot/core/rig.h"
#include "bcot/core/status.h"

namespace bcot {

// One frame of one view, as indices into a Sequence (camera in rig order).
struct ReviewTarget {
  int frame = 0;
  int camera = 0;
};

// `text` must be a plain decimal index (digits only, at most 9 of them: no sign, no spaces, no
// dots or slashes) in [0, num_frames). InvalidInput for malformed text, NotFound when out of
// range; the message quotes the (length-limited) input.
StatusOr<int> ParseFrameIndex(const std::string& text, int num_frames);

// The rig index of the camera called `name`; NotFound for any other name (path-like names such
// as "../rig.yaml" are simply unknown cameras).
StatusOr<int> FindCameraIndex(const std::string& name, const Rig& rig);

// Both of the above.
StatusOr<ReviewTarget> ResolveReviewTarget(const std::string& frame_text,
                                           const std::string& camera_name, int num_frames,
                                           const Rig& rig);

}  // namespace bcot

#include "bcot/review/review_request.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace bcot {
namespace {

// The input quoted in error messages: at most 40 characters, non-printable ones as '?'.
std::string Quoted(const std::string& text) {
  std::string shown = text.substr(0, 40);
  for (char& c : shown) {
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  }
  return "'" + shown + (text.size() > 40 ? "...'" : "'");
}

}  // namespace

StatusOr<int> ParseFrameIndex(const std::string& text, int num_frames) {
  constexpr size_t kMaxDigits = 9;  // fits an int
  const bool digits =
      !text.empty() && text.size() <= kMaxDigits &&
      std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digits) {
    return Status::InvalidInput(
        fmt::format("frame {} is not a frame index (decimal digits expected)", Quoted(text)));
  }
  const int frame = std::stoi(text);
  if (frame >= num_frames) {
    return Status::NotFound(fmt::format("frame {} is out of range: the sequence has frames 0..{}",
                                        frame, num_frames - 1));
  }
  return frame;
}

StatusOr<int> FindCameraIndex(const std::string& name, const Rig& rig) {
  const int index = rig.Find(name);
  if (index < 0 || name.empty()) {
    std::string names;
    for (int c = 0; c < rig.size(); ++c) names += (c ? ", " : "") + rig[c].camera.name;
    return Status::NotFound(
        fmt::format("no camera {} in the sequence; its cameras are: {}", Quoted(name), names));
  }
  return index;
}

StatusOr<ReviewTarget> ResolveReviewTarget(const std::string& frame_text,
                                           const std::string& camera_name, int num_frames,
                                           const Rig& rig) {
  ReviewTarget target;
  BCOT_ASSIGN_OR_RETURN(target.frame, ParseFrameIndex(frame_text, num_frames));
  BCOT_ASSIGN_OR_RETURN(target.camera, FindCameraIndex(camera_name, rig));
  return target;
}

}  // namespace bcot

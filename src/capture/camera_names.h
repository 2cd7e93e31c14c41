// The rule on camera names shared by the capture layer's options (calibrate.yaml's
// input.cameras, capture.yaml's cameras): each becomes a folder of the sequence.
#pragma once

#include <string>
#include <vector>

namespace bcot::capture_internal {

// The rule camera name `names[i]` breaks (not usable as a folder name, listed before), or "".
inline std::string CameraNameRule(const std::vector<std::string>& names, size_t i) {
  const std::string& name = names[i];
  if (name.empty() || name == "." || name == ".." ||
      name.find_first_of("/\\") != std::string::npos) {
    return "must be usable as a folder name";
  }
  for (size_t j = 0; j < i; ++j) {
    if (names[j] == name) return "must not be listed twice";
  }
  return "";
}

}  // namespace bcot::capture_internal

// Helpers of the libFuzzer harnesses (tests/fuzz/CMakeLists.txt).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace bcot::fuzz {

inline std::string Text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Writes `content` to a per-process scratch file named `name` (e.g. "object.yaml") and returns
// its path: for readers whose only entry point is a path, so the harness exercises what
// `bcot` itself calls.
inline std::string ScratchFile(const std::string& name, const std::string& content) {
  static const std::string dir = [] {
    char pattern[] = "/tmp/bcot_fuzz_XXXXXX";
    const char* made = ::mkdtemp(pattern);
    return std::string(made != nullptr ? made : "/tmp");
  }();
  const std::string path = dir + "/" + name;
  if (std::FILE* file = std::fopen(path.c_str(), "wb")) {
    std::fwrite(content.data(), 1, content.size(), file);
    std::fclose(file);
  }
  return path;
}

}  // namespace bcot::fuzz

// A stable content hash of byte strings: FNV-1a, 64 bit. Not cryptographic; it detects changed
// inputs (the config and input hashes of DONE, the key of a cached viewpoint model).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace bcot {

class ContentHash {
 public:
  // Adds `bytes` and a field separator, so ("ab", "c") and ("a", "bc") differ.
  void Add(std::string_view bytes);
  // The hash so far as 16 lower-case hex digits.
  std::string Hex() const;

 private:
  void Mix(unsigned char byte) {
    hash_ ^= byte;
    hash_ *= 1099511628211ULL;
  }
  uint64_t hash_ = 14695981039346656037ULL;
};

}  // namespace bcot

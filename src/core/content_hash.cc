#include "bcot/core/content_hash.h"

#include <fmt/format.h>

namespace bcot {

void ContentHash::Add(std::string_view bytes) {
  for (unsigned char byte : bytes) Mix(byte);
  Mix(0xff);
}

std::string ContentHash::Hex() const { return fmt::format("{:016x}", hash_); }

}  // namespace bcot

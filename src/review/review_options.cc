#include "bcot/review/review_options.h"

#include <fmt/format.h>

#include <cstdio>

namespace bcot {

Status ReviewOptions::Validate() const {
  std::string errors;
  if (host.empty()) errors += "review.host is empty, must be an address to listen on\n";
  if (port < 0 || port > 65535) {
    errors += fmt::format("review.port = {}, must be in [0, 65535]\n", port);
  }
  if (jpeg_quality < 1 || jpeg_quality > 100) {
    errors += fmt::format("review.jpeg_quality = {}, must be in [1, 100]\n", jpeg_quality);
  }
  if (errors.empty()) return Status::Ok();
  errors.pop_back();
  return Status::InvalidConfig(errors);
}

bool ReviewOptions::LoopbackOnly() const { return IsLoopbackAddress(host); }

bool IsLoopbackAddress(const std::string& address) {
  if (address == "localhost" || address == "::1") return true;
  const std::string mapped = "::ffff:";
  const std::string v4 = address.rfind(mapped, 0) == 0 ? address.substr(mapped.size()) : address;
  unsigned a = 0, b = 0, c = 0, d = 0;
  char tail = 0;
  if (std::sscanf(v4.c_str(), "%u.%u.%u.%u%c", &a, &b, &c, &d, &tail) != 4) return false;
  return a == 127 && b <= 255 && c <= 255 && d <= 255;
}

}  // namespace bcot

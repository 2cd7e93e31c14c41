// Options of `bcot review`'s HTTP server.
#pragma once

#include <string>

#include "bcot/core/status.h"

namespace bcot {

struct ReviewOptions {
  // Address the server listens on. A loopback address (127.0.0.0/8, ::1, "localhost") also
  // makes the server answer 403 to any client that is not on loopback; any other address (e.g.
  // 0.0.0.0 to serve a network) is an explicit choice to accept remote clients.
  std::string host = "127.0.0.1";
  // TCP port; 0 picks a free (ephemeral) port. Range [0, 65535].
  int port = 8765;
  // Quality of the JPEG frame images, [1, 100].
  int jpeg_quality = 90;

  // Every violation, one per line ("review.port = 70000, must be in [0, 65535]").
  Status Validate() const;
  // Whether clients other than loopback ones are refused (`host` is a loopback address).
  bool LoopbackOnly() const;
};

// Whether `address` (an IPv4/IPv6 literal, or "localhost") is a loopback address: 127.x.y.z,
// ::1, ::ffff:127.x.y.z or localhost.
bool IsLoopbackAddress(const std::string& address);

}  // namespace bcot

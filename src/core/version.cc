#include <fmt/format.h>

#include <chrono>
#include <ctime>

#include "bcot/core/version.h"

namespace bcot {

Provenance CurrentProvenance(const std::string& config_hash) {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);  // thread-safe, unlike std::gmtime
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return Provenance{BcotVersion(), buffer, config_hash};
}

std::string FormatProvenance(const Provenance& provenance) {
  std::string line = fmt::format("bcot {}, {}", provenance.bcot_version, provenance.created_utc);
  if (!provenance.config_hash.empty()) line += ", config " + provenance.config_hash;
  return line;
}

}  // namespace bcot

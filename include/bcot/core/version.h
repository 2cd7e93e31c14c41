// bcot's version and the provenance stamped into every output header (report.html,
// summary.html, config.resolved.yaml, quality.json, summary.json).
#pragma once

#include <string>

namespace bcot {

// PROJECT_VERSION, plus "+g<git describe>" in a git checkout (e.g. "0.9.0+g1a2b3c4d5e-dirty");
// generated at build time by cmake/write_version.cmake.
const char* BcotVersion();

// Who wrote an output and from what: the version, the time (UTC, ISO 8601) and the hash of
// the options that produced it (empty when the output has no config).
struct Provenance {
  std::string bcot_version;
  std::string created_utc;
  std::string config_hash;
};
// The provenance of an output written now.
Provenance CurrentProvenance(const std::string& config_hash);
// One line for text headers: "bcot <version>, <time>, config <hash>".
std::string FormatProvenance(const Provenance& provenance);

}  // namespace bcot

// Internal helpers of the capture layer's option readers (calibrate.yaml, capture.yaml):
// loading a config file with `--set` overrides, strict sections, violation lists.
#pragma once

#include <yaml-cpp/yaml.h>

#include <functional>
#include <string>
#include <vector>

#include "bcot/core/status.h"
#include "bcot/core/yaml_util.h"

namespace bcot::capture_internal {

// The parsed config at `path` (an empty mapping when `path` is empty) with `overrides`
// ("section.key=value") applied. Every error is kInvalidConfig.
StatusOr<YAML::Node> LoadConfig(const std::string& path, const std::vector<std::string>& overrides);

// "--set" when `path` is empty (only overrides), else `path`.
std::string ConfigSourceName(const std::string& path);
// The folder that relative paths in the config at `path` refer to ("" for no file).
std::string ConfigBaseDir(const std::string& path);

// LoadConfig, then `parse(root, source_name, base_dir)`: the Read*Options entry points.
template <typename Options, typename Parse>
StatusOr<Options> ReadOptions(const std::string& path, const std::vector<std::string>& overrides,
                              const Parse& parse) {
  BCOT_ASSIGN_OR_RETURN(const YAML::Node root, LoadConfig(path, overrides));
  return parse(root, ConfigSourceName(path), ConfigBaseDir(path));
}

// The parsed options, or InvalidConfig "source_name: <every violation>".
template <typename Options>
StatusOr<Options> Validated(Options options, const std::string& source_name) {
  const Status valid = options.Validate();
  if (!valid.ok()) return Status::InvalidConfig(source_name + ": " + valid.message());
  return options;
}

// `path` resolved against `base_dir` unless empty or absolute.
std::string ResolveConfigPath(const std::string& base_dir, const std::string& path);

// Runs `parse` on root[section] when present, then rejects unknown keys of the section.
Status ParseSection(YamlMap& root, const std::string& section,
                    const std::function<Status(YamlMap&)>& parse);

// Any error as kInvalidConfig (a config file's syntax error is the user's to fix).
Status AsConfigError(const Status& status);

// Collects "field = value, rule" messages; Join gives one kInvalidConfig status.
class Violations {
 public:
  void Add(const std::string& field, const std::string& value, const std::string& rule);
  // Closed range [lo, hi]; NaN fails.
  void InRange(const std::string& field, double value, double lo, double hi);
  void Positive(const std::string& field, double value);
  void OneOf(const std::string& field, const std::string& value,
             const std::vector<std::string>& allowed);
  // Camera names: each non-empty, usable as a folder name, unique; `field` is "input.cameras"
  // or "cameras" (elements are reported as field[i]).
  void CameraNames(const std::string& field, const std::vector<std::string>& names);
  Status ToStatus(const std::string& context) const;  // OK when empty; "context: a; b"

 private:
  std::vector<std::string> messages_;
};

}  // namespace bcot::capture_internal

// Helpers of the option readers: a config file with `--set` overrides applied, and messages
// joined into one status text.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "bcot/core/status.h"
#include "bcot/core/yaml_util.h"

namespace bcot {

// Messages joined by "; ".
inline std::string JoinMessages(const std::vector<std::string>& messages) {
  std::string joined;
  for (const std::string& m : messages) joined += (joined.empty() ? "" : "; ") + m;
  return joined;
}

// The config document at `path` (empty = an empty mapping) with `overrides` applied; errors are
// kInvalidConfig. `*source` receives the name messages should use: the path, or "--set".
inline StatusOr<YAML::Node> LoadConfigWithOverrides(const std::string& path,
                                                    const std::vector<std::string>& overrides,
                                                    std::string* source) {
  YAML::Node root(YAML::NodeType::Map);
  *source = "--set";
  if (!path.empty()) {
    BCOT_ASSIGN_OR_RETURN(root, LoadYamlFile(path, StatusCode::kInvalidConfig));
    *source = path;
  }
  if (!overrides.empty()) {
    if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    BCOT_RETURN_IF_ERROR(ApplyYamlOverrides(overrides, &root));
  }
  return root;
}

}  // namespace bcot

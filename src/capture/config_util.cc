#include "config_util.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <set>

namespace bcot::capture_internal {

Status AsConfigError(const Status& status) {
  if (status.ok() || status.code() == StatusCode::kInvalidConfig) return status;
  return Status::InvalidConfig(status.message());
}

StatusOr<YAML::Node> LoadConfig(const std::string& path,
                                const std::vector<std::string>& overrides) {
  YAML::Node root(YAML::NodeType::Map);
  if (!path.empty()) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
      return Status::InvalidConfig(fmt::format("{}: config file not found", path));
    }
    StatusOr<YAML::Node> loaded = LoadYamlFile(path, StatusCode::kInvalidConfig);
    if (!loaded.ok()) return AsConfigError(loaded.status());
    root = *loaded;
  }
  if (!overrides.empty()) {
    if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    BCOT_RETURN_IF_ERROR(AsConfigError(ApplyYamlOverrides(overrides, &root)));
  }
  return root;
}

std::string ConfigSourceName(const std::string& path) { return path.empty() ? "--set" : path; }

std::string ConfigBaseDir(const std::string& path) {
  return path.empty() ? std::string() : std::filesystem::path(path).parent_path().string();
}

std::string ResolveConfigPath(const std::string& base_dir, const std::string& path) {
  if (path.empty()) return path;
  const std::filesystem::path p(path);
  if (p.is_absolute() || base_dir.empty()) return p.lexically_normal().string();
  return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

Status ParseSection(YamlMap& root, const std::string& section,
                    const std::function<Status(YamlMap&)>& parse) {
  if (!root.Has(section)) return Status::Ok();
  YamlMap map(root.Node(section), root.source_name(), section, StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(map.Check());
  BCOT_RETURN_IF_ERROR(parse(map));
  return map.CheckNoUnknownKeys();
}

void Violations::Add(const std::string& field, const std::string& value, const std::string& rule) {
  messages_.push_back(fmt::format("{} = {}, {}", field, value, rule));
}

void Violations::InRange(const std::string& field, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi)) {
    Add(field, fmt::format("{}", value), fmt::format("must be in [{}, {}]", lo, hi));
  }
}

void Violations::Positive(const std::string& field, double value) {
  if (!(value > 0.0 && std::isfinite(value))) Add(field, fmt::format("{}", value), "must be > 0");
}

void Violations::OneOf(const std::string& field, const std::string& value,
                       const std::vector<std::string>& allowed) {
  for (const std::string& candidate : allowed) {
    if (value == candidate) return;
  }
  Add(field, "'" + value + "'", fmt::format("must be one of {}", fmt::join(allowed, ", ")));
}

void Violations::CameraNames(const std::string& field, const std::vector<std::string>& names) {
  std::set<std::string> seen;
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    const std::string element = fmt::format("{}[{}]", field, i);
    if (name.empty() || name == "." || name == ".." ||
        name.find_first_of("/\\") != std::string::npos) {
      Add(element, "'" + name + "'", "must be usable as a folder name");
    } else if (!seen.insert(name).second) {
      Add(element, "'" + name + "'", "is listed twice");
    }
  }
}

Status Violations::ToStatus(const std::string& context) const {
  if (messages_.empty()) return Status::Ok();
  return Status::InvalidConfig(fmt::format("{}: {}", context, fmt::join(messages_, "; ")));
}

}  // namespace bcot::capture_internal

#include "bcot/core/object_io.h"

#include <filesystem>

#include <fmt/format.h>

#include "bcot/core/file_util.h"
#include "bcot/core/yaml_util.h"

namespace bcot {
namespace {

StatusOr<ObjectSpec> ReadObject(const std::string& path, bool check_mesh) {
  BCOT_ASSIGN_OR_RETURN(const YAML::Node root, LoadYamlFile(path));
  YamlMap map(root, path, "");
  ObjectSpec object;
  BCOT_RETURN_IF_ERROR(map.Get("name", &object.name));
  if (object.name.empty()) return map.Error("name", "must not be empty");
  BCOT_RETURN_IF_ERROR(map.Get("mesh", &object.mesh));
  if (object.mesh.empty()) return map.Error("mesh", "must not be empty");
  BCOT_RETURN_IF_ERROR(map.GetOptional("unit_to_mm", &object.unit_to_mm));
  if (!(object.unit_to_mm > 0.0)) {
    return map.Error("unit_to_mm", fmt::format("{} must be > 0 (mesh units × unit_to_mm = mm)",
                                               object.unit_to_mm));
  }
  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());
  object.mesh_path = ResolveRelativeTo(path, object.mesh);

  if (check_mesh) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(object.mesh_path, error)) {
      const bool exists = std::filesystem::exists(object.mesh_path, error);
      const std::string problem = exists
                                      ? fmt::format("'{}' is not a regular file", object.mesh_path)
                                      : fmt::format("mesh file '{}' not found", object.mesh_path);
      const Status status = map.Error("mesh", problem);
      return exists ? Status::InvalidInput(status.message()) : Status::NotFound(status.message());
    }
  }
  return object;
}

}  // namespace

StatusOr<ObjectSpec> ReadObjectYaml(const std::string& path) { return ReadObject(path, false); }

StatusOr<ObjectSpec> ReadObjectYamlAndCheckMesh(const std::string& path) {
  return ReadObject(path, true);
}

std::string FormatObjectYaml(const ObjectSpec& object) {
  return fmt::format("name: {}\nmesh: {}\nunit_to_mm: {}\n", FormatYamlString(object.name),
                     FormatYamlString(object.mesh), object.unit_to_mm);
}

Status WriteObjectYaml(const std::string& path, const ObjectSpec& object) {
  return WriteFileAtomic(path, FormatObjectYaml(object));
}

}  // namespace bcot

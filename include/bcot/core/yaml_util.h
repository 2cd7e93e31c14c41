// Strict YAML reading: every message names the file, the 1-based line and the key path;
// unknown keys and duplicate keys are errors (yaml-cpp silently keeps the first duplicate).
//
//   YamlMap map(node, "rig.yaml", "cameras[0]");
//   double fx; BCOT_RETURN_IF_ERROR(map.Get("fx", &fx));              // required
//   BCOT_RETURN_IF_ERROR(map.GetOptional("unit_to_mm", &unit));       // keeps default if absent
//   BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());                   // after all Get calls
//
// Errors use the StatusCode given to YamlMap: kInvalidInput (default) for data files such as
// rig.yaml, kInvalidConfig for tool configs. Keys are compared as written (case-sensitive).
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

#include "bcot/core/status.h"

namespace bcot {

// The source name of values given on the command line (`--set`): messages about them read
// "--set frame.rounds: ..." instead of "file:line: frame.rounds: ...".
inline constexpr const char kCommandLineSource[] = "--set";

// "location: key.path", or "--set key.path" when `location` is kCommandLineSource.
std::string JoinWhere(const std::string& location, const std::string& key_path);

// Parses YAML text; a syntax error names source:line. More than one document is an error;
// an empty text gives a Null node; so is a document of more than 100,000 nodes (counting
// aliases as often as they are used) or nested deeper than 64 levels. `code` is the StatusCode
// of these errors.
StatusOr<YAML::Node> ParseYaml(const std::string& text, const std::string& source_name,
                               StatusCode code = StatusCode::kInvalidInput);
// Reads and parses a file (NotFound / IoError when it cannot be read).
StatusOr<YAML::Node> LoadYamlFile(const std::string& path,
                                  StatusCode code = StatusCode::kInvalidInput);

// "file:line" for a node (line 1-based), or just "file" when the node has no mark.
std::string YamlWhere(const std::string& source_name, const YAML::Node& node);

// `value` as a YAML scalar that reads back as the same string: plain when that is unambiguous
// (`cam0`, `../models/cat.obj`), double-quoted with escapes otherwise (`"true"`, `"1.5"`,
// `"a: b"`, `""`). For writers of YAML files.
std::string FormatYamlString(const std::string& value);

// Applies command-line overrides `section.key=value` (`--set`) to a parsed config. The key
// path has one or more dot-separated components ([A-Za-z0-9_-]+); the value is parsed as YAML,
// so `[1, 2]`, `true` and `{a: 1}` work. Missing sections and keys are created (the struct
// reader then rejects unknown keys as usual); a Null section becomes a mapping; descending into
// a scalar or sequence is an error. Overridden values carry no line mark, so later messages
// about them name only the file. A Null or undefined `root` becomes a mapping. Errors are
// InvalidConfig and quote the override.
Status ApplyYamlOverrides(const std::vector<std::string>& overrides, YAML::Node* root);

// A strict view of one YAML mapping. Not thread-safe (records which keys were read).
class YamlMap {
 public:
  // `path` is the key path of this mapping in messages ("" for the document root). A Null or
  // undefined node (an empty file or an empty section) reads as an empty mapping. `code` is
  // the StatusCode of every error this map reports.
  YamlMap(YAML::Node node, std::string source_name, std::string path,
          StatusCode code = StatusCode::kInvalidInput);

  // Non-OK when the node is not a mapping, has a non-scalar key or duplicate keys. Get,
  // GetOptional, GetFixedArray and CheckNoUnknownKeys return this error first, so calling
  // Check() explicitly is optional.
  Status Check() const;

  bool Has(const std::string& key) const;
  YAML::Node Node(const std::string& key) const;      // marks the key as used
  std::string KeyPath(const std::string& key) const;  // "cameras[0].K"
  std::string Where(const std::string& key) const;    // "rig.yaml:7: cameras[0].K"

  // Scalars: bool, int, double, std::string. Sequences: std::vector<int|double|std::string>.
  // bool accepts true/false in any letter case (not yes/no/on/off); int rejects fractions and
  // out-of-range values; double must be finite (.inf/.nan are rejected); std::string takes any
  // scalar as written but not null/~. Get errors when the key is missing; GetOptional leaves
  // `*value` unchanged then. Both mark `key` as known.
  template <typename T>
  Status Get(const std::string& key, T* value);
  template <typename T>
  Status GetOptional(const std::string& key, T* value);

  // An optional string whose value must be one of `names`: `*index` becomes its position in
  // `names` (unchanged when the key is absent); another value is an error listing the choices
  // ("'x' is not one of a | b").
  Status GetOptionalChoice(const std::string& key, const std::vector<std::string>& names,
                           int* index);

  // Fixed-length numeric sequence, e.g. K (4) or cam_from_rig (16). Required.
  Status GetFixedArray(const std::string& key, size_t expected_size, std::vector<double>* values);

  // Error naming the first key (in document order) not read with Get/GetOptional/Node/
  // GetFixedArray, the keys that are known and the closest one ("did you mean").
  Status CheckNoUnknownKeys() const;

  // `Where(key): problem` with this map's StatusCode, for validation of values read from it:
  //   return map.Error("band_px", fmt::format("{} must be > 0", band_px));
  Status Error(const std::string& key, const std::string& problem) const;
  // "file:line" of `key` (the key's line), of the mapping when `key` is absent, or just "file"
  // when there is no line to claim (a value set by ApplyYamlOverrides, an empty section).
  std::string Location(const std::string& key) const;
  StatusCode code() const { return code_; }

  const YAML::Node& node() const { return node_; }
  const std::string& source_name() const { return source_name_; }
  const std::string& path() const { return path_; }

 private:
  struct Entry {
    std::string key;
    YAML::Node key_node;
    YAML::Node value;
  };
  const Entry* Find(const std::string& key) const;
  Status MakeError(const std::string& where, const std::string& problem) const;

  YAML::Node node_;
  std::string source_name_;
  std::string path_;
  StatusCode code_;
  std::vector<Entry> entries_;  // in document order; built once by the constructor
  Status check_;                // result of Check(), computed by the constructor
  mutable std::set<std::string> used_;
};

}  // namespace bcot

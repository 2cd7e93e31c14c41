// One declaration per option of a command, and everything derived from it: strict YAML
// parsing with file:line: key locations, `--set section.key=value` overrides (whose errors
// name `--set`), validation that names where each offending value came from, the resolved
// config written back with yaml-cpp's emitter, and the option list of `--help`.
//
//   OptionSchema<QualityOptions> schema;
//   schema.Add("quality.threshold_px", [](auto& o) -> auto& { return o.threshold_px; }, "px",
//              "a frame-view is bad when its statistic exceeds this")
//       .Range(Positive());
//   schema.AddChoice("quality.statistic", [](auto& o) -> auto& { return o.statistic; },
//                    {{"median", QualityStatistic::kMedian}, {"p90", QualityStatistic::kP90}},
//                    "statistic compared with threshold_px");
//   StatusOr<QualityOptions> options = schema.Read("run.yaml", {"quality.threshold_px=3"});
//
// The accessor is a generic lambda returning a reference to the field, so one accessor serves
// reading (const options) and writing. The default shown by --help is the field's value in a
// default-constructed Options (the struct's in-class default). Keys are "key" (top level) or
// "section.key" (any depth). Field types: bool, int, double, std::string, std::vector of
// int/double/std::string, std::array<double, N>; AddChoice takes any value type comparable
// with == (enums, std::optional<enum>, std::string); AddCustom any type with its own YAML
// reader and writer (capture's list of cameras).
//
// Messages:
//   run.yaml:3: frame.rounds: expected an integer, got 'abc'          (type, from the file)
//   --set frame.rounds: expected an integer, got 'abc'                (type, from --set)
//   run.yaml:2: frame.roundz: unknown key (did you mean 'rounds'?); known keys: <all of frame>
//   run.yaml:3: frame.rounds = 0, must be >= 1                        (rule, from the file)
//   --set frame.rounds = 0, must be >= 1                              (rule, from --set)
//   frame.rounds = 0 (default), must be >= 1                          (rule, value not set)
// Every rule violation is reported, joined by "; "; all errors are kInvalidConfig.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "bcot/core/status.h"
#include "bcot/core/yaml_util.h"

namespace bcot {

// An interval a numeric option (or every element of a numeric list) must lie in.
struct OptionRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  bool Contains(double value) const;
  // "> 0", ">= 1", "<= 5", "[0, 1]", "(0, 0.5)": for rules and --help.
  std::string Text() const;
};
OptionRange Positive();                      // > 0
OptionRange NonNegative();                   // >= 0
OptionRange AtLeast(double lo);              // >= lo
OptionRange Closed(double lo, double hi);    // [lo, hi]
OptionRange Open(double lo, double hi);      // (lo, hi)
OptionRange LeftOpen(double lo, double hi);  // (lo, hi]

// Where each option's value came from, by key: "run.yaml:3", "run.yaml" (no line) or "--set".
// Options absent from the map kept their defaults.
using OptionSources = std::map<std::string, std::string>;

namespace option_internal {

// The type-independent part of one declaration.
struct OptionInfo {
  std::string key;      // "frame.rounds"
  std::string section;  // "frame" ("" at the top level)
  std::string name;     // "rounds"
  std::string unit;     // "px", "deg", "" ...
  std::string help;     // one line
  std::string choices;  // "a | b" for choice options, else ""
  bool has_range = false;
  OptionRange range;
  std::vector<std::string> element_names;  // {"x", "y", "z"}: list elements in messages
  bool is_path = false;                    // strings resolved against the config file's folder
  bool is_list = false;             // a std::vector or std::array: ranges apply to every element
  std::vector<std::string> one_of;  // allowed strings (OneOf), empty = any
  std::function<std::string(const std::vector<std::string>&, size_t)> element_rule;  // CheckEach
};

// The strings OneOf applies to (none for other types).
template <typename T>
std::vector<std::string> Strings(const T& value) {
  if constexpr (std::is_same_v<T, std::string>) {
    return {value};
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    return value;
  } else {
    return {};
  }
}

// "key = value, rule" for every element of `values` outside the rule ("key[i] = ..." or
// "key = value (name)" for lists).
std::vector<std::string> ElementViolations(const OptionInfo& info, const std::string& source,
                                           const std::vector<double>& numbers,
                                           const std::vector<std::string>& strings);

template <typename T>
struct IsList : std::false_type {};
template <typename T>
struct IsList<std::vector<T>> : std::true_type {};
template <typename T, size_t N>
struct IsList<std::array<T, N>> : std::true_type {};

// One violated rule of a part of an option (an element of a list of mappings, say):
// "key = value, rule" with key "cameras[1].gain".
struct PartViolation {
  std::string key;
  std::string value;
  std::string rule;
};

// "where: key = value, rule"; "key = value (default), rule" when `source` is empty (not set);
// "key = value, rule" when `source` is "-" (not located).
std::string Violation(const std::string& source, const std::string& key, const std::string& value,
                      const std::string& rule);
// `path` resolved against `base_dir` unless empty or absolute.
std::string ResolvePath(const std::string& base_dir, const std::string& path);
// The --help list ("  section.key = default [unit] (rule)  help"), one line per option.
std::string HelpText(const std::vector<std::pair<const OptionInfo*, std::string>>& options);

// Value text for messages and --help; numbers in shortest round-trip form.
std::string ValueText(bool value);
std::string ValueText(int value);
std::string ValueText(double value);
std::string ValueText(const std::string& value);
template <typename T>
std::string ValueText(const std::vector<T>& values) {
  std::string text = "[";
  for (size_t i = 0; i < values.size(); ++i) text += (i > 0 ? ", " : "") + ValueText(values[i]);
  return text + "]";
}
template <size_t N>
std::string ValueText(const std::array<double, N>& values) {
  return ValueText(std::vector<double>(values.begin(), values.end()));
}

// The same as YAML into an emitter (strings quoted when a plain scalar would read differently).
void EmitValue(YAML::Emitter& out, bool value);
void EmitValue(YAML::Emitter& out, int value);
void EmitValue(YAML::Emitter& out, double value);
void EmitValue(YAML::Emitter& out, const std::string& value);
template <typename T>
void EmitValue(YAML::Emitter& out, const std::vector<T>& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const T& value : values) EmitValue(out, value);
  out << YAML::EndSeq;
}
template <size_t N>
void EmitValue(YAML::Emitter& out, const std::array<double, N>& values) {
  EmitValue(out, std::vector<double>(values.begin(), values.end()));
}

// The numbers a range applies to (none for strings and booleans).
inline std::vector<double> Numbers(bool) { return {}; }
inline std::vector<double> Numbers(int value) { return {static_cast<double>(value)}; }
inline std::vector<double> Numbers(double value) { return {value}; }
inline std::vector<double> Numbers(const std::string&) { return {}; }
inline std::vector<double> Numbers(const std::vector<std::string>&) { return {}; }
template <typename T>
std::vector<double> Numbers(const std::vector<T>& values) {
  return std::vector<double>(values.begin(), values.end());
}
template <size_t N>
std::vector<double> Numbers(const std::array<double, N>& values) {
  return std::vector<double>(values.begin(), values.end());
}

// Reads `map[name]` into `*value` when present (YamlMap's strict scalar and list rules).
Status ReadValue(YamlMap& map, const std::string& name, bool* value);
Status ReadValue(YamlMap& map, const std::string& name, int* value);
Status ReadValue(YamlMap& map, const std::string& name, double* value);
Status ReadValue(YamlMap& map, const std::string& name, std::string* value);
Status ReadValue(YamlMap& map, const std::string& name, std::vector<int>* value);
Status ReadValue(YamlMap& map, const std::string& name, std::vector<double>* value);
Status ReadValue(YamlMap& map, const std::string& name, std::vector<std::string>* value);
// A fixed-length list: "has 2 values, expected 3 (x, y, z)" when the length differs.
Status ReadFixedList(YamlMap& map, const std::string& name, size_t size,
                     const std::vector<std::string>& element_names, std::vector<double>* values);
template <size_t N>
Status ReadValue(YamlMap& map, const std::string& name,
                 const std::vector<std::string>& element_names, std::array<double, N>* value) {
  if (!map.Has(name)) {
    map.Node(name);  // known, absent
    return Status::Ok();
  }
  std::vector<double> values;
  BCOT_RETURN_IF_ERROR(ReadFixedList(map, name, N, element_names, &values));
  for (size_t i = 0; i < N; ++i) (*value)[i] = values[i];
  return Status::Ok();
}
template <typename T>
Status ReadValue(YamlMap& map, const std::string& name, const std::vector<std::string>&, T* value) {
  return ReadValue(map, name, value);
}

}  // namespace option_internal

template <typename Options>
class OptionSchema {
 public:
  // One declaration; the setters return it for chaining.
  class Option {
   public:
    Option() = default;
    // The value (every element of a list) must lie in `range`.
    Option& Range(const OptionRange& range) {
      info_.has_range = true;
      info_.range = range;
      return *this;
    }
    // The string (every element of a string list) must be one of `names`. Unlike AddChoice the
    // value is checked with the other rules, so every bad value is listed at once.
    Option& OneOf(std::vector<std::string> names) {
      info_.one_of = std::move(names);
      return *this;
    }
    // A rule on each element of a string list: `rule(list, i)` returns "" when element i is
    // fine, else the rule ("must not be listed twice"); reported as "key[i] = value, rule".
    Option& CheckEach(std::function<std::string(const std::vector<std::string>&, size_t)> rule) {
      info_.element_rule = std::move(rule);
      return *this;
    }
    // A rule across fields: `rule(options)` returns "" when satisfied, else the rule as it
    // follows "key = value, " ("must be > scale_px").
    Option& Check(std::function<std::string(const Options&)> rule) {
      checks_.push_back(std::move(rule));
      return *this;
    }
    // Rules on the parts of the option's value: `rules(options)` lists every violation, each
    // with the key of its part ("cameras[1].gain"); located like the option itself.
    Option& CheckParts(
        std::function<std::vector<option_internal::PartViolation>(const Options&)> rules) {
      part_checks_.push_back(std::move(rules));
      return *this;
    }
    // Names of the elements of a fixed-length list in messages ("x", "y", "z").
    Option& Elements(std::vector<std::string> names) {
      info_.element_names = std::move(names);
      return *this;
    }
    // A file path (or list of paths): relative ones in a config file are resolved against the
    // file's folder, those of --set against the working directory.
    Option& Path() {
      info_.is_path = true;
      return *this;
    }
    const option_internal::OptionInfo& info() const { return info_; }

   private:
    template <typename>
    friend class OptionSchema;
    option_internal::OptionInfo info_;
    std::function<Status(YamlMap&, const std::string& base_dir, Options*)> read_;
    std::function<void(YAML::Emitter&, const Options&)> emit_;
    std::function<std::string(const Options&)> text_;
    std::function<std::vector<double>(const Options&)> numbers_;
    std::function<std::vector<std::string>(const Options&)> strings_;
    std::vector<std::function<std::string(const Options&)>> checks_;
    std::vector<std::function<std::vector<option_internal::PartViolation>(const Options&)>>
        part_checks_;
  };

  // A plain option: `access(options)` is a reference to the field.
  template <typename Access>
  Option& Add(const std::string& key, Access access, const std::string& unit,
              const std::string& help) {
    using T = std::remove_cv_t<std::remove_reference_t<decltype(access(std::declval<Options&>()))>>;
    Option& option = NewOption(key, unit, help);
    option.info_.is_list = option_internal::IsList<T>::value;
    const option_internal::OptionInfo* info = &option.info_;
    option.read_ = [access, info](YamlMap& map, const std::string& base_dir, Options* o) {
      T& field = access(*o);
      BCOT_RETURN_IF_ERROR(
          option_internal::ReadValue(map, info->name, info->element_names, &field));
      if constexpr (std::is_same_v<T, std::string>) {
        if (info->is_path && map.Has(info->name)) {
          field = option_internal::ResolvePath(base_dir, field);
        }
      } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
        if (info->is_path && map.Has(info->name)) {
          for (std::string& path : field) path = option_internal::ResolvePath(base_dir, path);
        }
      }
      return Status::Ok();
    };
    option.emit_ = [access](YAML::Emitter& out, const Options& o) {
      option_internal::EmitValue(out, access(o));
    };
    option.text_ = [access](const Options& o) { return option_internal::ValueText(access(o)); };
    option.numbers_ = [access](const Options& o) { return option_internal::Numbers(access(o)); };
    option.strings_ = [access](const Options& o) { return option_internal::Strings(access(o)); };
    return option;
  }

  // An option whose YAML value is one of `choices` (name → field value), in this order.
  template <typename Access, typename Value>
  Option& AddChoice(const std::string& key, Access access,
                    std::vector<std::pair<std::string, Value>> choices, const std::string& help) {
    Option& option = NewOption(key, "", help);
    std::vector<std::string> names;
    for (const auto& choice : choices) names.push_back(choice.first);
    for (size_t i = 0; i < names.size(); ++i) {
      option.info_.choices += (i > 0 ? " | " : "") + names[i];
    }
    const option_internal::OptionInfo* info = &option.info_;
    option.read_ = [access, info, names, choices](YamlMap& map, const std::string&, Options* o) {
      int index = -1;
      BCOT_RETURN_IF_ERROR(map.GetOptionalChoice(info->name, names, &index));
      if (index >= 0) access(*o) = choices[index].second;
      return Status::Ok();
    };
    auto name_of = [access, choices](const Options& o) {
      for (const auto& choice : choices) {
        if (choice.second == access(o)) return choice.first;
      }
      return std::string("?");
    };
    option.emit_ = [name_of](YAML::Emitter& out, const Options& o) {
      option_internal::EmitValue(out, name_of(o));
    };
    option.text_ = name_of;
    option.numbers_ = [](const Options&) { return std::vector<double>(); };
    option.strings_ = [](const Options&) { return std::vector<std::string>(); };
    return option;
  }

  // An option of a type the plain readers do not cover (a list of mappings, say), with its own
  // reader and writer: `read(map, base_dir, &field)` reads map[name] (called only when the key
  // is present; YamlMap gives its location), `emit(out, field)` writes it so that `read` gives
  // it back, `text(field)` is its text in messages and --help. Rules: Check / CheckParts.
  template <typename Access, typename Read, typename Emit, typename Text>
  Option& AddCustom(const std::string& key, Access access, Read read, Emit emit, Text text,
                    const std::string& help) {
    Option& option = NewOption(key, "", help);
    const option_internal::OptionInfo* info = &option.info_;
    option.read_ = [access, info, read](YamlMap& map, const std::string& base_dir, Options* o) {
      if (!map.Has(info->name)) {
        map.Node(info->name);  // known, absent
        return Status::Ok();
      }
      return read(map, base_dir, &access(*o));
    };
    option.emit_ = [access, emit](YAML::Emitter& out, const Options& o) { emit(out, access(o)); };
    option.text_ = [access, text](const Options& o) { return text(access(o)); };
    option.numbers_ = [](const Options&) { return std::vector<double>(); };
    option.strings_ = [](const Options&) { return std::vector<std::string>(); };
    return option;
  }

  // Declares every option of `inner` (same keys) on the part `access(options)` of these
  // options: a command's schema made of its layers' schemas.
  template <typename Inner, typename Access>
  void Include(const OptionSchema<Inner>& inner, Access access) {
    for (const auto& inner_option : inner.options()) {
      const auto& in = *inner_option;
      auto option = std::make_unique<Option>();
      option->info_ = in.info_;
      option->read_ = [read = in.read_, access](YamlMap& map, const std::string& base_dir,
                                                Options* o) {
        return read(map, base_dir, &access(*o));
      };
      option->emit_ = [emit = in.emit_, access](YAML::Emitter& out, const Options& o) {
        emit(out, access(o));
      };
      option->text_ = [text = in.text_, access](const Options& o) { return text(access(o)); };
      option->numbers_ = [numbers = in.numbers_, access](const Options& o) {
        return numbers(access(o));
      };
      option->strings_ = [strings = in.strings_, access](const Options& o) {
        return strings(access(o));
      };
      for (const auto& check : in.checks_) {
        option->checks_.push_back([check, access](const Options& o) { return check(access(o)); });
      }
      for (const auto& check : in.part_checks_) {
        option->part_checks_.push_back(
            [check, access](const Options& o) { return check(access(o)); });
      }
      options_.push_back(std::move(option));
    }
  }

  // Parses a YAML document into `*options` (keys absent keep their values); records where each
  // value came from in `*sources` (may be null). Unknown keys are errors listing every key
  // declared at that level. Relative paths resolve against `base_dir`. No rule is checked.
  Status Parse(const YAML::Node& root, const std::string& source_name, const std::string& base_dir,
               Options* options, OptionSources* sources) const {
    if (!root.IsDefined() || root.IsNull()) return Status::Ok();
    return ParseLevel(root, source_name, "", base_dir, options, sources);
  }

  // Applies `section.key=value` overrides (values are YAML); errors name `--set key`.
  Status ApplyOverrides(const std::vector<std::string>& overrides, Options* options,
                        OptionSources* sources) const {
    if (overrides.empty()) return Status::Ok();
    YAML::Node tree(YAML::NodeType::Map);
    BCOT_RETURN_IF_ERROR(ApplyYamlOverrides(overrides, &tree));
    return Parse(tree, kCommandLineSource, "", options, sources);
  }

  // Every violated rule (ranges, then cross-field checks, in declaration order), each named by
  // where its value came from; OK when none. `sources` may be null (no locations).
  Status Validate(const Options& options, const OptionSources* sources) const {
    std::vector<std::string> violations;
    for (const std::unique_ptr<Option>& option : options_) {
      const option_internal::OptionInfo& info = option->info_;
      // "" = the value was not set (default); a null `sources` locates nothing.
      std::string source = sources == nullptr ? kUnlocated : "";
      if (sources != nullptr) {
        const auto it = sources->find(info.key);
        if (it != sources->end()) source = it->second;
      }
      for (std::string& violation : option_internal::ElementViolations(
               info, source, option->numbers_(options), option->strings_(options))) {
        violations.push_back(std::move(violation));
      }
      for (const auto& check : option->checks_) {
        const std::string rule = check(options);
        if (!rule.empty()) {
          violations.push_back(
              option_internal::Violation(source, info.key, option->text_(options), rule));
        }
      }
      for (const auto& check : option->part_checks_) {
        for (const option_internal::PartViolation& part : check(options)) {
          violations.push_back(option_internal::Violation(source, part.key, part.value, part.rule));
        }
      }
    }
    if (violations.empty()) return Status::Ok();
    std::string message = violations[0];
    for (size_t i = 1; i < violations.size(); ++i) message += "; " + violations[i];
    return Status::InvalidConfig(message);
  }

  // The config file at `path` (empty = none) with `overrides` applied on top, validated.
  StatusOr<Options> Read(const std::string& path, const std::vector<std::string>& overrides,
                         OptionSources* sources_out = nullptr) const {
    return ReadOnto(Options(), path, overrides, sources_out);
  }

  // The same starting from `base` instead of the defaults (a command's preset): keys neither
  // the file nor `overrides` set keep base's values.
  StatusOr<Options> ReadOnto(const Options& base, const std::string& path,
                             const std::vector<std::string>& overrides,
                             OptionSources* sources_out = nullptr) const {
    Options options = base;
    OptionSources sources;
    if (!path.empty()) {
      StatusOr<YAML::Node> root = LoadYamlFile(path, StatusCode::kInvalidConfig);
      if (!root.ok()) return Status::InvalidConfig(root.status().message());
      BCOT_RETURN_IF_ERROR(Parse(*root, path, ParentDir(path), &options, &sources));
    }
    BCOT_RETURN_IF_ERROR(ApplyOverrides(overrides, &options, &sources));
    BCOT_RETURN_IF_ERROR(Validate(options, &sources));
    if (sources_out != nullptr) *sources_out = std::move(sources);
    return options;
  }

  // Every option as YAML (sections in declaration order), preceded by `comment` lines (each
  // written as "# line"); Parse of the text gives the same options.
  std::string Emit(const Options& options, const std::vector<std::string>& comment = {}) const {
    YAML::Emitter out;
    for (const std::string& line : comment) out << YAML::Comment(line) << YAML::Newline;
    out << YAML::BeginMap;
    EmitLevel(out, options, "");
    out << YAML::EndMap;
    return std::string(out.c_str()) + "\n";
  }

  // One line per option: key, default, unit, rule and help (for a command's --help).
  std::string Help() const {
    const Options defaults{};
    std::vector<std::pair<const option_internal::OptionInfo*, std::string>> lines;
    for (const std::unique_ptr<Option>& option : options_) {
      lines.emplace_back(&option->info_, option->text_(defaults));
    }
    return option_internal::HelpText(lines);
  }

  // "key=default" of the first declared option: a --set example this command accepts.
  std::string Example() const {
    if (options_.empty()) return "";
    const Options defaults{};
    std::string value = options_.front()->text_(defaults);
    // A string's message text is quoted ('bcot'); on a command line the bare value reads the same.
    if (value.size() >= 2 && value.front() == '\'' && value.back() == '\'') {
      value = value.substr(1, value.size() - 2);
    }
    return options_.front()->info_.key + "=" + value;
  }

  const std::vector<std::unique_ptr<Option>>& options() const { return options_; }

 private:
  Option& NewOption(const std::string& key, const std::string& unit, const std::string& help) {
    auto option = std::make_unique<Option>();
    option->info_.key = key;
    const size_t dot = key.rfind('.');
    option->info_.section = dot == std::string::npos ? "" : key.substr(0, dot);
    option->info_.name = dot == std::string::npos ? key : key.substr(dot + 1);
    option->info_.unit = unit;
    option->info_.help = help;
    options_.push_back(std::move(option));
    return *options_.back();
  }

  static constexpr const char kUnlocated[] = "-";

  static std::string ParentDir(const std::string& path) {
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? "" : path.substr(0, slash);
  }

  // The sections directly below `section` ("" = top), in declaration order.
  std::vector<std::string> ChildSections(const std::string& section) const {
    std::vector<std::string> children;
    const std::string prefix = section.empty() ? "" : section + ".";
    for (const std::unique_ptr<Option>& option : options_) {
      const std::string& s = option->info_.section;
      if (s.size() <= prefix.size() || s.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string rest = s.substr(prefix.size());
      const std::string child = prefix + rest.substr(0, rest.find('.'));
      bool seen = false;
      for (const std::string& c : children) seen = seen || c == child;
      if (!seen) children.push_back(child);
    }
    return children;
  }

  static std::string LastComponent(const std::string& section) {
    const size_t dot = section.rfind('.');
    return dot == std::string::npos ? section : section.substr(dot + 1);
  }

  Status ParseLevel(const YAML::Node& node, const std::string& source_name,
                    const std::string& section, const std::string& base_dir, Options* options,
                    OptionSources* sources) const {
    YamlMap map(node, source_name, section, StatusCode::kInvalidConfig);
    BCOT_RETURN_IF_ERROR(map.Check());
    for (const std::unique_ptr<Option>& option : options_) {
      if (option->info_.section != section) continue;
      BCOT_RETURN_IF_ERROR(option->read_(map, base_dir, options));
      if (sources != nullptr && map.Has(option->info_.name)) {
        (*sources)[option->info_.key] = map.Location(option->info_.name);
      }
    }
    for (const std::string& child : ChildSections(section)) {
      const std::string name = LastComponent(child);
      const YAML::Node child_node = map.Node(name);  // marks the section as known
      if (!child_node.IsDefined() || child_node.IsNull()) continue;
      BCOT_RETURN_IF_ERROR(ParseLevel(child_node, source_name, child, base_dir, options, sources));
    }
    return map.CheckNoUnknownKeys();
  }

  void EmitLevel(YAML::Emitter& out, const Options& options, const std::string& section) const {
    for (const std::unique_ptr<Option>& option : options_) {
      if (option->info_.section != section) continue;
      out << YAML::Key << option->info_.name << YAML::Value;
      option->emit_(out, options);
    }
    for (const std::string& child : ChildSections(section)) {
      out << YAML::Key << LastComponent(child) << YAML::Value << YAML::BeginMap;
      EmitLevel(out, options, child);
      out << YAML::EndMap;
    }
  }

  std::vector<std::unique_ptr<Option>> options_;
};

}  // namespace bcot

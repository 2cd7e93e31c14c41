#include "bcot/core/option_schema.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace bcot {

bool OptionRange::Contains(double value) const {
  if (!std::isfinite(value)) return false;
  const bool above = lo_open ? value > lo : value >= lo;
  const bool below = hi_open ? value < hi : value <= hi;
  return above && below;
}

std::string OptionRange::Text() const {
  const bool has_lo = std::isfinite(lo);
  const bool has_hi = std::isfinite(hi);
  if (has_lo && !has_hi) return fmt::format("{} {}", lo_open ? ">" : ">=", lo);
  if (!has_lo && has_hi) return fmt::format("{} {}", hi_open ? "<" : "<=", hi);
  if (!has_lo && !has_hi) return "finite";
  return fmt::format("in {}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
}

OptionRange Positive() {
  OptionRange range = AtLeast(0.0);
  range.lo_open = true;
  return range;
}
OptionRange NonNegative() { return AtLeast(0.0); }
OptionRange AtLeast(double lo) {
  OptionRange range;
  range.lo = lo;
  return range;
}
OptionRange Closed(double lo, double hi) {
  OptionRange range;
  range.lo = lo;
  range.hi = hi;
  return range;
}
OptionRange Open(double lo, double hi) {
  OptionRange range = Closed(lo, hi);
  range.lo_open = true;
  range.hi_open = true;
  return range;
}
OptionRange LeftOpen(double lo, double hi) {
  OptionRange range = Closed(lo, hi);
  range.lo_open = true;
  return range;
}

namespace option_internal {

std::string Violation(const std::string& source, const std::string& key, const std::string& value,
                      const std::string& rule) {
  if (source.empty()) return fmt::format("{} = {} (default), {}", key, value, rule);
  if (source == "-") return fmt::format("{} = {}, {}", key, value, rule);
  return fmt::format("{} = {}, {}", JoinWhere(source, key), value, rule);
}

std::vector<std::string> ElementViolations(const OptionInfo& info, const std::string& source,
                                           const std::vector<double>& numbers,
                                           const std::vector<std::string>& strings) {
  std::vector<std::string> violations;
  // The key and value text of element i: "key[i]", or "value (name)" with element names.
  const auto add = [&](size_t i, const std::string& value, const std::string& rule) {
    std::string key = info.key;
    std::string text = value;
    if (info.is_list && i < info.element_names.size()) {
      text += " (" + info.element_names[i] + ")";
    } else if (info.is_list) {
      key += fmt::format("[{}]", i);
    }
    violations.push_back(Violation(source, key, text, rule));
  };
  if (info.has_range) {
    for (size_t i = 0; i < numbers.size(); ++i) {
      if (!info.range.Contains(numbers[i]))
        add(i, ValueText(numbers[i]), "must be " + info.range.Text());
    }
  }
  if (!info.one_of.empty()) {
    for (size_t i = 0; i < strings.size(); ++i) {
      if (std::find(info.one_of.begin(), info.one_of.end(), strings[i]) == info.one_of.end()) {
        add(i, ValueText(strings[i]),
            fmt::format("must be one of {}", fmt::join(info.one_of, ", ")));
      }
    }
  }
  if (info.element_rule) {
    for (size_t i = 0; i < strings.size(); ++i) {
      const std::string rule = info.element_rule(strings, i);
      if (!rule.empty()) add(i, ValueText(strings[i]), rule);
    }
  }
  return violations;
}

std::string ResolvePath(const std::string& base_dir, const std::string& path) {
  if (path.empty()) return path;
  const std::filesystem::path p(path);
  if (p.is_absolute() || base_dir.empty()) return p.lexically_normal().string();
  return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

std::string HelpText(const std::vector<std::pair<const OptionInfo*, std::string>>& options) {
  // key = default, then unit and rule, then the help line; columns aligned over all options.
  std::vector<std::string> heads;
  size_t width = 0;
  for (const auto& [info, value] : options) {
    std::string head = fmt::format("{} = {}", info->key, value.empty() ? "\"\"" : value);
    if (!info->unit.empty()) head += " " + info->unit;
    width = std::max(width, head.size());
    heads.push_back(std::move(head));
  }
  width = std::min<size_t>(width, 44);
  std::string text;
  for (size_t i = 0; i < options.size(); ++i) {
    const OptionInfo& info = *options[i].first;
    std::string rule;
    if (!info.choices.empty()) rule = "(" + info.choices + ") ";
    if (!info.one_of.empty()) rule = fmt::format("({}) ", fmt::join(info.one_of, " | "));
    if (info.has_range) rule = "(" + info.range.Text() + ") ";
    text += fmt::format("  {:<{}}  {}{}\n", heads[i], width, rule, info.help);
  }
  return text;
}

std::string ValueText(bool value) { return value ? "true" : "false"; }
std::string ValueText(int value) { return fmt::format("{}", value); }
std::string ValueText(double value) { return fmt::format("{}", value); }
// Single-quoted, so a message shows where the value starts and ends ("object = 'a/b', ...").
std::string ValueText(const std::string& value) { return "'" + value + "'"; }

void EmitValue(YAML::Emitter& out, bool value) { out << ValueText(value); }
void EmitValue(YAML::Emitter& out, int value) { out << ValueText(value); }
void EmitValue(YAML::Emitter& out, double value) { out << ValueText(value); }
void EmitValue(YAML::Emitter& out, const std::string& value) {
  // Quoted when a plain scalar would read as something else ("no", "1.5", "", "a: b").
  if (FormatYamlString(value) != value) out << YAML::DoubleQuoted;
  out << value;
}

Status ReadValue(YamlMap& map, const std::string& name, bool* value) {
  return map.GetOptional(name, value);
}
Status ReadValue(YamlMap& map, const std::string& name, int* value) {
  return map.GetOptional(name, value);
}
Status ReadValue(YamlMap& map, const std::string& name, double* value) {
  return map.GetOptional(name, value);
}
Status ReadValue(YamlMap& map, const std::string& name, std::string* value) {
  return map.GetOptional(name, value);
}
Status ReadValue(YamlMap& map, const std::string& name, std::vector<int>* value) {
  return map.GetOptional(name, value);
}
Status ReadValue(YamlMap& map, const std::string& name, std::vector<double>* value) {
  return map.GetOptional(name, value);
}
Status ReadValue(YamlMap& map, const std::string& name, std::vector<std::string>* value) {
  return map.GetOptional(name, value);
}

Status ReadFixedList(YamlMap& map, const std::string& name, size_t size,
                     const std::vector<std::string>& element_names, std::vector<double>* values) {
  std::vector<double> read;
  BCOT_RETURN_IF_ERROR(map.Get(name, &read));
  if (read.size() != size) {
    std::string problem = fmt::format("has {} values, expected {}", read.size(), size);
    if (!element_names.empty()) problem += fmt::format(" ({})", fmt::join(element_names, ", "));
    return map.Error(name, problem);
  }
  *values = std::move(read);
  return Status::Ok();
}

}  // namespace option_internal
}  // namespace bcot

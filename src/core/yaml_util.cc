#include "bcot/core/yaml_util.h"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "bcot/core/file_util.h"

namespace bcot {
namespace {

// Records where each document of a YAML stream starts; the events inside are ignored.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> marks;

  void OnDocumentStart(const YAML::Mark& mark) override { marks.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// The number of documents in `text`, counted up to two (enough to tell one from several), and
// where the second starts. Not YAML::LoadAll: on some malformed input (a lone ',' is one)
// yaml-cpp 0.7's parser hands out the same document again and again without consuming input,
// so LoadAll never returns and its memory grows without bound. A document that starts where
// the previous one did is that stall, reported as a syntax error. Throws YAML::Exception.
StatusOr<int> CountYamlDocuments(const std::string& text, const std::string& source_name,
                                 StatusCode code, YAML::Mark* second_start) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentStarts starts;
  while (starts.marks.size() < 2 && parser.HandleNextDocument(starts)) {
    const size_t n = starts.marks.size();
    if (n == 2 && starts.marks[1].pos == starts.marks[0].pos) {
      return Status(
          code, fmt::format("{}:{}: YAML syntax error: unexpected text at column {}", source_name,
                            starts.marks[1].line + 1, starts.marks[1].column + 1));
    }
  }
  if (starts.marks.size() == 2) *second_start = starts.marks[1];
  return static_cast<int>(starts.marks.size());
}

// yaml-cpp marks 0-based lines; a node built in code (e.g. by an override) has no mark.
bool HasMark(const YAML::Node& node) {
  try {
    return node.IsDefined() && !node.Mark().is_null();
  } catch (const YAML::Exception&) {
    return false;
  }
}

// Aliases make a YAML document a graph that every reader walks as a tree: ten nested aliases
// of ten entries each ("billion laughs") expand to 10^10 nodes. No file bcot reads is anywhere
// near these limits, so a document past them is refused before anything walks it.
constexpr size_t kMaxYamlNodes = 100000;
constexpr int kMaxYamlDepth = 64;

Status CheckYamlSize(const YAML::Node& root, const std::string& source_name, StatusCode code) {
  std::vector<std::pair<YAML::Node, int>> stack = {{root, 0}};
  size_t visited = 0;
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    if (++visited > kMaxYamlNodes) {
      return Status(code, fmt::format("{}: more than {} YAML nodes (with aliases expanded); not "
                                      "a bcot file",
                                      source_name, kMaxYamlNodes));
    }
    if (depth > kMaxYamlDepth) {
      return Status(code, fmt::format("{}: YAML nested deeper than {} levels; not a bcot file",
                                      YamlWhere(source_name, node), kMaxYamlDepth));
    }
    if (node.IsSequence()) {
      for (const YAML::Node& element : node) stack.push_back({element, depth + 1});
    } else if (node.IsMap()) {
      for (const auto& entry : node) {
        stack.push_back({entry.first, depth + 1});
        stack.push_back({entry.second, depth + 1});
      }
    }
  }
  return Status::Ok();
}

// 1-based line of a map entry, 0 when unknown. The key's line rather than the value's: a block
// value starts on the next line, and the mark of an empty value points past it. A value without
// a mark was set in code (an override), so no line of the file describes it.
int EntryLine(const YAML::Node& key_node, const YAML::Node& value) {
  if (!HasMark(value)) return 0;
  return HasMark(key_node) ? key_node.Mark().line + 1 : value.Mark().line + 1;
}

// Plain (unquoted, untagged) scalars are the only ones read as numbers or booleans: `"5"` is
// a string. Nodes built in code have an empty tag and count as plain.
bool IsPlainScalar(const YAML::Node& node) {
  return node.IsScalar() && (node.Tag() == "?" || node.Tag().empty());
}

// Short description of what a node holds, for "expected X, got Y" messages.
std::string Describe(const YAML::Node& node) {
  if (!node.IsDefined()) return "nothing";
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return "null";
    case YAML::NodeType::Sequence:
      return fmt::format("a sequence of {}", node.size());
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Scalar:
      return IsPlainScalar(node) ? fmt::format("'{}'", node.Scalar())
                                 : fmt::format("'{}' (quoted or tagged: a string)", node.Scalar());
    default:
      return "nothing";
  }
}

// Where a value sits, for messages "file:line: key.path: problem".
struct Context {
  const std::string& source_name;
  int line;  // 1-based, 0 = unknown
  std::string key_path;
  StatusCode code;

  Status Error(const std::string& problem) const {
    const std::string location =
        line > 0 ? fmt::format("{}:{}", source_name, line) : std::string(source_name);
    return Status(code, fmt::format("{}: {}", JoinWhere(location, key_path), problem));
  }
  Status TypeError(const std::string& expected, const YAML::Node& node) const {
    return Error(fmt::format("expected {}, got {}", expected, Describe(node)));
  }
};

Status ParseValue(const YAML::Node& node, const Context& context, double* value) {
  if (!IsPlainScalar(node)) return context.TypeError("a number", node);
  const std::string& text = node.Scalar();
  double parsed = 0.0;
  if (!ParseDouble(text, &parsed)) {
    // YAML's spellings of infinity and NaN are numbers, but never meaningful in bcot's files.
    std::string lower = text;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (lower == ".inf" || lower == "+.inf" || lower == "-.inf" || lower == ".nan") {
      return context.Error(fmt::format("expected a finite number, got '{}'", text));
    }
    return context.TypeError("a number", node);
  }
  if (!std::isfinite(parsed)) {
    return context.Error(fmt::format("expected a finite number, got '{}'", text));
  }
  *value = parsed;
  return Status::Ok();
}

Status ParseValue(const YAML::Node& node, const Context& context, int* value) {
  if (!IsPlainScalar(node)) return context.TypeError("an integer", node);
  int64_t parsed = 0;
  if (!ParseInt64(node.Scalar(), &parsed)) return context.TypeError("an integer", node);
  if (parsed < std::numeric_limits<int>::min() || parsed > std::numeric_limits<int>::max()) {
    return context.Error(fmt::format("expected an integer in [{}, {}], got '{}'",
                                     std::numeric_limits<int>::min(),
                                     std::numeric_limits<int>::max(), node.Scalar()));
  }
  *value = static_cast<int>(parsed);
  return Status::Ok();
}

Status ParseValue(const YAML::Node& node, const Context& context, bool* value) {
  if (IsPlainScalar(node)) {
    std::string lower = node.Scalar();
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (lower == "true" || lower == "false") {
      *value = lower == "true";
      return Status::Ok();
    }
  }
  return context.TypeError("true or false", node);
}

Status ParseValue(const YAML::Node& node, const Context& context, std::string* value) {
  if (!node.IsScalar()) return context.TypeError("a string", node);
  *value = node.Scalar();
  return Status::Ok();
}

template <typename T>
Status ParseValue(const YAML::Node& node, const Context& context, std::vector<T>* values) {
  if (!node.IsSequence()) return context.TypeError("a sequence [...]", node);
  std::vector<T> parsed(node.size());
  for (size_t i = 0; i < node.size(); ++i) {
    const YAML::Node element = node[i];
    // An element carries its own line: in a sequence spread over lines, point at the element.
    const Context element_context{context.source_name,
                                  HasMark(element) ? element.Mark().line + 1 : context.line,
                                  fmt::format("{}[{}]", context.key_path, i), context.code};
    BCOT_RETURN_IF_ERROR(ParseValue(element, element_context, &parsed[i]));
  }
  *values = std::move(parsed);
  return Status::Ok();
}

// Optimal string alignment distance: insertions, deletions, substitutions and transpositions of
// adjacent letters ("scael" → "scale") each cost 1.
size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min(
          {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

bool IsValidOverrideKey(const std::string& component) {
  if (component.empty()) return false;
  return std::all_of(component.begin(), component.end(),
                     [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; });
}

// A deep copy without line marks: the value came from the command line, so a line number of
// the override string would be mistaken for a line of the config file.
YAML::Node WithoutMarks(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: {
      YAML::Node copy(node.Scalar());
      copy.SetTag(node.Tag());
      return copy;
    }
    case YAML::NodeType::Sequence: {
      YAML::Node copy(YAML::NodeType::Sequence);
      for (const YAML::Node& element : node) copy.push_back(WithoutMarks(element));
      return copy;
    }
    case YAML::NodeType::Map: {
      YAML::Node copy(YAML::NodeType::Map);
      for (const auto& entry : node) copy[WithoutMarks(entry.first)] = WithoutMarks(entry.second);
      return copy;
    }
    default:
      return YAML::Node(YAML::NodeType::Null);
  }
}

// The value node stored under scalar key `key` in `map`, or an undefined node. Iterates
// instead of using operator[], which on a non-const node may insert the key.
YAML::Node FindChild(const YAML::Node& map, const std::string& key) {
  for (const auto& entry : map) {
    if (entry.first.IsScalar() && entry.first.Scalar() == key) return entry.second;
  }
  return YAML::Node(YAML::NodeType::Undefined);
}

Status ApplyOneOverride(const std::string& override_text, YAML::Node* root) {
  const auto fail = [&](const std::string& problem) {
    return Status::InvalidConfig(fmt::format("override '{}': {}", override_text, problem));
  };
  const size_t equals = override_text.find('=');
  if (equals == std::string::npos) return fail("expected section.key=value");
  const std::string key_path(TrimWhitespace(std::string_view(override_text).substr(0, equals)));
  const std::string value_text(TrimWhitespace(std::string_view(override_text).substr(equals + 1)));
  if (key_path.empty()) return fail("missing key before '=' (expected section.key=value)");
  if (value_text.empty()) return fail("missing value after '=' (expected section.key=value)");

  std::vector<std::string> components;
  size_t start = 0;
  while (true) {
    const size_t dot = key_path.find('.', start);
    components.push_back(key_path.substr(start, dot == std::string::npos ? dot : dot - start));
    if (!IsValidOverrideKey(components.back())) {
      return fail(fmt::format(
          "key path '{}' has an invalid component '{}' (expected names of letters, digits, "
          "'_' or '-' joined by '.')",
          key_path, components.back()));
    }
    if (dot == std::string::npos) break;
    start = dot + 1;
  }

  YAML::Node value;
  try {
    YAML::Mark second_start;
    const StatusOr<int> documents =
        CountYamlDocuments(value_text, "value", StatusCode::kInvalidConfig, &second_start);
    if (!documents.ok()) return fail(documents.status().message());
    if (*documents != 1) return fail("value must be a single YAML value");
    const YAML::Node document = YAML::Load(value_text);
    const Status size = CheckYamlSize(document, "value", StatusCode::kInvalidConfig);
    if (!size.ok()) return fail(size.message());
    value = WithoutMarks(document);
  } catch (const YAML::Exception& error) {
    return fail(fmt::format("value '{}' is not valid YAML: {}", value_text, error.msg));
  }

  try {
    if (!root->IsDefined() || root->IsNull()) *root = YAML::Node(YAML::NodeType::Map);
    if (!root->IsMap()) return fail("the config is not a mapping of sections");
    // Node handles share their data, so assigning through `current` edits the tree in `root`.
    YAML::Node current = *root;
    std::string walked;
    for (size_t i = 0; i + 1 < components.size(); ++i) {
      walked += (i == 0 ? "" : ".") + components[i];
      YAML::Node child = FindChild(current, components[i]);
      if (!child.IsDefined() || child.IsNull()) {
        current[components[i]] = YAML::Node(YAML::NodeType::Map);
        // reset(), not operator=: assigning to a Node handle overwrites the node it refers to.
        child.reset(FindChild(current, components[i]));
      } else if (!child.IsMap()) {
        return fail(fmt::format("'{}' is {}, not a section with keys", walked, Describe(child)));
      }
      current.reset(child);
    }
    current[components.back()] = value;
  } catch (const YAML::Exception& error) {
    return fail(fmt::format("cannot apply: {}", error.msg));
  }
  return Status::Ok();
}

}  // namespace

StatusOr<YAML::Node> ParseYaml(const std::string& text, const std::string& source_name,
                               StatusCode code) {
  try {
    YAML::Mark second_start;
    BCOT_ASSIGN_OR_RETURN(const int documents,
                          CountYamlDocuments(text, source_name, code, &second_start));
    if (documents == 0) return YAML::Node(YAML::NodeType::Null);
    if (documents > 1) {
      return Status(code, fmt::format("{}:{}: more than one YAML document ('---'), expected one",
                                      source_name, second_start.line + 1));
    }
    YAML::Node document = YAML::Load(text);
    BCOT_RETURN_IF_ERROR(CheckYamlSize(document, source_name, code));
    return document;
  } catch (const YAML::Exception& error) {
    const std::string where =
        error.mark.is_null() ? source_name : fmt::format("{}:{}", source_name, error.mark.line + 1);
    return Status(code, fmt::format("{}: YAML syntax error: {}", where, error.msg));
  }
}

StatusOr<YAML::Node> LoadYamlFile(const std::string& path, StatusCode code) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  return ParseYaml(text, path, code);
}

std::string FormatYamlString(const std::string& value) {
  static constexpr const char* kReserved[] = {"true", "false", "yes",  "no",   "on",   "off",
                                              "y",    "n",     "null", ".inf", ".nan", "~"};
  std::string lower = value;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  bool plain = !value.empty() && (std::isalpha(static_cast<unsigned char>(value[0])) ||
                                  value[0] == '_' || value[0] == '.' || value[0] == '/');
  for (const char c : value) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '/' &&
        c != '-') {
      plain = false;
    }
  }
  for (const char* reserved : kReserved) {
    if (lower == reserved) plain = false;
  }
  if (plain) return value;

  std::string quoted = "\"";
  for (const char c : value) {
    switch (c) {
      case '"':
        quoted += "\\\"";
        break;
      case '\\':
        quoted += "\\\\";
        break;
      case '\n':
        quoted += "\\n";
        break;
      case '\t':
        quoted += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          quoted += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
        } else {
          quoted += c;  // printable ASCII and UTF-8 bytes pass through
        }
    }
  }
  quoted += '"';
  return quoted;
}

std::string JoinWhere(const std::string& location, const std::string& key_path) {
  if (location == kCommandLineSource) return fmt::format("{} {}", location, key_path);
  return fmt::format("{}: {}", location, key_path);
}

std::string YamlWhere(const std::string& source_name, const YAML::Node& node) {
  if (!HasMark(node)) return source_name;
  return fmt::format("{}:{}", source_name, node.Mark().line + 1);
}

Status ApplyYamlOverrides(const std::vector<std::string>& overrides, YAML::Node* root) {
  BCOT_CHECK(root != nullptr);
  for (const std::string& override_text : overrides) {
    BCOT_RETURN_IF_ERROR(ApplyOneOverride(override_text, root));
  }
  return Status::Ok();
}

YamlMap::YamlMap(YAML::Node node, std::string source_name, std::string path, StatusCode code)
    : node_(std::move(node)),
      source_name_(std::move(source_name)),
      path_(std::move(path)),
      code_(code) {
  if (!node_.IsDefined() || node_.IsNull()) return;  // an empty section reads as {}
  const std::string self = path_.empty() ? "the document" : path_;
  if (!node_.IsMap()) {
    check_ = MakeError(fmt::format("{}: {}", YamlWhere(source_name_, node_), self),
                       fmt::format("expected a mapping of keys, got {}", Describe(node_)));
    return;
  }
  std::map<std::string, int> first_line;  // key → 1-based line of its first occurrence
  for (const auto& item : node_) {
    if (!item.first.IsScalar()) {
      check_ = MakeError(fmt::format("{}: {}", YamlWhere(source_name_, item.first), self),
                         fmt::format("keys must be plain names, got {}", Describe(item.first)));
      return;
    }
    Entry entry{item.first.Scalar(), item.first, item.second};
    const int line = HasMark(item.first) ? item.first.Mark().line + 1 : 0;
    const auto [it, inserted] = first_line.emplace(entry.key, line);
    if (!inserted) {
      check_ =
          MakeError(fmt::format("{}: {}", YamlWhere(source_name_, item.first), KeyPath(entry.key)),
                    it->second > 0 ? fmt::format("duplicate key (first at line {})", it->second)
                                   : "duplicate key");
      return;
    }
    entries_.push_back(std::move(entry));
  }
}

Status YamlMap::Check() const { return check_; }

const YamlMap::Entry* YamlMap::Find(const std::string& key) const {
  for (const Entry& entry : entries_) {
    if (entry.key == key) return &entry;
  }
  return nullptr;
}

Status YamlMap::MakeError(const std::string& where, const std::string& problem) const {
  return Status(code_, fmt::format("{}: {}", where, problem));
}

bool YamlMap::Has(const std::string& key) const { return Find(key) != nullptr; }

YAML::Node YamlMap::Node(const std::string& key) const {
  used_.insert(key);
  const Entry* entry = Find(key);
  return entry != nullptr ? entry->value : YAML::Node(YAML::NodeType::Undefined);
}

std::string YamlMap::KeyPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

std::string YamlMap::Location(const std::string& key) const {
  const Entry* entry = Find(key);
  if (entry == nullptr) {
    // The mapping's own line (its first key). An empty section has no line of its own: the
    // mark of a Null value points at whatever follows it.
    return node_.IsMap() ? YamlWhere(source_name_, node_) : source_name_;
  }
  const int line = EntryLine(entry->key_node, entry->value);
  return line > 0 ? fmt::format("{}:{}", source_name_, line) : source_name_;
}

std::string YamlMap::Where(const std::string& key) const {
  return JoinWhere(Location(key), KeyPath(key));
}

Status YamlMap::Error(const std::string& key, const std::string& problem) const {
  return MakeError(Where(key), problem);
}

template <typename T>
Status YamlMap::Get(const std::string& key, T* value) {
  BCOT_RETURN_IF_ERROR(check_);
  used_.insert(key);
  const Entry* entry = Find(key);
  if (entry == nullptr) return Error(key, "missing required key");
  const Context context{source_name_, EntryLine(entry->key_node, entry->value), KeyPath(key),
                        code_};
  return ParseValue(entry->value, context, value);
}

template <typename T>
Status YamlMap::GetOptional(const std::string& key, T* value) {
  BCOT_RETURN_IF_ERROR(check_);
  used_.insert(key);
  if (Find(key) == nullptr) return Status::Ok();
  return Get(key, value);
}

Status YamlMap::GetOptionalChoice(const std::string& key, const std::vector<std::string>& names,
                                  int* index) {
  std::string value;
  BCOT_RETURN_IF_ERROR(GetOptional(key, &value));
  if (!Has(key)) return Status::Ok();
  for (size_t i = 0; i < names.size(); ++i) {
    if (value == names[i]) {
      *index = static_cast<int>(i);
      return Status::Ok();
    }
  }
  std::string choices = names.empty() ? "" : names[0];
  for (size_t i = 1; i < names.size(); ++i) choices += " | " + names[i];
  return Error(key, fmt::format("'{}' is not one of {}", value, choices));
}

Status YamlMap::GetFixedArray(const std::string& key, size_t expected_size,
                              std::vector<double>* values) {
  std::vector<double> parsed;
  BCOT_RETURN_IF_ERROR(Get(key, &parsed));
  if (parsed.size() != expected_size) {
    return Error(key, fmt::format("expected {} numbers, got {}", expected_size, parsed.size()));
  }
  *values = std::move(parsed);
  return Status::Ok();
}

Status YamlMap::CheckNoUnknownKeys() const {
  BCOT_RETURN_IF_ERROR(check_);
  std::vector<const Entry*> unknown;
  for (const Entry& entry : entries_) {
    if (used_.count(entry.key) == 0) unknown.push_back(&entry);
  }
  if (unknown.empty()) return Status::Ok();

  const std::string& key = unknown.front()->key;
  std::string problem = "unknown key";
  const std::string* closest = nullptr;
  size_t closest_distance = 0;
  for (const std::string& known : used_) {
    const size_t distance = EditDistance(key, known);
    if (closest == nullptr || distance < closest_distance) {
      closest = &known;
      closest_distance = distance;
    }
  }
  // A suggestion only when it is plausibly a typo: at most a third of the letters differ.
  if (closest != nullptr && closest_distance * 3 <= std::max<size_t>(key.size(), 3)) {
    problem += fmt::format(" (did you mean '{}'?)", *closest);
  }
  if (used_.empty()) {
    problem += "; this section takes no keys";
  } else {
    problem += fmt::format("; known keys: {}", fmt::join(used_, ", "));
  }
  if (unknown.size() > 1) {
    problem +=
        fmt::format("; {} more unknown key{}", unknown.size() - 1, unknown.size() > 2 ? "s" : "");
  }
  return Error(key, problem);
}

// The types the header promises; anything else fails to link.
template Status YamlMap::Get<bool>(const std::string&, bool*);
template Status YamlMap::Get<int>(const std::string&, int*);
template Status YamlMap::Get<double>(const std::string&, double*);
template Status YamlMap::Get<std::string>(const std::string&, std::string*);
template Status YamlMap::Get<std::vector<int>>(const std::string&, std::vector<int>*);
template Status YamlMap::Get<std::vector<double>>(const std::string&, std::vector<double>*);
template Status YamlMap::Get<std::vector<std::string>>(const std::string&,
                                                       std::vector<std::string>*);
template Status YamlMap::GetOptional<bool>(const std::string&, bool*);
template Status YamlMap::GetOptional<int>(const std::string&, int*);
template Status YamlMap::GetOptional<double>(const std::string&, double*);
template Status YamlMap::GetOptional<std::string>(const std::string&, std::string*);
template Status YamlMap::GetOptional<std::vector<int>>(const std::string&, std::vector<int>*);
template Status YamlMap::GetOptional<std::vector<double>>(const std::string&, std::vector<double>*);
template Status YamlMap::GetOptional<std::vector<std::string>>(const std::string&,
                                                               std::vector<std::string>*);

}  // namespace bcot

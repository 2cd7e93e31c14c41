#include "bcot/synth/synth_options.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>
#include <utility>

#include "bcot/core/file_util.h"
#include "bcot/core/yaml_util.h"

namespace bcot {
namespace {

// A violated rule of one field, e.g. {"motion.fps", "motion.fps = 0, must be > 0"}.
struct Violation {
  std::string field;
  std::string message;
};

std::string FormatNumber(double value) { return fmt::format("{}", value); }

class ViolationList {
 public:
  void Add(const std::string& field, const std::string& value, const std::string& rule) {
    list_.push_back({field, fmt::format("{} = {}, {}", field, value, rule)});
  }
  // Closed range [lo, hi].
  void InRange(const std::string& field, double value, double lo, double hi) {
    if (!(value >= lo && value <= hi)) {
      Add(field, FormatNumber(value),
          fmt::format("must be in [{}, {}]", FormatNumber(lo), FormatNumber(hi)));
    }
  }
  // Open range (lo, hi).
  void InOpenRange(const std::string& field, double value, double lo, double hi) {
    if (!(value > lo && value < hi)) {
      Add(field, FormatNumber(value),
          fmt::format("must be in ({}, {})", FormatNumber(lo), FormatNumber(hi)));
    }
  }
  // (lo, hi].
  void InLeftOpenRange(const std::string& field, double value, double lo, double hi) {
    if (!(value > lo && value <= hi)) {
      Add(field, FormatNumber(value),
          fmt::format("must be in ({}, {}]", FormatNumber(lo), FormatNumber(hi)));
    }
  }
  void Positive(const std::string& field, double value) {
    if (!(value > 0.0 && std::isfinite(value))) Add(field, FormatNumber(value), "must be > 0");
  }
  void NonNegative(const std::string& field, double value) {
    if (!(value >= 0.0 && std::isfinite(value))) Add(field, FormatNumber(value), "must be >= 0");
  }
  const std::vector<Violation>& list() const { return list_; }

 private:
  std::vector<Violation> list_;
};

std::vector<Violation> CollectViolations(const SynthOptions& o) {
  ViolationList v;
  v.NonNegative("seed", o.seed);

  const auto& ob = o.object;
  v.InRange("object.size_mm", ob.size_mm, 0.0, 5000.0);
  v.Positive("object.unit_to_mm", ob.unit_to_mm);
  for (int i = 0; i < 3; ++i) {
    v.InRange(fmt::format("object.color_rgb[{}]", i), ob.color_rgb[i], 0.0, 255.0);
  }
  v.InRange("object.diffuse", ob.diffuse, 0.0, 1.0);
  v.InRange("object.specular", ob.specular, 0.0, 10.0);
  v.InRange("object.shininess", ob.shininess, 1.0, 10000.0);
  v.InRange("object.crease_angle_deg", ob.crease_angle_deg, 0.0, 180.0);
  if (ob.name.find('/') != std::string::npos || ob.name == "." || ob.name == "..") {
    v.Add("object.name", ob.name, "must be a plain file name");
  }

  const auto& c = o.cameras;
  v.InRange("cameras.width", c.width, 16, 8192);
  v.InRange("cameras.height", c.height, 16, 8192);
  v.InOpenRange("cameras.hfov_deg", c.hfov_deg, 1.0, 170.0);
  v.Positive("cameras.distance_mm", c.distance_mm);
  v.InRange("cameras.elevation_deg", c.elevation_deg, -80.0, 80.0);
  for (size_t i = 0; i < c.arc_angles_deg.size(); ++i) {
    v.InOpenRange(fmt::format("cameras.arc_angles_deg[{}]", i), c.arc_angles_deg[i], 0.0, 180.0);
  }
  for (size_t i = 0; i < c.cone_angles_deg.size(); ++i) {
    v.InOpenRange(fmt::format("cameras.cone_angles_deg[{}]", i), c.cone_angles_deg[i], 0.0, 120.0);
  }
  for (int i = 0; i < 5; ++i) {
    v.InRange(fmt::format("cameras.distortion[{}]", i), c.distortion[i], -1.0, 1.0);
  }
  if (c.name_prefix.empty() || c.name_prefix.find('/') != std::string::npos) {
    v.Add("cameras.name_prefix", "\"" + c.name_prefix + "\"",
          "must be a non-empty plain file name");
  }

  const auto& m = o.motion;
  if (m.mode != "free" && m.mode != "rotate" && m.mode != "rig") {
    v.Add("motion.mode", m.mode, "must be one of free, rotate, rig");
  }
  v.InRange("motion.num_frames", m.num_frames, 1, 100000);
  v.InLeftOpenRange("motion.fps", m.fps, 0.0, 10000.0);
  v.InRange("motion.rotation_deg_per_frame", m.rotation_deg_per_frame, 0.0, 90.0);
  v.InRange("motion.translation_mm_per_frame", m.translation_mm_per_frame, 0.0, 1000.0);
  v.InRange("motion.speed_variation", m.speed_variation, 0.0, 0.9);
  v.NonNegative("motion.workspace_radius_mm", m.workspace_radius_mm);
  v.InRange("motion.frustum_margin_px", m.frustum_margin_px, 0.0, 1000.0);
  v.InLeftOpenRange("motion.rig_max_rotation_deg", m.rig_max_rotation_deg, 0.0, 90.0);
  v.InRange("motion.object_motion_scale", m.object_motion_scale, 0.0, 1.0);

  const auto& b = o.background;
  if (b.kinds.empty()) v.Add("background.kinds", "[]", "must list at least one kind");
  int image_views = 0;
  for (size_t i = 0; i < b.kinds.size(); ++i) {
    const std::string& kind = b.kinds[i];
    if (kind == "image") ++image_views;
    if (kind != "plain" && kind != "cluttered" && kind != "image") {
      v.Add(fmt::format("background.kinds[{}]", i), kind, "must be one of plain, cluttered, image");
    }
  }
  if (image_views > 0 && b.images.empty()) {
    v.Add("background.images", "[]", "must list at least one photo when a kind is image");
  }
  v.Positive("background.backdrop_distance_mm", b.backdrop_distance_mm);
  v.NonNegative("background.ground_clearance_mm", b.ground_clearance_mm);
  v.InRange("background.clutter_shapes", b.clutter_shapes, 0, 10000);
  v.InRange("background.similar_color_fraction", b.similar_color_fraction, 0.0, 1.0);
  v.InRange("background.object_tint", b.object_tint, 0.0, 1.0);

  const auto& d = o.distractors;
  v.InRange("distractors.count", d.count, 0, 100);
  v.Positive("distractors.size_min_mm", d.size_min_mm);
  v.Positive("distractors.size_max_mm", d.size_max_mm);
  if (d.size_max_mm < d.size_min_mm) {
    v.Add("distractors.size_max_mm", FormatNumber(d.size_max_mm),
          fmt::format("must be >= distractors.size_min_mm ({})", FormatNumber(d.size_min_mm)));
  }
  v.InRange("distractors.similar_color_fraction", d.similar_color_fraction, 0.0, 1.0);

  const auto& l = o.light;
  v.InRange("light.azimuth_deg", l.azimuth_deg, -360.0, 360.0);
  v.InRange("light.elevation_deg", l.elevation_deg, -90.0, 90.0);
  v.InRange("light.intensity", l.intensity, 0.0, 10.0);
  v.InRange("light.ambient", l.ambient, 0.0, 10.0);
  v.InRange("light.softness_deg", l.softness_deg, 0.0, 60.0);
  v.InRange("light.deg_per_frame", l.deg_per_frame, -90.0, 90.0);

  const auto& r = o.render;
  v.InRange("render.object_samples_per_axis", r.object_samples_per_axis, 1, 16);
  v.InRange("render.background_samples_per_axis", r.background_samples_per_axis, 1, 8);
  v.InRange("render.threads", r.threads, 0, 256);

  const auto& s = o.sensor;
  v.InLeftOpenRange("sensor.exposure", s.exposure, 0.0, 100.0);
  v.InRange("sensor.gamma", s.gamma, 1.0, 4.0);
  v.InRange("sensor.noise_sigma", s.noise_sigma, 0.0, 1.0);
  v.InRange("sensor.shot_noise_gain", s.shot_noise_gain, 0.0, 1.0);
  v.InRange("sensor.blur_sigma_px", s.blur_sigma_px, 0.0, 20.0);
  v.InRange("sensor.motion_blur_subframes", s.motion_blur_subframes, 1, 64);
  v.InLeftOpenRange("sensor.exposure_fraction", s.exposure_fraction, 0.0, 1.0);
  v.InRange("sensor.jpeg_quality", s.jpeg_quality, 0, 100);

  v.InRange("init.rotation_deg", o.init.rotation_deg, 0.0, 180.0);
  v.InRange("init.translation_mm", o.init.translation_mm, 0.0, 1e6);
  return v.list();
}

std::string JoinViolations(const std::vector<std::string>& messages) {
  std::string joined;
  for (const std::string& message : messages) {
    if (!joined.empty()) joined += "; ";
    joined += message;
  }
  return joined;
}

// The node of "section.key[3]" in `root` (index suffix ignored), or an invalid node.
YAML::Node FindField(const YAML::Node& root, const std::string& field) {
  std::string path = field.substr(0, field.find('['));
  // Node::reset rebinds a handle; operator= would overwrite the referenced node in the tree.
  YAML::Node node;
  node.reset(root);
  std::stringstream parts(path);
  std::string part;
  while (std::getline(parts, part, '.')) {
    if (!node.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    bool found = false;
    YAML::Node child;
    for (const auto& entry : node) {
      if (entry.first.IsScalar() && entry.first.Scalar() == part) {
        child.reset(entry.second);
        found = true;
      }
    }
    if (!found) return YAML::Node(YAML::NodeType::Undefined);
    node.reset(child);
  }
  return node;
}

std::string ResolvePath(const std::string& base_dir, const std::string& path) {
  if (path.empty()) return path;
  std::filesystem::path p(path);
  if (p.is_absolute() || base_dir.empty()) return p.lexically_normal().string();
  return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

Status ToConfigError(const Status& status) {
  if (status.ok() || status.code() == StatusCode::kInvalidConfig) return status;
  return Status::InvalidConfig(status.message());
}

// Reads a fixed-size numeric array when present.
template <size_t N>
Status GetArray(YamlMap& map, const std::string& key, std::array<double, N>* values) {
  if (!map.Has(key)) return Status::Ok();
  std::vector<double> read;
  BCOT_RETURN_IF_ERROR(map.GetFixedArray(key, N, &read));
  for (size_t i = 0; i < N; ++i) (*values)[i] = read[i];
  return Status::Ok();
}

// Runs `parse` on root[section] when the section is present.
Status ParseSection(YamlMap& root, const std::string& section,
                    const std::function<Status(YamlMap&)>& parse) {
  if (!root.Has(section)) return Status::Ok();
  YamlMap map(root.Node(section), root.source_name(), section, StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(map.Check());
  BCOT_RETURN_IF_ERROR(parse(map));
  return map.CheckNoUnknownKeys();
}

Status ParseInto(const YAML::Node& root_node, const std::string& source_name,
                 const std::string& base_dir, SynthOptions* o) {
  if (!root_node.IsDefined() || root_node.IsNull()) return Status::Ok();  // empty file
  YamlMap root(root_node, source_name, "", StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(root.Check());
  BCOT_RETURN_IF_ERROR(root.GetOptional("seed", &o->seed));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "object", [&](YamlMap& m) -> Status {
    auto& s = o->object;
    BCOT_RETURN_IF_ERROR(m.GetOptional("mesh", &s.mesh));
    s.mesh = ResolvePath(base_dir, s.mesh);
    BCOT_RETURN_IF_ERROR(m.GetOptional("name", &s.name));
    BCOT_RETURN_IF_ERROR(m.GetOptional("size_mm", &s.size_mm));
    BCOT_RETURN_IF_ERROR(m.GetOptional("unit_to_mm", &s.unit_to_mm));
    BCOT_RETURN_IF_ERROR(GetArray(m, "color_rgb", &s.color_rgb));
    BCOT_RETURN_IF_ERROR(m.GetOptional("diffuse", &s.diffuse));
    BCOT_RETURN_IF_ERROR(m.GetOptional("specular", &s.specular));
    BCOT_RETURN_IF_ERROR(m.GetOptional("shininess", &s.shininess));
    return m.GetOptional("crease_angle_deg", &s.crease_angle_deg);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "cameras", [&](YamlMap& m) -> Status {
    auto& s = o->cameras;
    BCOT_RETURN_IF_ERROR(m.GetOptional("width", &s.width));
    BCOT_RETURN_IF_ERROR(m.GetOptional("height", &s.height));
    BCOT_RETURN_IF_ERROR(m.GetOptional("hfov_deg", &s.hfov_deg));
    BCOT_RETURN_IF_ERROR(m.GetOptional("distance_mm", &s.distance_mm));
    BCOT_RETURN_IF_ERROR(m.GetOptional("elevation_deg", &s.elevation_deg));
    BCOT_RETURN_IF_ERROR(m.GetOptional("arc_angles_deg", &s.arc_angles_deg));
    BCOT_RETURN_IF_ERROR(m.GetOptional("cone_angles_deg", &s.cone_angles_deg));
    BCOT_RETURN_IF_ERROR(GetArray(m, "distortion", &s.distortion));
    return m.GetOptional("name_prefix", &s.name_prefix);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "motion", [&](YamlMap& m) -> Status {
    auto& s = o->motion;
    BCOT_RETURN_IF_ERROR(m.GetOptional("mode", &s.mode));
    BCOT_RETURN_IF_ERROR(m.GetOptional("num_frames", &s.num_frames));
    BCOT_RETURN_IF_ERROR(m.GetOptional("fps", &s.fps));
    BCOT_RETURN_IF_ERROR(m.GetOptional("rotation_deg_per_frame", &s.rotation_deg_per_frame));
    BCOT_RETURN_IF_ERROR(m.GetOptional("translation_mm_per_frame", &s.translation_mm_per_frame));
    BCOT_RETURN_IF_ERROR(m.GetOptional("speed_variation", &s.speed_variation));
    BCOT_RETURN_IF_ERROR(m.GetOptional("workspace_radius_mm", &s.workspace_radius_mm));
    BCOT_RETURN_IF_ERROR(m.GetOptional("frustum_margin_px", &s.frustum_margin_px));
    BCOT_RETURN_IF_ERROR(m.GetOptional("rig_max_rotation_deg", &s.rig_max_rotation_deg));
    return m.GetOptional("object_motion_scale", &s.object_motion_scale);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "background", [&](YamlMap& m) -> Status {
    auto& s = o->background;
    BCOT_RETURN_IF_ERROR(m.GetOptional("kinds", &s.kinds));
    BCOT_RETURN_IF_ERROR(m.GetOptional("images", &s.images));
    for (std::string& image : s.images) image = ResolvePath(base_dir, image);
    BCOT_RETURN_IF_ERROR(m.GetOptional("backdrop_distance_mm", &s.backdrop_distance_mm));
    BCOT_RETURN_IF_ERROR(m.GetOptional("ground", &s.ground));
    BCOT_RETURN_IF_ERROR(m.GetOptional("ground_clearance_mm", &s.ground_clearance_mm));
    BCOT_RETURN_IF_ERROR(m.GetOptional("clutter_shapes", &s.clutter_shapes));
    BCOT_RETURN_IF_ERROR(m.GetOptional("similar_color_fraction", &s.similar_color_fraction));
    return m.GetOptional("object_tint", &s.object_tint);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "distractors", [&](YamlMap& m) -> Status {
    auto& s = o->distractors;
    BCOT_RETURN_IF_ERROR(m.GetOptional("count", &s.count));
    BCOT_RETURN_IF_ERROR(m.GetOptional("meshes", &s.meshes));
    for (std::string& mesh : s.meshes) mesh = ResolvePath(base_dir, mesh);
    BCOT_RETURN_IF_ERROR(m.GetOptional("size_min_mm", &s.size_min_mm));
    BCOT_RETURN_IF_ERROR(m.GetOptional("size_max_mm", &s.size_max_mm));
    BCOT_RETURN_IF_ERROR(m.GetOptional("allow_occlusion", &s.allow_occlusion));
    return m.GetOptional("similar_color_fraction", &s.similar_color_fraction);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "light", [&](YamlMap& m) -> Status {
    auto& s = o->light;
    BCOT_RETURN_IF_ERROR(m.GetOptional("azimuth_deg", &s.azimuth_deg));
    BCOT_RETURN_IF_ERROR(m.GetOptional("elevation_deg", &s.elevation_deg));
    BCOT_RETURN_IF_ERROR(m.GetOptional("intensity", &s.intensity));
    BCOT_RETURN_IF_ERROR(m.GetOptional("ambient", &s.ambient));
    BCOT_RETURN_IF_ERROR(m.GetOptional("softness_deg", &s.softness_deg));
    BCOT_RETURN_IF_ERROR(m.GetOptional("moves", &s.moves));
    return m.GetOptional("deg_per_frame", &s.deg_per_frame);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "render", [&](YamlMap& m) -> Status {
    auto& s = o->render;
    BCOT_RETURN_IF_ERROR(m.GetOptional("object_samples_per_axis", &s.object_samples_per_axis));
    BCOT_RETURN_IF_ERROR(
        m.GetOptional("background_samples_per_axis", &s.background_samples_per_axis));
    return m.GetOptional("threads", &s.threads);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "sensor", [&](YamlMap& m) -> Status {
    auto& s = o->sensor;
    BCOT_RETURN_IF_ERROR(m.GetOptional("exposure", &s.exposure));
    BCOT_RETURN_IF_ERROR(m.GetOptional("gamma", &s.gamma));
    BCOT_RETURN_IF_ERROR(m.GetOptional("noise_sigma", &s.noise_sigma));
    BCOT_RETURN_IF_ERROR(m.GetOptional("shot_noise_gain", &s.shot_noise_gain));
    BCOT_RETURN_IF_ERROR(m.GetOptional("blur_sigma_px", &s.blur_sigma_px));
    BCOT_RETURN_IF_ERROR(m.GetOptional("motion_blur_subframes", &s.motion_blur_subframes));
    BCOT_RETURN_IF_ERROR(m.GetOptional("exposure_fraction", &s.exposure_fraction));
    return m.GetOptional("jpeg_quality", &s.jpeg_quality);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "init", [&](YamlMap& m) -> Status {
    BCOT_RETURN_IF_ERROR(m.GetOptional("rotation_deg", &o->init.rotation_deg));
    return m.GetOptional("translation_mm", &o->init.translation_mm);
  }));

  BCOT_RETURN_IF_ERROR(ParseSection(root, "output", [&](YamlMap& m) -> Status {
    return m.GetOptional("write_coverage", &o->output.write_coverage);
  }));

  return root.CheckNoUnknownKeys();
}

// YAML scalar text for a string: always double-quoted so names like "no" or "1" stay strings.
std::string Quote(const std::string& text) {
  std::string quoted = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') quoted += '\\';
    quoted += ch;
  }
  return quoted + "\"";
}

std::string Bool(bool value) { return value ? "true" : "false"; }

template <typename Container>
std::string NumberList(const Container& values) {
  std::string text = "[";
  for (size_t i = 0; i < values.size(); ++i) {
    if (i > 0) text += ", ";
    text += FormatNumber(values[i]);
  }
  return text + "]";
}

std::string StringList(const std::vector<std::string>& values) {
  std::string text = "[";
  for (size_t i = 0; i < values.size(); ++i) {
    if (i > 0) text += ", ";
    text += Quote(values[i]);
  }
  return text + "]";
}

}  // namespace

Status SynthOptions::Validate() const {
  std::vector<std::string> messages;
  for (const Violation& violation : CollectViolations(*this)) {
    messages.push_back(violation.message);
  }
  if (messages.empty()) return Status::Ok();
  return Status::InvalidConfig(JoinViolations(messages));
}

StatusOr<SynthOptions> ParseSynthOptions(const YAML::Node& root, const std::string& source_name,
                                         const std::string& base_dir) {
  SynthOptions options;
  Status status = ParseInto(root, source_name, base_dir, &options);
  if (!status.ok()) return ToConfigError(status);
  std::vector<std::string> messages;
  for (const Violation& violation : CollectViolations(options)) {
    const YAML::Node node = FindField(root, violation.field);
    const std::string where =
        node.IsDefined() ? YamlWhere(source_name, node) : source_name + " (default)";
    messages.push_back(where + ": " + violation.message);
  }
  if (!messages.empty()) return Status::InvalidConfig(JoinViolations(messages));
  return options;
}

StatusOr<SynthOptions> ReadSynthOptions(const std::string& path,
                                        const std::vector<std::string>& overrides) {
  YAML::Node node(YAML::NodeType::Map);
  if (!path.empty()) {
    if (!std::filesystem::exists(path)) {
      return Status::InvalidConfig(fmt::format("{}: config file not found", path));
    }
    StatusOr<YAML::Node> root = LoadYamlFile(path, StatusCode::kInvalidConfig);
    if (!root.ok()) return ToConfigError(root.status());
    node = *root;
  }
  if (!overrides.empty()) {
    if (!node.IsDefined() || node.IsNull()) node = YAML::Node(YAML::NodeType::Map);
    Status status = ApplyYamlOverrides(overrides, &node);
    if (!status.ok()) return ToConfigError(status);
  }
  if (path.empty()) return ParseSynthOptions(node, "--set", "");
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  return ParseSynthOptions(node, path, base_dir);
}

std::string FormatSynthOptions(const SynthOptions& o) {
  std::string y;
  auto line = [&y](const std::string& key, const std::string& value) {
    y += "  " + key + ": " + value + "\n";
  };
  y += "# bcot synth: fully resolved options (bcot " BCOT_VERSION ")\n";
  y += "seed: " + std::to_string(o.seed) + "\n";

  y += "object:\n";
  line("mesh", Quote(o.object.mesh));
  line("name", Quote(o.object.name));
  line("size_mm", FormatNumber(o.object.size_mm));
  line("unit_to_mm", FormatNumber(o.object.unit_to_mm));
  line("color_rgb", NumberList(o.object.color_rgb));
  line("diffuse", FormatNumber(o.object.diffuse));
  line("specular", FormatNumber(o.object.specular));
  line("shininess", FormatNumber(o.object.shininess));
  line("crease_angle_deg", FormatNumber(o.object.crease_angle_deg));

  y += "cameras:\n";
  line("width", std::to_string(o.cameras.width));
  line("height", std::to_string(o.cameras.height));
  line("hfov_deg", FormatNumber(o.cameras.hfov_deg));
  line("distance_mm", FormatNumber(o.cameras.distance_mm));
  line("elevation_deg", FormatNumber(o.cameras.elevation_deg));
  line("arc_angles_deg", NumberList(o.cameras.arc_angles_deg));
  line("cone_angles_deg", NumberList(o.cameras.cone_angles_deg));
  line("distortion", NumberList(o.cameras.distortion));
  line("name_prefix", Quote(o.cameras.name_prefix));

  y += "motion:\n";
  line("mode", Quote(o.motion.mode));
  line("num_frames", std::to_string(o.motion.num_frames));
  line("fps", FormatNumber(o.motion.fps));
  line("rotation_deg_per_frame", FormatNumber(o.motion.rotation_deg_per_frame));
  line("translation_mm_per_frame", FormatNumber(o.motion.translation_mm_per_frame));
  line("speed_variation", FormatNumber(o.motion.speed_variation));
  line("workspace_radius_mm", FormatNumber(o.motion.workspace_radius_mm));
  line("frustum_margin_px", FormatNumber(o.motion.frustum_margin_px));
  line("rig_max_rotation_deg", FormatNumber(o.motion.rig_max_rotation_deg));
  line("object_motion_scale", FormatNumber(o.motion.object_motion_scale));

  y += "background:\n";
  line("kinds", StringList(o.background.kinds));
  line("images", StringList(o.background.images));
  line("backdrop_distance_mm", FormatNumber(o.background.backdrop_distance_mm));
  line("ground", Bool(o.background.ground));
  line("ground_clearance_mm", FormatNumber(o.background.ground_clearance_mm));
  line("clutter_shapes", std::to_string(o.background.clutter_shapes));
  line("similar_color_fraction", FormatNumber(o.background.similar_color_fraction));
  line("object_tint", FormatNumber(o.background.object_tint));

  y += "distractors:\n";
  line("count", std::to_string(o.distractors.count));
  line("meshes", StringList(o.distractors.meshes));
  line("size_min_mm", FormatNumber(o.distractors.size_min_mm));
  line("size_max_mm", FormatNumber(o.distractors.size_max_mm));
  line("allow_occlusion", Bool(o.distractors.allow_occlusion));
  line("similar_color_fraction", FormatNumber(o.distractors.similar_color_fraction));

  y += "light:\n";
  line("azimuth_deg", FormatNumber(o.light.azimuth_deg));
  line("elevation_deg", FormatNumber(o.light.elevation_deg));
  line("intensity", FormatNumber(o.light.intensity));
  line("ambient", FormatNumber(o.light.ambient));
  line("softness_deg", FormatNumber(o.light.softness_deg));
  line("moves", Bool(o.light.moves));
  line("deg_per_frame", FormatNumber(o.light.deg_per_frame));

  y += "render:\n";
  line("object_samples_per_axis", std::to_string(o.render.object_samples_per_axis));
  line("background_samples_per_axis", std::to_string(o.render.background_samples_per_axis));
  line("threads", std::to_string(o.render.threads));

  y += "sensor:\n";
  line("exposure", FormatNumber(o.sensor.exposure));
  line("gamma", FormatNumber(o.sensor.gamma));
  line("noise_sigma", FormatNumber(o.sensor.noise_sigma));
  line("shot_noise_gain", FormatNumber(o.sensor.shot_noise_gain));
  line("blur_sigma_px", FormatNumber(o.sensor.blur_sigma_px));
  line("motion_blur_subframes", std::to_string(o.sensor.motion_blur_subframes));
  line("exposure_fraction", FormatNumber(o.sensor.exposure_fraction));
  line("jpeg_quality", std::to_string(o.sensor.jpeg_quality));

  y += "init:\n";
  line("rotation_deg", FormatNumber(o.init.rotation_deg));
  line("translation_mm", FormatNumber(o.init.translation_mm));

  y += "output:\n";
  line("write_coverage", Bool(o.output.write_coverage));
  return y;
}

}  // namespace bcot

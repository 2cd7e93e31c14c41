#include "bcot/capture/capture_options.h"

#include <fmt/format.h>

#include "bcot/core/yaml_util.h"
#include "bcot/core/version.h"
#include "config_util.h"

namespace bcot {
namespace {

using capture_internal::ParseSection;

template <typename T>
Status GetOptionalValue(YamlMap& map, const std::string& key, std::optional<T>* value) {
  if (!map.Has(key)) return Status::Ok();
  T read{};
  BCOT_RETURN_IF_ERROR(map.Get(key, &read));
  *value = read;
  return Status::Ok();
}

StatusOr<CaptureOptions::Camera> ParseCamera(const YAML::Node& node, const std::string& source,
                                             int index) {
  YamlMap map(node, source, fmt::format("cameras[{}]", index), StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(map.Check());
  CaptureOptions::Camera camera;
  BCOT_RETURN_IF_ERROR(map.Get("name", &camera.name));
  BCOT_RETURN_IF_ERROR(map.Get("device_id", &camera.device_id));
  BCOT_RETURN_IF_ERROR(map.GetOptional("pixel_format", &camera.pixel_format));
  BCOT_RETURN_IF_ERROR(GetOptionalValue(map, "exposure_us", &camera.exposure_us));
  BCOT_RETURN_IF_ERROR(GetOptionalValue(map, "gain", &camera.gain));
  BCOT_RETURN_IF_ERROR(GetOptionalValue(map, "frame_rate_hz", &camera.frame_rate_hz));
  if (map.Has("region")) {
    std::vector<double> region;
    BCOT_RETURN_IF_ERROR(map.GetFixedArray("region", 4, &region));
    std::array<int, 4> pixels{};
    for (int i = 0; i < 4; ++i) {
      pixels[i] = static_cast<int>(region[i]);
      if (pixels[i] != region[i]) {
        return map.Error(
            "region", fmt::format("[x, y, width, height] must be whole pixels, got {}", region[i]));
      }
    }
    camera.region = pixels;
  }
  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());
  return camera;
}

}  // namespace

Status CaptureOptions::Validate() const {
  capture_internal::Violations v;
  v.InRange("aravis.num_buffers", aravis.num_buffers, 2, 256);
  v.OneOf("trigger.mode", trigger.mode, {"software", "hardware", "free_run"});
  if (trigger.mode == "hardware" && trigger.source.empty()) {
    v.Add("trigger.source", "\"\"", "must name an input line in hardware mode");
  }
  if (cameras.empty()) v.Add("cameras", "[]", "must list at least one camera");
  std::vector<std::string> names;
  for (size_t i = 0; i < cameras.size(); ++i) {
    const Camera& camera = cameras[i];
    const std::string field = fmt::format("cameras[{}]", i);
    names.push_back(camera.name);
    if (camera.device_id.empty()) v.Add(field + ".device_id", "\"\"", "must not be empty");
    if (camera.exposure_us) v.Positive(field + ".exposure_us", *camera.exposure_us);
    if (camera.gain && !(*camera.gain >= 0.0)) {
      v.Add(field + ".gain", fmt::format("{}", *camera.gain), "must be >= 0");
    }
    if (camera.frame_rate_hz) v.Positive(field + ".frame_rate_hz", *camera.frame_rate_hz);
    if (camera.region) {
      const std::array<int, 4>& r = *camera.region;
      if (r[0] < 0 || r[1] < 0 || r[2] <= 0 || r[3] <= 0) {
        v.Add(field + ".region", fmt::format("[{}, {}, {}, {}]", r[0], r[1], r[2], r[3]),
              "x, y must be >= 0 and width, height > 0");
      }
    }
  }
  v.CameraNames("cameras", names);
  const Status options = v.ToStatus("capture options");
  const Status recording_options = recording.Validate();
  if (options.ok()) return recording_options;
  if (recording_options.ok()) return options;
  return Status::InvalidConfig(options.message() + "; " + recording_options.message());
}

StatusOr<CaptureOptions> ParseCaptureOptions(const YAML::Node& root_node,
                                             const std::string& source_name,
                                             const std::string& base_dir) {
  CaptureOptions o;
  if (root_node.IsDefined() && !root_node.IsNull()) {
    YamlMap root(root_node, source_name, "", StatusCode::kInvalidConfig);
    BCOT_RETURN_IF_ERROR(root.Check());
    BCOT_RETURN_IF_ERROR(ParseSection(root, "aravis", [&](YamlMap& m) -> Status {
      BCOT_RETURN_IF_ERROR(m.GetOptional("enable_fake_interface", &o.aravis.enable_fake_interface));
      return m.GetOptional("num_buffers", &o.aravis.num_buffers);
    }));
    BCOT_RETURN_IF_ERROR(ParseSection(root, "trigger", [&](YamlMap& m) -> Status {
      BCOT_RETURN_IF_ERROR(m.GetOptional("mode", &o.trigger.mode));
      return m.GetOptional("source", &o.trigger.source);
    }));
    if (root.Has("cameras")) {
      const YAML::Node cameras = root.Node("cameras");
      if (!cameras.IsSequence()) {
        return root.Error("cameras", "expected a list of cameras (- name: ..., device_id: ...)");
      }
      for (size_t i = 0; i < cameras.size(); ++i) {
        BCOT_ASSIGN_OR_RETURN(CaptureOptions::Camera camera,
                              ParseCamera(cameras[i], source_name, static_cast<int>(i)));
        o.cameras.push_back(std::move(camera));
      }
    }
    BCOT_RETURN_IF_ERROR(ParseSection(root, "recording", [&](YamlMap& m) -> Status {
      RecorderOptions& r = o.recording;
      BCOT_RETURN_IF_ERROR(m.GetOptional("max_frame_sets", &r.max_frame_sets));
      BCOT_RETURN_IF_ERROR(m.GetOptional("max_duration_s", &r.max_duration_s));
      BCOT_RETURN_IF_ERROR(m.GetOptional("max_skew_ms", &r.max_skew_ms));
      BCOT_RETURN_IF_ERROR(m.GetOptional("grab_timeout_ms", &r.grab_timeout_ms));
      BCOT_RETURN_IF_ERROR(m.GetOptional("max_consecutive_misses", &r.max_consecutive_misses));
      BCOT_RETURN_IF_ERROR(m.GetOptional("max_rounds_without_set", &r.max_rounds_without_set));
      BCOT_RETURN_IF_ERROR(m.GetOptional("png_compression", &r.png_compression));
      BCOT_RETURN_IF_ERROR(m.GetOptional("rig_yaml", &r.rig_yaml));
      r.rig_yaml = capture_internal::ResolveConfigPath(base_dir, r.rig_yaml);
      return Status::Ok();
    }));
    BCOT_RETURN_IF_ERROR(root.CheckNoUnknownKeys());
  }
  return capture_internal::Validated(std::move(o), source_name);
}

StatusOr<CaptureOptions> ReadCaptureOptions(const std::string& path,
                                            const std::vector<std::string>& overrides) {
  return capture_internal::ReadOptions<CaptureOptions>(path, overrides, ParseCaptureOptions);
}

std::string FormatCaptureOptions(const CaptureOptions& o) {
  const auto b = [](bool value) { return value ? "true" : "false"; };
  std::string y = fmt::format("# bcot capture: fully resolved options (bcot {})\n", BcotVersion());
  y += fmt::format("aravis:\n  enable_fake_interface: {}\n  num_buffers: {}\n",
                   b(o.aravis.enable_fake_interface), o.aravis.num_buffers);
  y += fmt::format("trigger:\n  mode: {}\n  source: {}\n", FormatYamlString(o.trigger.mode),
                   FormatYamlString(o.trigger.source));
  y += "cameras:\n";
  for (const CaptureOptions::Camera& c : o.cameras) {
    y += fmt::format("  - name: {}\n    device_id: {}\n", FormatYamlString(c.name),
                     FormatYamlString(c.device_id));
    if (!c.pixel_format.empty()) {
      y += fmt::format("    pixel_format: {}\n", FormatYamlString(c.pixel_format));
    }
    if (c.exposure_us) y += fmt::format("    exposure_us: {}\n", *c.exposure_us);
    if (c.gain) y += fmt::format("    gain: {}\n", *c.gain);
    if (c.frame_rate_hz) y += fmt::format("    frame_rate_hz: {}\n", *c.frame_rate_hz);
    if (c.region) y += fmt::format("    region: [{}]\n", fmt::join(*c.region, ", "));
  }
  const RecorderOptions& r = o.recording;
  y += fmt::format(
      "recording:\n  max_frame_sets: {}\n  max_duration_s: {}\n  max_skew_ms: {}\n"
      "  grab_timeout_ms: {}\n  max_consecutive_misses: {}\n  max_rounds_without_set: {}\n"
      "  png_compression: {}\n  rig_yaml: {}\n",
      r.max_frame_sets, r.max_duration_s, r.max_skew_ms, r.grab_timeout_ms,
      r.max_consecutive_misses, r.max_rounds_without_set, r.png_compression,
      FormatYamlString(r.rig_yaml));
  return y;
}

}  // namespace bcot

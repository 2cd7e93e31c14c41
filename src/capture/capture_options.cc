#include "bcot/capture/capture_options.h"

#include <fmt/format.h>

#include "bcot/core/version.h"
#include "bcot/core/yaml_util.h"
#include "camera_names.h"

namespace bcot {
namespace {

using Camera = CaptureOptions::Camera;
using option_internal::PartViolation;

template <typename T>
Status GetOptionalValue(YamlMap& map, const std::string& key, std::optional<T>* value) {
  if (!map.Has(key)) {
    map.Node(key);  // a known key (listed by unknown-key errors), absent
    return Status::Ok();
  }
  T read{};
  BCOT_RETURN_IF_ERROR(map.Get(key, &read));
  *value = read;
  return Status::Ok();
}

StatusOr<Camera> ParseCamera(const YAML::Node& node, const std::string& source, int index) {
  YamlMap map(node, source, fmt::format("cameras[{}]", index), StatusCode::kInvalidConfig);
  BCOT_RETURN_IF_ERROR(map.Check());
  Camera camera;
  BCOT_RETURN_IF_ERROR(map.Get("name", &camera.name));
  BCOT_RETURN_IF_ERROR(map.Get("device_id", &camera.device_id));
  BCOT_RETURN_IF_ERROR(map.GetOptional("pixel_format", &camera.pixel_format));
  BCOT_RETURN_IF_ERROR(GetOptionalValue(map, "exposure_us", &camera.exposure_us));
  BCOT_RETURN_IF_ERROR(GetOptionalValue(map, "gain", &camera.gain));
  BCOT_RETURN_IF_ERROR(GetOptionalValue(map, "frame_rate_hz", &camera.frame_rate_hz));
  if (!map.Has("region")) {
    map.Node("region");  // known, absent
  } else {
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

// `cameras`: a list of mappings, one per camera (the header's Camera).
Status ReadCameras(YamlMap& map, const std::string&, std::vector<Camera>* cameras) {
  const YAML::Node node = map.Node("cameras");
  if (!node.IsSequence()) {
    return map.Error("cameras", "expected a list of cameras (- name: ..., device_id: ...)");
  }
  cameras->clear();
  for (size_t i = 0; i < node.size(); ++i) {
    BCOT_ASSIGN_OR_RETURN(Camera camera,
                          ParseCamera(node[i], map.source_name(), static_cast<int>(i)));
    cameras->push_back(std::move(camera));
  }
  return Status::Ok();
}

// The cameras as ReadCameras reads them back (absent settings stay absent).
void EmitCameras(YAML::Emitter& out, const std::vector<Camera>& cameras) {
  if (cameras.empty()) {
    out << YAML::Flow << YAML::BeginSeq << YAML::EndSeq;
    return;
  }
  out << YAML::BeginSeq;
  for (const Camera& camera : cameras) {
    out << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value;
    option_internal::EmitValue(out, camera.name);
    out << YAML::Key << "device_id" << YAML::Value;
    option_internal::EmitValue(out, camera.device_id);
    if (!camera.pixel_format.empty()) {
      out << YAML::Key << "pixel_format" << YAML::Value;
      option_internal::EmitValue(out, camera.pixel_format);
    }
    const std::pair<const char*, const std::optional<double>*> numbers[] = {
        {"exposure_us", &camera.exposure_us},
        {"gain", &camera.gain},
        {"frame_rate_hz", &camera.frame_rate_hz}};
    for (const auto& [key, value] : numbers) {
      if (!value->has_value()) continue;
      out << YAML::Key << key << YAML::Value;
      option_internal::EmitValue(out, **value);
    }
    if (camera.region) {
      out << YAML::Key << "region" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (int v : *camera.region) out << v;
      out << YAML::EndSeq;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

std::string CamerasText(const std::vector<Camera>& cameras) {
  std::vector<std::string> names;
  for (const Camera& camera : cameras) names.push_back(camera.name);
  return option_internal::ValueText(names);
}

// Every camera setting that breaks its rule, and every name that cannot be a folder.
std::vector<PartViolation> CameraViolations(const CaptureOptions& o) {
  std::vector<PartViolation> violations;
  std::vector<std::string> names;
  for (const Camera& camera : o.cameras) names.push_back(camera.name);
  for (size_t i = 0; i < o.cameras.size(); ++i) {
    const Camera& camera = o.cameras[i];
    const std::string key = fmt::format("cameras[{}]", i);
    const std::string name_rule = capture_internal::CameraNameRule(names, i);
    if (!name_rule.empty()) {
      violations.push_back({key, option_internal::ValueText(camera.name), name_rule});
    }
    if (camera.device_id.empty()) {
      violations.push_back({key + ".device_id", "''", "must not be empty"});
    }
    const auto check = [&](const char* field, const std::optional<double>& value, bool ok,
                           const char* rule) {
      if (value && !ok) {
        violations.push_back({key + "." + field, option_internal::ValueText(*value), rule});
      }
    };
    check("exposure_us", camera.exposure_us, camera.exposure_us > 0.0, "must be > 0");
    check("gain", camera.gain, camera.gain >= 0.0, "must be >= 0");
    check("frame_rate_hz", camera.frame_rate_hz, camera.frame_rate_hz > 0.0, "must be > 0");
    if (camera.region) {
      const std::array<int, 4>& r = *camera.region;
      if (r[0] < 0 || r[1] < 0 || r[2] <= 0 || r[3] <= 0) {
        violations.push_back({key + ".region",
                              fmt::format("[{}, {}, {}, {}]", r[0], r[1], r[2], r[3]),
                              "x, y must be >= 0 and width, height > 0"});
      }
    }
  }
  return violations;
}

OptionSchema<CaptureOptions>* BuildCaptureOptionSchema() {
  auto* s = new OptionSchema<CaptureOptions>();
  s->Add(
      "aravis.enable_fake_interface",
      [](auto& o) -> auto& { return o.aravis.enable_fake_interface; }, "",
      "also list Aravis' in-process fake camera (Fake_1), for tests and demos");
  s->Add(
       "aravis.num_buffers", [](auto& o) -> auto& { return o.aravis.num_buffers; }, "",
       "stream buffers per camera: frames held while the recorder writes")
      .Range(Closed(2, 256));
  s->Add(
       "trigger.mode", [](auto& o) -> auto& { return o.trigger.mode; }, "",
       "software: one trigger per frame set; hardware: an edge on `source`; free_run: pair by "
       "host timestamp")
      .OneOf({"software", "hardware", "free_run"});
  s->Add(
       "trigger.source", [](auto& o) -> auto& { return o.trigger.source; }, "",
       "trigger input line of hardware mode (Line0, Line1, ...)")
      .Check([](const CaptureOptions& o) {
        return o.trigger.mode == "hardware" && o.trigger.source.empty()
                   ? "must name an input line in hardware mode"
                   : "";
      });
  s->AddCustom(
       "cameras", [](auto& o) -> auto& { return o.cameras; }, ReadCameras, EmitCameras, CamerasText,
       "one mapping per camera: name, device_id, and optional pixel_format, exposure_us, gain, "
       "frame_rate_hz, region [x, y, width, height]")
      .Check([](const CaptureOptions& o) {
        return o.cameras.empty() ? "must list at least one camera" : "";
      })
      .CheckParts(CameraViolations);
  s->Include(
      RecorderOptionSchema(), [](auto& o) -> auto& { return o.recording; });
  return s;
}

}  // namespace

const OptionSchema<CaptureOptions>& CaptureOptionSchema() {
  static const OptionSchema<CaptureOptions>* const schema = BuildCaptureOptionSchema();
  return *schema;
}

Status CaptureOptions::Validate() const { return CaptureOptionSchema().Validate(*this, nullptr); }

StatusOr<CaptureOptions> ReadCaptureOptions(const std::string& path,
                                            const std::vector<std::string>& overrides) {
  return CaptureOptionSchema().Read(path, overrides);
}

StatusOr<CaptureOptions> ParseCaptureOptions(const YAML::Node& root, const std::string& source_name,
                                             const std::string& base_dir) {
  CaptureOptions options;
  OptionSources sources;
  BCOT_RETURN_IF_ERROR(
      CaptureOptionSchema().Parse(root, source_name, base_dir, &options, &sources));
  BCOT_RETURN_IF_ERROR(CaptureOptionSchema().Validate(options, &sources));
  return options;
}

std::string FormatCaptureOptions(const CaptureOptions& options) {
  return CaptureOptionSchema().Emit(
      options, {fmt::format("bcot capture: fully resolved options (bcot {})", BcotVersion())});
}

}  // namespace bcot

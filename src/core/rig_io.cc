#include "bcot/core/rig_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/yaml_util.h"

namespace bcot {
namespace {

// Plausibility bounds of rig.yaml (beyond them a value is a typo or a unit slip, and would make
// the projection or the ray caster meaningless).
constexpr double kMinFocalPerImageSize = 0.01;  // f ≥ 1 % of the larger image side
constexpr double kMaxFocalPerImageSize = 1000;  // f ≤ 1000 × the larger image side
constexpr double kMaxCameraDistanceMm = 1e7;    // 10 km
constexpr double kMinRadialFactor = 0.25;       // r_distorted / r over the image
constexpr double kMaxRadialFactor = 4.0;

// Focal lengths within [kMin, kMax]FocalPerImageSize × max(width, height); the principal point
// at most one image size outside the image.
Status CheckIntrinsicsPlausible(const Camera& camera, const YamlMap& map) {
  const double size = std::max(camera.width, camera.height);
  const double min_f = kMinFocalPerImageSize * size, max_f = kMaxFocalPerImageSize * size;
  for (const double f : {camera.fx, camera.fy}) {
    if (!(f >= min_f && f <= max_f)) {
      return map.Error(
          "K", fmt::format("fx = {}, fy = {}: outside [{:g}, {:g}] px, the plausible "
                           "focal lengths of a {}x{} image",
                           camera.fx, camera.fy, min_f, max_f, camera.width, camera.height));
    }
  }
  if (!(camera.cx >= -camera.width && camera.cx <= 2.0 * camera.width &&
        camera.cy >= -camera.height && camera.cy <= 2.0 * camera.height)) {
    return map.Error("K", fmt::format("principal point ({}, {}) lies more than one image size "
                                      "outside the {}x{} image",
                                      camera.cx, camera.cy, camera.width, camera.height));
  }
  return Status::Ok();
}

// The radial distortion r ↦ r·(1 + k1 r² + k2 r⁴ + k3 r⁶) must be increasing, and scale r by a
// factor within [kMinRadialFactor, kMaxRadialFactor], for every r up to the normalised radius
// of the image corner farthest from the principal point: otherwise two rays map to one pixel
// (the model folds over inside the image) and the inverse the renderer needs does not exist.
Status CheckDistortionPlausible(const Camera& camera, const YamlMap& map) {
  const double k1 = camera.distortion[0], k2 = camera.distortion[1], k3 = camera.distortion[4];
  double corner_radius = 0.0;
  for (const double u : {0.0, camera.width - 1.0}) {
    for (const double v : {0.0, camera.height - 1.0}) {
      corner_radius = std::max(
          corner_radius, std::hypot((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy));
    }
  }
  constexpr int kSteps = 200;
  for (int i = 1; i <= kSteps; ++i) {
    const double r = corner_radius * i / kSteps, r2 = r * r;
    const double factor = 1.0 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2;
    const double slope = 1.0 + 3.0 * k1 * r2 + 5.0 * k2 * r2 * r2 + 7.0 * k3 * r2 * r2 * r2;
    if (!(slope > 0.0) || !(factor >= kMinRadialFactor && factor <= kMaxRadialFactor)) {
      return map.Error(
          "distortion",
          fmt::format("[k1, k2, p1, p2, k3] = [{}, {}, {}, {}, {}]: at normalised radius {:.3g} "
                      "(within the image) the radial model {} (factor {:.3g}); expected an "
                      "increasing model scaling radii by {} to {}",
                      k1, k2, camera.distortion[2], camera.distortion[3], k3, r,
                      slope > 0.0 ? "is out of range" : "folds over", factor, kMinRadialFactor,
                      kMaxRadialFactor));
    }
  }
  return Status::Ok();
}

StatusOr<RigCamera> ParseCamera(const YAML::Node& node, const std::string& source_name, int index) {
  YamlMap map(node, source_name, fmt::format("cameras[{}]", index));
  RigCamera rig_camera;
  Camera& camera = rig_camera.camera;

  BCOT_RETURN_IF_ERROR(map.Get("name", &camera.name));
  if (camera.name.empty()) return map.Error("name", "must not be empty");
  // The name is a folder name in the sequence directory.
  if (camera.name.find_first_of("/\\") != std::string::npos || camera.name == "." ||
      camera.name == "..") {
    return map.Error("name", fmt::format("'{}' must be usable as a folder name (no '/', '\\', "
                                         "'.' or '..')",
                                         camera.name));
  }

  std::vector<int> image_size;
  BCOT_RETURN_IF_ERROR(map.Get("image_size", &image_size));
  if (image_size.size() != 2) {
    return map.Error("image_size",
                     fmt::format("expected 2 numbers [width, height], got {}", image_size.size()));
  }
  if (image_size[0] <= 0 || image_size[1] <= 0) {
    return map.Error("image_size", fmt::format("[{}, {}], width and height must be > 0",
                                               image_size[0], image_size[1]));
  }
  camera.width = image_size[0];
  camera.height = image_size[1];

  std::vector<double> k;
  BCOT_RETURN_IF_ERROR(map.GetFixedArray("K", 4, &k));
  if (!(k[0] > 0.0) || !(k[1] > 0.0)) {
    return map.Error("K", fmt::format("[fx, fy, cx, cy] = [{}, {}, {}, {}], fx and fy must be > 0",
                                      k[0], k[1], k[2], k[3]));
  }
  camera.fx = k[0];
  camera.fy = k[1];
  camera.cx = k[2];
  camera.cy = k[3];

  BCOT_RETURN_IF_ERROR(CheckIntrinsicsPlausible(camera, map));

  if (map.Has("distortion")) {
    std::vector<double> distortion;
    BCOT_RETURN_IF_ERROR(map.GetFixedArray("distortion", 5, &distortion));
    for (int i = 0; i < 5; ++i) camera.distortion[i] = distortion[i];
    BCOT_RETURN_IF_ERROR(CheckDistortionPlausible(camera, map));
  } else {
    map.Node("distortion");  // known key, absent: zeros
  }

  std::vector<double> m;
  BCOT_RETURN_IF_ERROR(map.GetFixedArray("cam_from_rig", 16, &m));
  if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0) {
    return map.Error("cam_from_rig",
                     fmt::format("last row is [{}, {}, {}, {}], expected [0, 0, 0, 1]", m[12],
                                 m[13], m[14], m[15]));
  }
  Eigen::Matrix3d rotation;
  rotation << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
  std::string why;
  if (!OrthonormalizeReadRotation(&rotation, &why)) return map.Error("cam_from_rig", why);
  rig_camera.cam_from_rig.linear() = rotation;
  rig_camera.cam_from_rig.translation() = Eigen::Vector3d(m[3], m[7], m[11]);
  if (!(rig_camera.cam_from_rig.translation().norm() <= kMaxCameraDistanceMm)) {
    return map.Error("cam_from_rig",
                     fmt::format("translation ({}, {}, {}) mm is more than {:g} km from the rig "
                                 "origin; translations are in mm",
                                 m[3], m[7], m[11], kMaxCameraDistanceMm / 1e6));
  }

  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());
  return rig_camera;
}

std::string FormatNumbers(const double* values, int count) {
  std::string text;
  for (int i = 0; i < count; ++i) text += fmt::format("{}{}", i == 0 ? "" : ", ", values[i]);
  return text;
}

}  // namespace

StatusOr<Rig> ParseRigYaml(const std::string& text, const std::string& source_name) {
  BCOT_ASSIGN_OR_RETURN(const YAML::Node root, ParseYaml(text, source_name));
  YamlMap map(root, source_name, "");
  BCOT_RETURN_IF_ERROR(map.Check());
  const YAML::Node cameras = map.Node("cameras");
  if (!cameras.IsDefined()) return map.Error("cameras", "missing required key");
  if (!cameras.IsSequence() || cameras.size() == 0) {
    return map.Error("cameras", "expected a non-empty sequence of cameras (- name: ...)");
  }
  BCOT_RETURN_IF_ERROR(map.CheckNoUnknownKeys());

  Rig rig;
  std::map<std::string, int> first_index;
  for (size_t i = 0; i < cameras.size(); ++i) {
    const int index = static_cast<int>(i);
    BCOT_ASSIGN_OR_RETURN(RigCamera camera, ParseCamera(cameras[i], source_name, index));
    const auto [it, inserted] = first_index.emplace(camera.camera.name, index);
    if (!inserted) {
      YamlMap camera_map(cameras[i], source_name, fmt::format("cameras[{}]", index));
      return camera_map.Error("name", fmt::format("'{}' is already the name of cameras[{}]",
                                                  camera.camera.name, it->second));
    }
    rig.Add(std::move(camera));
  }
  // Everything Validate checks was checked above with line numbers; this guards against the
  // two drifting apart.
  const Status valid = rig.Validate();
  if (!valid.ok()) return Status::InvalidInput(source_name + ": " + valid.message());
  return rig;
}

StatusOr<Rig> ReadRigYaml(const std::string& path) {
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  return ParseRigYaml(text, path);
}

std::string FormatRigYaml(const Rig& rig) {
  std::string text = "cameras:\n";
  for (const RigCamera& rig_camera : rig.cameras()) {
    const Camera& camera = rig_camera.camera;
    text += fmt::format("  - name: {}\n", FormatYamlString(camera.name));
    text += fmt::format("    image_size: [{}, {}]\n", camera.width, camera.height);
    const double k[4] = {camera.fx, camera.fy, camera.cx, camera.cy};
    text += fmt::format("    K: [{}]\n", FormatNumbers(k, 4));
    if (camera.HasDistortion()) {
      text += fmt::format("    distortion: [{}]\n", FormatNumbers(camera.distortion.data(), 5));
    }
    // Row-major 4×4, one row per line; the continuation lines are indented past the key, as a
    // flow sequence inside a block mapping requires.
    const Eigen::Matrix4d m = rig_camera.cam_from_rig.matrix();
    text += "    cam_from_rig: [";
    for (int row = 0; row < 4; ++row) {
      const double values[4] = {m(row, 0), m(row, 1), m(row, 2), m(row, 3)};
      text += FormatNumbers(values, 4);
      text += row < 3 ? ",\n                   " : "]\n";
    }
  }
  return text;
}

Status WriteRigYaml(const std::string& path, const Rig& rig) {
  return WriteFileAtomic(path, FormatRigYaml(rig));
}

}  // namespace bcot

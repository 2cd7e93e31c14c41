#include "bcot/synth/synth_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "bcot/core/version.h"

namespace bcot {
namespace {

// "must be a plain file name" unless `name` can be a file name (no folder, not "." or "..").
std::string PlainFileName(const std::string& name, bool allow_empty) {
  if (name.empty() && allow_empty) return "";
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") {
    return allow_empty ? "must be a plain file name" : "must be a non-empty plain file name";
  }
  return "";
}

void DeclareObjectAndCameras(OptionSchema<SynthOptions>* s) {
  s->Add(
       "seed", [](auto& o) -> auto& { return o.seed; }, "",
       "seed of every random choice (same options + seed = same output)")
      .Range(NonNegative());
  s->Add(
       "object.mesh", [](auto& o) -> auto& { return o.object.mesh; }, "",
       "mesh file (OBJ, PLY, OFF, STL); \"\" = the built-in trefoil-knot part")
      .Path();
  s->Add(
       "object.name", [](auto& o) -> auto& { return o.object.name; }, "",
       "object and model-file name; \"\" = the mesh file's stem")
      .Check([](const SynthOptions& o) { return PlainFileName(o.object.name, true); });
  s->Add(
       "object.size_mm", [](auto& o) -> auto& { return o.object.size_mm; }, "mm",
       "scale the mesh to this longest bounding-box side; 0 = use unit_to_mm")
      .Range(Closed(0, 5000));
  s->Add(
       "object.unit_to_mm", [](auto& o) -> auto& { return o.object.unit_to_mm; }, "",
       "mesh units to mm when size_mm = 0")
      .Range(Positive());
  s->Add(
       "object.color_rgb", [](auto& o) -> auto& { return o.object.color_rgb; }, "sRGB",
       "surface colour (textureless)")
      .Range(Closed(0, 255));
  s->Add(
       "object.diffuse", [](auto& o) -> auto& { return o.object.diffuse; }, "",
       "diffuse albedo multiplier")
      .Range(Closed(0, 1));
  s->Add(
       "object.specular", [](auto& o) -> auto& { return o.object.specular; }, "",
       "Blinn-Phong specular strength")
      .Range(Closed(0, 10));
  s->Add(
       "object.shininess", [](auto& o) -> auto& { return o.object.shininess; }, "",
       "Blinn-Phong exponent: larger = smaller, sharper highlights")
      .Range(Closed(1, 10000));
  s->Add(
       "object.reflectance", [](auto& o) -> auto& { return o.object.reflectance; }, "",
       "clear-coat reflectance F0 (Schlick Fresnel; mirrors backdrop and table, 1 at the rim; "
       "0 = none)")
      .Range(Closed(0, 1));
  s->Add(
       "object.crease_angle_deg", [](auto& o) -> auto& { return o.object.crease_angle_deg; }, "deg",
       "normals are averaged across edges below this dihedral angle (0 = flat)")
      .Range(Closed(0, 180));
  s->Add(
       "cameras.width", [](auto& o) -> auto& { return o.cameras.width; }, "px",
       "image width of every camera")
      .Range(Closed(16, 8192));
  s->Add(
       "cameras.height", [](auto& o) -> auto& { return o.cameras.height; }, "px",
       "image height of every camera")
      .Range(Closed(16, 8192));
  s->Add(
       "cameras.hfov_deg", [](auto& o) -> auto& { return o.cameras.hfov_deg; }, "deg",
       "horizontal field of view")
      .Range(Open(1, 170));
  s->Add(
       "cameras.distance_mm", [](auto& o) -> auto& { return o.cameras.distance_mm; }, "mm",
       "distance of every camera centre to the target point")
      .Range(Positive());
  s->Add(
       "cameras.elevation_deg", [](auto& o) -> auto& { return o.cameras.elevation_deg; }, "deg",
       "elevation of C-0 above the horizontal plane through the target")
      .Range(Closed(-80, 80));
  s->Add(
       "cameras.arc_angles_deg", [](auto& o) -> auto& { return o.cameras.arc_angles_deg; }, "deg",
       "one camera per entry on the arc through C-0, at this angle to C-0")
      .Range(Open(0, 180));
  s->Add(
       "cameras.cone_angles_deg", [](auto& o) -> auto& { return o.cameras.cone_angles_deg; }, "deg",
       "one out-of-plane cone camera per entry, at this angle to C-0 and the arc")
      .Range(Open(0, 120));
  s->Add(
       "cameras.distortion", [](auto& o) -> auto& { return o.cameras.distortion; }, "",
       "OpenCV distortion k1, k2, p1, p2, k3 of every camera")
      .Range(Closed(-1, 1));
  s->Add(
       "cameras.name_prefix", [](auto& o) -> auto& { return o.cameras.name_prefix; }, "",
       "camera names are this prefix + index")
      .Check([](const SynthOptions& o) { return PlainFileName(o.cameras.name_prefix, false); });
}

void DeclareMotionAndBackground(OptionSchema<SynthOptions>* s) {
  s->Add(
       "motion.mode", [](auto& o) -> auto& { return o.motion.mode; }, "",
       "free: object moves; rotate: object rotates in place; rig: the rig moves")
      .OneOf({"free", "rotate", "rig"});
  s->Add(
       "motion.num_frames", [](auto& o) -> auto& { return o.motion.num_frames; }, "",
       "number of frames")
      .Range(Closed(1, 100000));
  s->Add(
       "motion.fps", [](auto& o) -> auto& { return o.motion.fps; }, "Hz",
       "frame rate for timestamps.csv")
      .Range(LeftOpen(0, 10000));
  s->Add(
       "motion.rotation_deg_per_frame",
       [](auto& o) -> auto& { return o.motion.rotation_deg_per_frame; }, "deg",
       "mean rotation speed")
      .Range(Closed(0, 90));
  s->Add(
       "motion.translation_mm_per_frame",
       [](auto& o) -> auto& { return o.motion.translation_mm_per_frame; }, "mm",
       "mean translation speed")
      .Range(Closed(0, 1000));
  s->Add(
       "motion.speed_variation", [](auto& o) -> auto& { return o.motion.speed_variation; }, "",
       "relative amplitude of the smooth speed modulation")
      .Range(Closed(0, 0.9));
  s->Add(
       "motion.workspace_radius_mm", [](auto& o) -> auto& { return o.motion.workspace_radius_mm; },
       "mm", "ball the object centre stays in; 0 = the largest that keeps it in every view")
      .Range(NonNegative());
  s->Add(
       "motion.frustum_margin_px", [](auto& o) -> auto& { return o.motion.frustum_margin_px; },
       "px", "margin the object keeps to every image border")
      .Range(Closed(0, 1000));
  s->Add(
       "motion.rig_max_rotation_deg",
       [](auto& o) -> auto& { return o.motion.rig_max_rotation_deg; }, "deg",
       "rig mode: largest pan of the rig about the look-at point")
      .Range(LeftOpen(0, 90));
  s->Add(
       "motion.object_motion_scale", [](auto& o) -> auto& { return o.motion.object_motion_scale; },
       "", "rig mode: object speeds relative to the rig's (0 = static object)")
      .Range(Closed(0, 1));
  s->Add(
       "background.kinds", [](auto& o) -> auto& { return o.background.kinds; }, "",
       "per view, cycled: plain, cluttered or image")
      .OneOf({"plain", "cluttered", "image"})
      .Check([](const SynthOptions& o) {
        return o.background.kinds.empty() ? "must list at least one kind" : "";
      });
  s->Add(
       "background.images", [](auto& o) -> auto& { return o.background.images; }, "",
       "photos of the image views, cycled")
      .Path()
      .Check([](const SynthOptions& o) {
        const auto& b = o.background;
        const bool image_view = std::find(b.kinds.begin(), b.kinds.end(), "image") != b.kinds.end();
        return image_view && b.images.empty() ? "must list at least one photo when a kind is image"
                                              : "";
      });
  s->Add(
       "background.backdrop_distance_mm",
       [](auto& o) -> auto& { return o.background.backdrop_distance_mm; }, "mm",
       "each view's backdrop plane lies this far behind the target")
      .Range(Positive());
  s->Add(
      "background.ground", [](auto& o) -> auto& { return o.background.ground; }, "",
      "a textured table plane below the workspace");
  s->Add(
       "background.ground_clearance_mm",
       [](auto& o) -> auto& { return o.background.ground_clearance_mm; }, "mm",
       "gap between the object's lowest reach and the table")
      .Range(NonNegative());
  s->Add(
       "background.clutter_shapes", [](auto& o) -> auto& { return o.background.clutter_shapes; },
       "", "random shapes on a cluttered backdrop")
      .Range(Closed(0, 10000));
  s->Add(
       "background.similar_color_fraction",
       [](auto& o) -> auto& { return o.background.similar_color_fraction; }, "",
       "fraction of clutter shapes coloured close to the object")
      .Range(Closed(0, 1));
  s->Add(
       "background.object_tint", [](auto& o) -> auto& { return o.background.object_tint; }, "",
       "blend every backdrop and table texel towards the object colour (low contrast)")
      .Range(Closed(0, 1));
}

void DeclareSceneAndSensor(OptionSchema<SynthOptions>* s) {
  s->Add(
       "distractors.count", [](auto& o) -> auto& { return o.distractors.count; }, "",
       "distractor objects in the world")
      .Range(Closed(0, 100));
  s->Add(
       "distractors.meshes", [](auto& o) -> auto& { return o.distractors.meshes; }, "",
       "meshes to draw them from, cycled; [] = built-in boxes, cylinders, ellipsoids")
      .Path();
  s->Add(
       "distractors.size_min_mm", [](auto& o) -> auto& { return o.distractors.size_min_mm; }, "mm",
       "smallest longest bounding-box side")
      .Range(Positive());
  s->Add(
       "distractors.size_max_mm", [](auto& o) -> auto& { return o.distractors.size_max_mm; }, "mm",
       "largest longest bounding-box side")
      .Range(Positive())
      .Check([](const SynthOptions& o) -> std::string {
        const auto& d = o.distractors;
        if (d.size_max_mm >= d.size_min_mm) return "";
        return fmt::format("must be >= distractors.size_min_mm ({})", d.size_min_mm);
      });
  s->Add(
      "distractors.allow_occlusion", [](auto& o) -> auto& { return o.distractors.allow_occlusion; },
      "", "distractors may occlude the object partially");
  s->Add(
       "distractors.similar_color_fraction",
       [](auto& o) -> auto& { return o.distractors.similar_color_fraction; }, "",
       "fraction of distractors coloured close to the object")
      .Range(Closed(0, 1));
  s->Add(
       "light.azimuth_deg", [](auto& o) -> auto& { return o.light.azimuth_deg; }, "deg",
       "direction towards the light: azimuth about z")
      .Range(Closed(-360, 360));
  s->Add(
       "light.elevation_deg", [](auto& o) -> auto& { return o.light.elevation_deg; }, "deg",
       "... and elevation above the horizontal")
      .Range(Closed(-90, 90));
  s->Add(
       "light.intensity", [](auto& o) -> auto& { return o.light.intensity; }, "",
       "directional intensity")
      .Range(Closed(0, 10));
  s->Add(
       "light.ambient", [](auto& o) -> auto& { return o.light.ambient; }, "", "ambient intensity")
      .Range(Closed(0, 10));
  s->Add(
       "light.softness_deg", [](auto& o) -> auto& { return o.light.softness_deg; }, "deg",
       "angular radius of the key light: the terminator is smoothed over +-softness")
      .Range(Closed(0, 60));
  s->Add(
      "light.moves", [](auto& o) -> auto& { return o.light.moves; }, "",
      "the light turns about z by deg_per_frame every frame");
  s->Add(
       "light.deg_per_frame", [](auto& o) -> auto& { return o.light.deg_per_frame; }, "deg",
       "turn of a moving light per frame")
      .Range(Closed(-90, 90));
  s->Add(
       "render.object_samples_per_axis",
       [](auto& o) -> auto& { return o.render.object_samples_per_axis; }, "",
       "n x n rays per pixel near the object (anti-aliasing)")
      .Range(Closed(1, 16));
  s->Add(
       "render.background_samples_per_axis",
       [](auto& o) -> auto& { return o.render.background_samples_per_axis; }, "",
       "n x n background samples per pixel elsewhere")
      .Range(Closed(1, 8));
  s->Add(
       "render.threads", [](auto& o) -> auto& { return o.render.threads; }, "",
       "worker threads; 0 = all cores")
      .Range(Closed(0, 256));
  s->Add(
       "sensor.exposure", [](auto& o) -> auto& { return o.sensor.exposure; }, "",
       "linear radiance multiplier before noise and gamma")
      .Range(LeftOpen(0, 100));
  s->Add(
       "sensor.gamma", [](auto& o) -> auto& { return o.sensor.gamma; }, "",
       "display gamma of the 8-bit images (1 = linear)")
      .Range(Closed(1, 4));
  s->Add(
       "sensor.noise_sigma", [](auto& o) -> auto& { return o.sensor.noise_sigma; }, "",
       "Gaussian read noise, fraction of full scale")
      .Range(Closed(0, 1));
  s->Add(
       "sensor.shot_noise_gain", [](auto& o) -> auto& { return o.sensor.shot_noise_gain; }, "",
       "shot noise: variance += gain x signal")
      .Range(Closed(0, 1));
  s->Add(
       "sensor.blur_sigma_px", [](auto& o) -> auto& { return o.sensor.blur_sigma_px; }, "px",
       "Gaussian optical blur; 0 = off")
      .Range(Closed(0, 20));
  s->Add(
       "sensor.motion_blur_subframes",
       [](auto& o) -> auto& { return o.sensor.motion_blur_subframes; }, "",
       "sub-frame renders averaged for motion blur; 1 = off")
      .Range(Closed(1, 64));
  s->Add(
       "sensor.exposure_fraction", [](auto& o) -> auto& { return o.sensor.exposure_fraction; }, "",
       "motion blur spans this fraction of the frame interval")
      .Range(LeftOpen(0, 1));
  s->Add(
       "sensor.jpeg_quality", [](auto& o) -> auto& { return o.sensor.jpeg_quality; }, "",
       "0: frames as PNG; 1..100: as JPEG of that quality (libjpeg's 4:2:0 chroma)")
      .Range(Closed(0, 100));
  s->Add(
       "init.rotation_deg", [](auto& o) -> auto& { return o.init.rotation_deg; }, "deg",
       "init_pose.txt = frame 0's truth turned by this about a random axis ...")
      .Range(Closed(0, 180));
  s->Add(
       "init.translation_mm", [](auto& o) -> auto& { return o.init.translation_mm; }, "mm",
       "... and moved by this in a random direction")
      .Range(Closed(0, 1e6));
  s->Add(
      "output.write_coverage", [](auto& o) -> auto& { return o.output.write_coverage; }, "",
      "also write gt/<camera>/coverage_XXXXXX.png (anti-aliased object coverage)");
}

OptionSchema<SynthOptions>* BuildSynthOptionSchema() {
  auto* s = new OptionSchema<SynthOptions>();
  DeclareObjectAndCameras(s);
  DeclareMotionAndBackground(s);
  DeclareSceneAndSensor(s);
  return s;
}

}  // namespace

const OptionSchema<SynthOptions>& SynthOptionSchema() {
  static const OptionSchema<SynthOptions>* const schema = BuildSynthOptionSchema();
  return *schema;
}

Status SynthOptions::Validate() const { return SynthOptionSchema().Validate(*this, nullptr); }

StatusOr<SynthOptions> ParseSynthOptions(const YAML::Node& root, const std::string& source_name,
                                         const std::string& base_dir) {
  SynthOptions options;
  OptionSources sources;
  BCOT_RETURN_IF_ERROR(SynthOptionSchema().Parse(root, source_name, base_dir, &options, &sources));
  BCOT_RETURN_IF_ERROR(SynthOptionSchema().Validate(options, &sources));
  return options;
}

StatusOr<SynthOptions> ReadSynthOptions(const std::string& path,
                                        const std::vector<std::string>& overrides) {
  return SynthOptionSchema().Read(path, overrides);
}

std::string FormatSynthOptions(const SynthOptions& options) {
  return SynthOptionSchema().Emit(
      options, {fmt::format("bcot {}: fully resolved options (bcot {})", "synth", BcotVersion())});
}

}  // namespace bcot

// Options of `bcot synth`: synthetic multi-view sequences with exact ground truth.
//
// One struct per YAML section; YAML keys are spelled exactly as the fields. Paths in a config
// file (object.mesh, background.images, distractors.meshes) are relative to the config file
// and are stored here resolved (absolute or relative to the working directory), so the
// resolved YAML written by FormatSynthOptions reads back to the same options anywhere.
//
// World frame W used by the synthesizer: origin at the target point (centre of the object's
// workspace), z up, mm. The rig frame is C-0's camera frame (OpenCV axes).
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <string>
#include <vector>

#include "bcot/core/option_schema.h"
#include "bcot/core/status.h"

namespace bcot {

struct SynthOptions {
  // Seed of every random choice (trajectories, textures, distractors, noise, init pose).
  // Same options + same seed → byte-identical output. Range ≥ 0.
  int seed = 1;

  struct Object {
    // Mesh file (OBJ, PLY, OFF, STL). Empty = a built-in procedural trefoil-knot part.
    std::string mesh;
    // Object and model-file name in the sequence; empty = the mesh file's stem ("knot" for
    // the built-in mesh).
    std::string name;
    // > 0: scale the mesh so its longest bounding-box side is `size_mm` (BCOT objects are
    // 90–230 mm); 0: use `unit_to_mm` as given. Range [0, 5000].
    double size_mm = 150.0;
    // Mesh units → mm when size_mm = 0. Range > 0.
    double unit_to_mm = 1.0;
    // Surface colour, sRGB 0..255 (one colour per object: textureless).
    std::array<double, 3> color_rgb = {200.0, 70.0, 45.0};
    // Diffuse albedo multiplier, [0, 1].
    double diffuse = 0.85;
    // Blinn-Phong specular strength (painted 3D prints are glossy), [0, 10].
    double specular = 0.25;
    // Blinn-Phong exponent, [1, 10000]: larger = smaller, sharper highlights.
    double shininess = 40.0;
    // Reflectance at normal incidence F0 of a smooth clear coat, [0, 1]; 0 = none. The coat
    // mirrors the backdrop and the table with Schlick's Fresnel weight F0 + (1 − F0)(1 − n·v)⁵,
    // which reaches 1 at the silhouette: the outermost sliver of the rim shows what lies behind
    // the object, as glossy and metal surfaces do under real light (issue 12).
    double reflectance = 0.0;
    // Smooth-shading crease angle (deg), [0, 180]: normals are averaged across edges whose
    // dihedral angle is below it (0 = flat facets).
    double crease_angle_deg = 35.0;
  } object;

  struct Cameras {
    // Image size (px) of every camera, each in [16, 8192].
    int width = 640;
    int height = 512;
    // Horizontal field of view (deg), (1, 170); fx = fy = (width/2) / tan(hfov/2), principal
    // point at the image centre ((w−1)/2, (h−1)/2).
    double hfov_deg = 40.0;
    // Distance (mm) of every camera centre to the target point, > 0.
    double distance_mm = 600.0;
    // Elevation (deg) of C-0 above the horizontal plane through the target, [−80, 80].
    double elevation_deg = 20.0;
    // One camera per entry on the arc through C-0 and the target (the plane spanned by C-0's
    // x and z axes), at that included angle (deg) to C-0, each in (0, 180).
    std::vector<double> arc_angles_deg = {90.0};
    // One out-of-plane "cone" camera per entry: the apex of the equilateral spherical triangle
    // over C-0 and the arc position at that angle α, so its included angle with both is α.
    // It lies on the upper side of the arc plane. Each in (0, 120).
    std::vector<double> cone_angles_deg;
    // OpenCV distortion (k1, k2, p1, p2, k3) of every camera, written to rig.yaml and used
    // when rendering (through Camera::PixelToRay). Each |k| ≤ 1.
    std::array<double, 5> distortion = {0.0, 0.0, 0.0, 0.0, 0.0};
    // Camera names are `name_prefix` + index: 0 = C-0, then arc cameras, then cone cameras.
    std::string name_prefix = "cam";
  } cameras;

  struct Motion {
    // "free": object translates and rotates, cameras fixed; "rotate": object rotates about
    // its bounding-box centre, no translation; "rig": the whole rig moves in the world
    // (background moves, relative camera poses fixed), the object moves slowly.
    std::string mode = "free";
    // Number of frames, [1, 100000].
    int num_frames = 30;
    // Frame rate for timestamps.csv (Hz), (0, 10000].
    double fps = 60.0;
    // Mean speeds over the sequence (free/rotate: of the object; rig: of the rig), ≥ 0.
    double rotation_deg_per_frame = 2.0;
    double translation_mm_per_frame = 2.0;
    // Relative amplitude of the smooth speed modulation around the mean, [0, 0.9].
    double speed_variation = 0.35;
    // Radius (mm) of the ball around the target the object centre stays in, ≥ 0; 0 = auto:
    // the largest ball keeping the object's bounding sphere inside every view with the
    // margin below.
    double workspace_radius_mm = 0.0;
    // Margin (px) the object keeps to every image border, [0, 1000].
    double frustum_margin_px = 8.0;
    // rig mode: the rig pans about the moving look-at point by at most this angle (deg,
    // (0, 90]); mostly yaw, a third of it in pitch and roll.
    double rig_max_rotation_deg = 25.0;
    // rig mode: object speeds relative to the rig speeds, [0, 1] (0 = static object).
    double object_motion_scale = 0.2;
  } motion;

  struct Background {
    // Per view, cycled when shorter than the number of cameras: "plain" (smooth gradient with
    // low-frequency noise), "cluttered" (random shapes, gradients, textures, some in colours
    // close to the object's), "image" (a photo from `images`).
    std::vector<std::string> kinds = {"cluttered", "plain"};
    // Photos for the "image" views, cycled over them; resized/cropped to cover the backdrop.
    std::vector<std::string> images;
    // Each view's textured backdrop plane, fixed in the world, lies this far (mm) behind the
    // target along that camera's frame-0 optical axis and perpendicular to it, > 0.
    double backdrop_distance_mm = 350.0;
    // A textured table plane below the workspace, seen by every camera.
    bool ground = true;
    // Gap (mm) between the lowest reach of the object and the table, ≥ 0.
    double ground_clearance_mm = 20.0;
    // Number of random shapes on a cluttered backdrop, [0, 10000].
    int clutter_shapes = 150;
    // Fraction of clutter shapes coloured close to the object colour, [0, 1].
    double similar_color_fraction = 0.25;
    // Every backdrop and table texel is blended towards the object colour by this fraction,
    // [0, 1]: low object/background contrast, as in real scenes with same-coloured
    // surroundings (0 = textures as generated).
    double object_tint = 0.0;
  } background;

  struct Distractors {
    // Number of distractor objects in the world, [0, 100].
    int count = 3;
    // Meshes to draw them from (cycled); empty = built-in boxes, cylinders and ellipsoids.
    std::vector<std::string> meshes;
    // Longest bounding-box side (mm), uniform in [size_min_mm, size_max_mm], > 0.
    double size_min_mm = 60.0;
    double size_max_mm = 150.0;
    // false: distractors are placed behind or beside the object's workspace, never between a
    // camera and it; true: they may occlude it partially (never intersect its workspace).
    bool allow_occlusion = false;
    // Fraction of distractors coloured close to the object colour, [0, 1].
    double similar_color_fraction = 0.3;
  } distractors;

  struct Light {
    // Direction towards the directional light in the world: azimuth about z (deg) and
    // elevation above the horizontal (deg, [−90, 90]).
    double azimuth_deg = -45.0;
    double elevation_deg = 50.0;
    // Directional and ambient intensities, each [0, 10].
    double intensity = 0.85;
    double ambient = 0.3;
    // Angular radius (deg) of the key light, [0, 60]: a soft (area-like) light whose shading
    // terminator is smoothed over ±softness around n·l = 0 (0 = a point-like directional light).
    double softness_deg = 0.0;
    // When true the light turns about z by `deg_per_frame` every frame.
    bool moves = false;
    double deg_per_frame = 1.0;  // [−90, 90]
  } light;

  struct Render {
    // n×n rays per pixel inside the object's projected box (anti-aliasing), [1, 16].
    int object_samples_per_axis = 4;
    // n×n analytic background/distractor samples per pixel elsewhere, [1, 8].
    int background_samples_per_axis = 2;
    // Worker threads (TBB), [0, 256]; 0 = all cores.
    int threads = 0;
  } render;

  struct Sensor {
    // Linear radiance multiplier before noise and gamma, (0, 100].
    double exposure = 1.0;
    // Display gamma of the written 8-bit images, [1, 4] (1 = linear).
    double gamma = 2.2;
    // Gaussian read noise sigma, fraction of full scale (linear), [0, 1].
    double noise_sigma = 0.004;
    // Poisson-like shot noise: variance += shot_noise_gain · signal (linear), [0, 1].
    double shot_noise_gain = 0.002;
    // Gaussian optical blur sigma (px), [0, 20]; 0 = off.
    double blur_sigma_px = 0.0;
    // Motion blur: average of this many sub-frame renders along the trajectory over
    // `exposure_fraction` of the frame interval centred on the frame time, [1, 64]; 1 = off.
    int motion_blur_subframes = 1;
    double exposure_fraction = 0.5;  // (0, 1]
    // 0: frames are written as PNG; 1..100: as JPEG of that quality with 4:2:0 chroma
    // subsampling (what most cameras and video codecs deliver).
    int jpeg_quality = 0;
  } sensor;

  struct Init {
    // init_pose.txt = GT rig_from_object of frame 0 perturbed by exactly this rotation (deg,
    // [0, 180]) about a random axis and this translation (mm, ≥ 0) in a random direction.
    double rotation_deg = 5.0;
    double translation_mm = 5.0;
  } init;

  struct Output {
    // Also write gt/<camera>/coverage_XXXXXX.png: 8-bit anti-aliased object coverage (the
    // fraction of the pixel where the object is the nearest surface).
    bool write_coverage = false;
  } output;

  // Lists every violation as "field = value, rule", joined by "; " (kInvalidConfig): the rules
  // of SynthOptionSchema().
  Status Validate() const;
};

// The declaration of every option above (key, field, unit, rule, help). Built once.
const OptionSchema<SynthOptions>& SynthOptionSchema();

// Reads a config file strictly (unknown or duplicate keys are errors naming file:line:key),
// resolves its paths against the config file's directory, applies `overrides`
// ("section.key=value", YAML values; errors name `--set key`, paths are relative to the working
// directory) on top and validates. Missing sections and keys keep their defaults; an empty
// `path` means the defaults plus `overrides`.
StatusOr<SynthOptions> ReadSynthOptions(const std::string& path,
                                        const std::vector<std::string>& overrides = {});

// Same from a parsed document; `source_name` prefixes messages, `base_dir` resolves paths.
StatusOr<SynthOptions> ParseSynthOptions(const YAML::Node& root, const std::string& source_name,
                                         const std::string& base_dir);

// The fully resolved options as YAML (every key, paths as stored); reads back identically.
std::string FormatSynthOptions(const SynthOptions& options);

}  // namespace bcot

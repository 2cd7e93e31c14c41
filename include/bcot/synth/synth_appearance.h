// Appearance of `bcot synth` scenes: procedural and photo textures on backdrop/table planes,
// Blinn-Phong shading, and the sensor model (blur, shot and read noise, gamma, 8-bit).
//
// Colours are linear RGB floats (1 = full scale) until the sensor model encodes them; inputs
// given as sRGB 0..255 are converted with SrgbToLinear.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "bcot/core/status.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synth_scene.h"

namespace bcot {

// sRGB transfer function (IEC 61966-2-1) on [0, 1].
float SrgbToLinear(float value);
Eigen::Vector3f SrgbToLinear(const std::array<double, 3>& rgb_255);
cv::Mat3f SrgbImageToLinear(const cv::Mat3b& rgb);

// A linear-RGB image sampled bilinearly in texel units (texel centres at integer coordinates)
// with mirrored repetition outside, so planes are endless without seams.
class Texture {
 public:
  Texture() = default;
  explicit Texture(cv::Mat3f linear_rgb) : image_(std::move(linear_rgb)) {}
  Eigen::Vector3f Sample(double x, double y) const;
  const cv::Mat3f& image() const { return image_; }

 private:
  cv::Mat3f image_;
};

// Procedural textures (RGB, 8-bit sRGB), deterministic given the generator.
//   plain:     smooth muted gradient with low-frequency shading noise and fine grain;
//   cluttered: a plain base under `shapes` random rectangles, discs, ellipses, polygons,
//              strokes, stripes, checkers, gradients, noise patches and text, a
//              `similar_fraction` of them coloured close to `object_rgb_255`;
//   table:     wood-like grain with plank seams.
cv::Mat3b MakePlainTexture(const cv::Size& size, SynthRng* rng);
cv::Mat3b MakeClutteredTexture(const cv::Size& size, const std::array<double, 3>& object_rgb_255,
                               int shapes, double similar_fraction, SynthRng* rng);
cv::Mat3b MakeTableTexture(const cv::Size& size, SynthRng* rng);
// A photo resized to cover `size` and centre-cropped (RGB). kNotFound / kInvalidInput.
StatusOr<cv::Mat3b> LoadPhotoTexture(const std::string& path, const cv::Size& size);

// A textured plane fixed in the world. Texel (x, y) of the texture lies at
// origin + (x − (cols−1)/2)·texel_mm·u_axis + (y − (rows−1)/2)·texel_mm·v_axis.
struct TexturedPlane {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d u_axis = Eigen::Vector3d::UnitX();
  Eigen::Vector3d v_axis = Eigen::Vector3d::UnitY();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit; the textured side faces it
  double texel_mm = 1.0;
  Texture texture;

  // Distance t > 0 along `direction` from `from` to the plane (front side only), or −1.
  double Intersect(const Eigen::Vector3d& from, const Eigen::Vector3d& direction) const;
  Eigen::Vector3f Albedo(const Eigen::Vector3d& point) const;
};

// Surface reflectance: diffuse albedo (linear) plus a white Blinn-Phong lobe.
struct SurfaceMaterial {
  Eigen::Vector3f albedo = Eigen::Vector3f::Constant(0.5f);
  float specular = 0.0f;
  float shininess = 20.0f;
  float reflectance = 0.0f;  // clear-coat F0 (SynthOptions::Object::reflectance)
};

// Schlick's Fresnel weight of a clear coat with reflectance F0 at normal incidence, for
// cos θ = n·v (clamped to [0, 1]).
float SchlickFresnel(float f0, float cos_theta);

// Directional light plus ambient, in the frame the normals are given in.
struct SceneLight {
  Eigen::Vector3f to_light = Eigen::Vector3f::UnitZ();  // unit, towards the light
  float intensity = 1.0f;
  float ambient = 0.3f;
  // sin of the light's angular radius, [0, 1): 0 = a directional light.
  float softness = 0.0f;
};

// Irradiance factor of a light of angular radius ρ (softness = sin ρ) on a surface with
// c = n·l: c above sin ρ, 0 below −sin ρ and (c + sin ρ)² / (4 sin ρ) between (the usual
// smooth-terminator approximation of a disc light; C¹ at both ends). max(0, c) when
// softness = 0.
float SoftLambert(float n_dot_l, float softness);

// albedo·(ambient + intensity·SoftLambert(n·l)) + specular·intensity·(s+8)/(8π)·max(0, n·h)^s
// (energy-normalised Blinn-Phong), n and to_viewer unit.
Eigen::Vector3f Shade(const SurfaceMaterial& material, const SceneLight& light,
                      const Eigen::Vector3f& normal, const Eigen::Vector3f& to_viewer);

// Blends every texel of an sRGB texture towards `rgb_255` by `fraction` (background.object_tint).
void TintTexture(const std::array<double, 3>& rgb_255, double fraction, cv::Mat3b* rgb);

// Sensor model on a linear RGB image: optional Gaussian blur, exposure, shot noise
// (variance gain·signal) and read noise (sigma), clipping, gamma, 8-bit rounding. Noise is
// a hash of (noise_key, pixel, channel), so it is independent of threading. Returns BGR.
cv::Mat3b ApplySensor(const cv::Mat3f& linear_rgb, const SynthOptions::Sensor& sensor,
                      uint64_t noise_key);

}  // namespace bcot

#include "bcot/synth/synth_appearance.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "bcot/core/se3.h"

namespace bcot {
namespace {

int Mirror(int i, int n) {
  const int period = 2 * n;
  i %= period;
  if (i < 0) i += period;
  return i < n ? i : period - 1 - i;
}

cv::Scalar ToScalar(const Eigen::Vector3d& rgb) { return cv::Scalar(rgb[0], rgb[1], rgb[2]); }

// HSV (h in [0, 1), s, v in [0, 1]) → RGB 0..255.
Eigen::Vector3d HsvToRgb(double h, double s, double v) {
  const double h6 = 6.0 * (h - std::floor(h));
  const int sector = static_cast<int>(h6) % 6;
  const double f = h6 - std::floor(h6);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  Eigen::Vector3d rgb;
  switch (sector) {
    case 0:
      rgb = {v, t, p};
      break;
    case 1:
      rgb = {q, v, p};
      break;
    case 2:
      rgb = {p, v, t};
      break;
    case 3:
      rgb = {p, q, v};
      break;
    case 4:
      rgb = {t, p, v};
      break;
    default:
      rgb = {v, p, q};
      break;
  }
  return 255.0 * rgb;
}

Eigen::Vector3d RandomColor(SynthRng* rng) {
  return HsvToRgb(rng->Uniform(), rng->Uniform(0.1, 0.9), rng->Uniform(0.15, 0.95));
}

Eigen::Vector3d SimilarColor(const std::array<double, 3>& rgb, SynthRng* rng) {
  Eigen::Vector3d c;
  const double brightness = rng->Uniform(0.8, 1.15);
  for (int i = 0; i < 3; ++i)
    c[i] = std::clamp(rgb[i] * brightness + 10.0 * rng->Normal(), 0.0, 255.0);
  return c;
}

// Smooth noise in about [−1, 1]: a random cells_x × cells_y grid, bicubically upsampled.
cv::Mat1f LowFrequencyNoise(const cv::Size& size, int cells_x, int cells_y, SynthRng* rng) {
  cv::Mat1f grid(cells_y, cells_x);
  for (int r = 0; r < cells_y; ++r) {
    for (int c = 0; c < cells_x; ++c) grid(r, c) = static_cast<float>(rng->Uniform(-1.0, 1.0));
  }
  cv::Mat1f noise;
  cv::resize(grid, noise, size, 0, 0, cv::INTER_CUBIC);
  return noise;
}

// Multiplies each channel by (1 + shade) and adds Gaussian grain (8-bit levels).
void ModulateAndGrain(const cv::Mat1f& shade, double grain_levels, SynthRng* rng,
                      cv::Mat3b* image) {
  const uint64_t key = rng->Next();
  for (int r = 0; r < image->rows; ++r) {
    for (int c = 0; c < image->cols; ++c) {
      cv::Vec3b& px = (*image)(r, c);
      const double grain = grain_levels * HashNormal(key + static_cast<uint64_t>(r) * 100003u + c);
      for (int k = 0; k < 3; ++k) {
        px[k] = cv::saturate_cast<uchar>(px[k] * (1.0 + shade(r, c)) + grain);
      }
    }
  }
}

void PastePatch(const cv::Mat3b& patch, const cv::Mat1b& mask, cv::Point top_left,
                cv::Mat3b* image) {
  const cv::Rect target =
      cv::Rect(top_left, patch.size()) & cv::Rect(0, 0, image->cols, image->rows);
  if (target.empty()) return;
  const cv::Rect source(target.tl() - top_left, target.size());
  patch(source).copyTo((*image)(target), mask(source));
}

// A random filled region (rotated rectangle or ellipse) as a mask of `size`.
cv::Mat1b PatchMask(const cv::Size& size, SynthRng* rng) {
  cv::Mat1b mask(size, uchar(0));
  const cv::Point2f centre(0.5f * size.width, 0.5f * size.height);
  const cv::Size2f axes(0.7f * size.width, 0.7f * size.height);
  const float angle = static_cast<float>(rng->Uniform(0.0, 180.0));
  if (rng->Uniform() < 0.6) {
    cv::Point2f corners[4];
    cv::RotatedRect(centre, axes, angle).points(corners);
    std::vector<cv::Point> polygon;
    for (const cv::Point2f& p : corners) polygon.emplace_back(cvRound(p.x), cvRound(p.y));
    cv::fillConvexPoly(mask, polygon, cv::Scalar(255), cv::LINE_8);
  } else {
    cv::ellipse(mask, cv::RotatedRect(centre, axes, angle), cv::Scalar(255), cv::FILLED);
  }
  return mask;
}

}  // namespace

float SrgbToLinear(float value) {
  return value <= 0.04045f ? value / 12.92f : std::pow((value + 0.055f) / 1.055f, 2.4f);
}

Eigen::Vector3f SrgbToLinear(const std::array<double, 3>& rgb_255) {
  return {SrgbToLinear(static_cast<float>(rgb_255[0] / 255.0)),
          SrgbToLinear(static_cast<float>(rgb_255[1] / 255.0)),
          SrgbToLinear(static_cast<float>(rgb_255[2] / 255.0))};
}

cv::Mat3f SrgbImageToLinear(const cv::Mat3b& rgb) {
  float table[256];
  for (int i = 0; i < 256; ++i) table[i] = SrgbToLinear(i / 255.0f);
  cv::Mat3f linear(rgb.size());
  for (int r = 0; r < rgb.rows; ++r) {
    for (int c = 0; c < rgb.cols; ++c) {
      const cv::Vec3b& px = rgb(r, c);
      linear(r, c) = cv::Vec3f(table[px[0]], table[px[1]], table[px[2]]);
    }
  }
  return linear;
}

Eigen::Vector3f Texture::Sample(double x, double y) const {
  const int cols = image_.cols, rows = image_.rows;
  const double fx = std::floor(x), fy = std::floor(y);
  const float wx = static_cast<float>(x - fx), wy = static_cast<float>(y - fy);
  int x0 = static_cast<int>(fx), x1 = x0 + 1, y0 = static_cast<int>(fy), y1 = y0 + 1;
  if (x0 < 0 || x1 >= cols || y0 < 0 || y1 >= rows) {  // outside: mirrored repetition
    x0 = Mirror(x0, cols);
    x1 = Mirror(x1, cols);
    y0 = Mirror(y0, rows);
    y1 = Mirror(y1, rows);
  }
  const cv::Vec3f top = (1.0f - wx) * image_(y0, x0) + wx * image_(y0, x1);
  const cv::Vec3f bottom = (1.0f - wx) * image_(y1, x0) + wx * image_(y1, x1);
  const cv::Vec3f v = (1.0f - wy) * top + wy * bottom;
  return {v[0], v[1], v[2]};
}

cv::Mat3b MakePlainTexture(const cv::Size& size, SynthRng* rng) {
  const Eigen::Vector3d base =
      HsvToRgb(rng->Uniform(), rng->Uniform(0.03, 0.3), rng->Uniform(0.35, 0.85));
  cv::Mat3b image(size,
                  cv::Vec3b(cv::saturate_cast<uchar>(base[0]), cv::saturate_cast<uchar>(base[1]),
                            cv::saturate_cast<uchar>(base[2])));
  // Linear gradient (±20 %) in a random direction plus low-frequency shading (±7 %).
  const double angle = rng->Uniform(0.0, 2.0 * kPi);
  const double slope = rng->Uniform(0.05, 0.2);
  const cv::Mat1f noise = LowFrequencyNoise(size, 6, 5, rng);
  cv::Mat1f shade(size);
  const double diag = std::hypot(size.width, size.height);
  for (int r = 0; r < size.height; ++r) {
    for (int c = 0; c < size.width; ++c) {
      const double u =
          ((c - 0.5 * size.width) * std::cos(angle) + (r - 0.5 * size.height) * std::sin(angle)) /
          diag;
      shade(r, c) = static_cast<float>(2.0 * slope * u + 0.07 * noise(r, c));
    }
  }
  ModulateAndGrain(shade, 1.5, rng, &image);
  return image;
}

cv::Mat3b MakeClutteredTexture(const cv::Size& size, const std::array<double, 3>& object_rgb_255,
                               int shapes, double similar_fraction, SynthRng* rng) {
  cv::Mat3b image = MakePlainTexture(size, rng);
  const double min_side = std::min(size.width, size.height);
  static const char* const kWords[] = {"BCOT", "box",  "42", "Lot 7",  "fragile", "A4",
                                       "kg",   "TEST", "#3", "0.5 mm", "OK",      "up"};
  for (int i = 0; i < shapes; ++i) {
    const Eigen::Vector3d color =
        rng->Uniform() < similar_fraction ? SimilarColor(object_rgb_255, rng) : RandomColor(rng);
    const Eigen::Vector3d color2 = RandomColor(rng);
    const double extent = min_side * std::exp(rng->Uniform(std::log(0.02), std::log(0.3)));
    const cv::Point centre(rng->UniformInt(0, size.width - 1), rng->UniformInt(0, size.height - 1));
    const int kind = rng->UniformInt(0, 9);
    switch (kind) {
      case 0: {  // rotated rectangle
        cv::Point2f corners[4];
        cv::RotatedRect(centre, cv::Size2f(extent, extent * rng->Uniform(0.2, 1.0)),
                        rng->Uniform(0.0, 180.0))
            .points(corners);
        std::vector<cv::Point> polygon;
        for (const cv::Point2f& p : corners) polygon.emplace_back(cvRound(p.x), cvRound(p.y));
        cv::fillConvexPoly(image, polygon, ToScalar(color), cv::LINE_AA);
        break;
      }
      case 1:  // disc
        cv::circle(image, centre, static_cast<int>(0.5 * extent), ToScalar(color), cv::FILLED,
                   cv::LINE_AA);
        break;
      case 2:  // ellipse, filled or outlined
        cv::ellipse(image, centre,
                    cv::Size(static_cast<int>(0.5 * extent),
                             static_cast<int>(0.5 * extent * rng->Uniform(0.2, 1.0))),
                    rng->Uniform(0.0, 180.0), 0.0, 360.0, ToScalar(color),
                    rng->Uniform() < 0.7 ? cv::FILLED : rng->UniformInt(1, 6), cv::LINE_AA);
        break;
      case 3: {  // random star-shaped polygon
        const int n = rng->UniformInt(3, 8);
        std::vector<cv::Point> polygon;
        for (int k = 0; k < n; ++k) {
          const double a = 2.0 * kPi * (k + rng->Uniform(0.0, 0.8)) / n;
          const double radius = 0.5 * extent * rng->Uniform(0.4, 1.0);
          polygon.emplace_back(centre.x + cvRound(radius * std::cos(a)),
                               centre.y + cvRound(radius * std::sin(a)));
        }
        cv::fillPoly(image, std::vector<std::vector<cv::Point>>{polygon}, ToScalar(color),
                     cv::LINE_AA);
        break;
      }
      case 4: {  // strokes
        std::vector<cv::Point> line;
        cv::Point p = centre;
        for (int k = 0; k < rng->UniformInt(2, 6); ++k) {
          line.push_back(p);
          p += cv::Point(cvRound(rng->Uniform(-0.5, 0.5) * extent),
                         cvRound(rng->Uniform(-0.5, 0.5) * extent));
        }
        cv::polylines(image, std::vector<std::vector<cv::Point>>{line}, false, ToScalar(color),
                      rng->UniformInt(1, std::max(2, static_cast<int>(extent / 15))), cv::LINE_AA);
        break;
      }
      case 5:    // stripes
      case 6:    // checker
      case 7:    // gradient
      case 8: {  // coloured noise
        const int side = std::max(4, static_cast<int>(extent));
        const cv::Size patch_size(side,
                                  std::max(4, static_cast<int>(side * rng->Uniform(0.4, 1.0))));
        cv::Mat3b patch(patch_size);
        const double period = rng->Uniform(3.0, 0.25 * side + 4.0);
        const double a = rng->Uniform(0.0, kPi);
        const cv::Mat1f noise =
            LowFrequencyNoise(patch_size, rng->UniformInt(2, 8), rng->UniformInt(2, 8), rng);
        for (int r = 0; r < patch.rows; ++r) {
          for (int c = 0; c < patch.cols; ++c) {
            const double u = c * std::cos(a) + r * std::sin(a);
            const double v = -c * std::sin(a) + r * std::cos(a);
            double w = 0.0;
            if (kind == 5) {
              w = std::fmod(u / period, 1.0) < 0.5 ? 0.0 : 1.0;
            } else if (kind == 6) {
              w = (static_cast<int>(std::floor(u / period)) +
                   static_cast<int>(std::floor(v / period))) %
                          2
                      ? 1.0
                      : 0.0;
            } else if (kind == 7) {
              w = std::clamp(u / (patch.cols + patch.rows), 0.0, 1.0);
            } else {
              w = 0.5 + 0.5 * noise(r, c);
            }
            const Eigen::Vector3d mixed = (1.0 - w) * color + w * color2;
            patch(r, c) =
                cv::Vec3b(cv::saturate_cast<uchar>(mixed[0]), cv::saturate_cast<uchar>(mixed[1]),
                          cv::saturate_cast<uchar>(mixed[2]));
          }
        }
        PastePatch(patch, PatchMask(patch_size, rng),
                   centre - cv::Point(patch_size.width / 2, patch_size.height / 2), &image);
        break;
      }
      default: {  // text
        const char* word = kWords[rng->UniformInt(0, 11)];
        const double scale = std::max(0.4, extent / 60.0);
        cv::putText(image, word, centre, cv::FONT_HERSHEY_SIMPLEX, scale, ToScalar(color),
                    std::max(1, static_cast<int>(scale * 2)), cv::LINE_AA);
        break;
      }
    }
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.6);
  return image;
}

cv::Mat3b MakeTableTexture(const cv::Size& size, SynthRng* rng) {
  const Eigen::Vector3d base =
      HsvToRgb(rng->Uniform(0.05, 0.11), rng->Uniform(0.25, 0.55), rng->Uniform(0.45, 0.75));
  const Eigen::Vector3d dark = base * 0.7;
  const cv::Mat1f warp = LowFrequencyNoise(size, 12, 4, rng);
  const cv::Mat1f tone = LowFrequencyNoise(size, 5, 5, rng);
  const double period = rng->Uniform(30.0, 60.0);
  const int plank = std::max(40, size.height / rng->UniformInt(5, 9));
  cv::Mat3b image(size);
  for (int r = 0; r < size.height; ++r) {
    for (int c = 0; c < size.width; ++c) {
      const double grain = 0.5 + 0.5 * std::sin(2.0 * kPi * (r + 40.0 * warp(r, c)) / period);
      double w = 0.2 * grain * grain + 0.1 * tone(r, c);
      if (r % plank == 0) w = 1.0;  // seam between planks
      const Eigen::Vector3d color = (1.0 - w) * base + w * dark;
      image(r, c) =
          cv::Vec3b(cv::saturate_cast<uchar>(color[0]), cv::saturate_cast<uchar>(color[1]),
                    cv::saturate_cast<uchar>(color[2]));
    }
  }
  const cv::Mat1f zero = cv::Mat1f::zeros(size);
  ModulateAndGrain(zero, 2.0, rng, &image);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.7);
  return image;
}

StatusOr<cv::Mat3b> LoadPhotoTexture(const std::string& path, const cv::Size& size) {
  if (!std::filesystem::exists(path))
    return Status::NotFound(path + ": background image not found");
  const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
  if (bgr.empty()) return Status::InvalidInput(path + ": cannot decode background image");
  const double scale = std::max(static_cast<double>(size.width) / bgr.cols,
                                static_cast<double>(size.height) / bgr.rows);
  const cv::Size scaled(std::max(size.width, cvCeil(bgr.cols * scale)),
                        std::max(size.height, cvCeil(bgr.rows * scale)));
  cv::Mat resized;
  cv::resize(bgr, resized, scaled, 0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_CUBIC);
  const cv::Rect crop((scaled.width - size.width) / 2, (scaled.height - size.height) / 2,
                      size.width, size.height);
  cv::Mat3b rgb;
  cv::cvtColor(resized(crop), rgb, cv::COLOR_BGR2RGB);
  return rgb;
}

double TexturedPlane::Intersect(const Eigen::Vector3d& from,
                                const Eigen::Vector3d& direction) const {
  const double height = (from - origin).dot(normal);
  const double approach = direction.dot(normal);
  if (height <= 0.0 || approach >= -1e-12) return -1.0;
  return -height / approach;
}

Eigen::Vector3f TexturedPlane::Albedo(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d d = point - origin;
  const cv::Mat3f& image = texture.image();
  return texture.Sample(d.dot(u_axis) / texel_mm + 0.5 * (image.cols - 1),
                        d.dot(v_axis) / texel_mm + 0.5 * (image.rows - 1));
}

float SoftLambert(float n_dot_l, float softness) {
  if (n_dot_l >= softness) return n_dot_l;
  if (n_dot_l <= -softness) return 0.0f;
  const float u = n_dot_l + softness;
  return u * u / (4.0f * softness);
}

void TintTexture(const std::array<double, 3>& rgb_255, double fraction, cv::Mat3b* rgb) {
  if (fraction <= 0.0) return;
  const float f = static_cast<float>(fraction);
  for (int r = 0; r < rgb->rows; ++r) {
    for (int c = 0; c < rgb->cols; ++c) {
      cv::Vec3b& px = (*rgb)(r, c);
      for (int k = 0; k < 3; ++k) {
        px[k] = cv::saturate_cast<uchar>((1.0f - f) * px[k] + f * static_cast<float>(rgb_255[k]));
      }
    }
  }
}

float SchlickFresnel(float f0, float cos_theta) {
  const float m = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (1.0f - f0) * m2 * m2 * m;
}

Eigen::Vector3f Shade(const SurfaceMaterial& material, const SceneLight& light,
                      const Eigen::Vector3f& normal, const Eigen::Vector3f& to_viewer) {
  const float n_dot_l = normal.dot(light.to_light);
  Eigen::Vector3f color =
      material.albedo * (light.ambient + light.intensity * SoftLambert(n_dot_l, light.softness));
  if (material.specular > 0.0f && n_dot_l > 0.0f) {
    const Eigen::Vector3f half = (light.to_light + to_viewer).normalized();
    const float n_dot_h = std::max(0.0f, normal.dot(half));
    const float lobe = material.specular * light.intensity * (material.shininess + 8.0f) /
                       (8.0f * static_cast<float>(kPi)) * std::pow(n_dot_h, material.shininess);
    color += Eigen::Vector3f::Constant(lobe);
  }
  return color;
}

cv::Mat3b ApplySensor(const cv::Mat3f& linear_rgb, const SynthOptions::Sensor& sensor,
                      uint64_t noise_key) {
  cv::Mat3f image = linear_rgb;
  if (sensor.blur_sigma_px > 0.0) {
    cv::GaussianBlur(linear_rgb, image, cv::Size(0, 0), sensor.blur_sigma_px, 0.0,
                     cv::BORDER_REFLECT);
  }
  const double inv_gamma = 1.0 / sensor.gamma;
  // 8-bit lookup of the gamma curve at 1/65536 resolution (value is clipped to [0, 1]).
  constexpr int kLevels = 65536;
  std::vector<uchar> encode(kLevels + 1);
  for (int i = 0; i <= kLevels; ++i) {
    encode[i] =
        cv::saturate_cast<uchar>(255.0 * std::pow(static_cast<double>(i) / kLevels, inv_gamma));
  }
  cv::Mat3b out(image.size());
  const bool noisy = sensor.noise_sigma > 0.0 || sensor.shot_noise_gain > 0.0;
  tbb::parallel_for(0, image.rows, [&](int r) {
    for (int c = 0; c < image.cols; ++c) {
      const cv::Vec3f& px = image(r, c);
      cv::Vec3b& o = out(r, c);
      for (int k = 0; k < 3; ++k) {
        double v = std::max(0.0, static_cast<double>(px[k]) * sensor.exposure);
        if (noisy) {
          const double sigma =
              std::sqrt(sensor.noise_sigma * sensor.noise_sigma + sensor.shot_noise_gain * v);
          const uint64_t key =
              noise_key ^ ((static_cast<uint64_t>(r) << 40) + (static_cast<uint64_t>(c) << 4) + k);
          v += sigma * HashNormal(key);
        }
        const int level = static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * kLevels));
        o[2 - k] = encode[level];  // RGB → BGR
      }
    }
  });
  return out;
}

}  // namespace bcot

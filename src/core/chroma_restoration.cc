#include "bcot/core/chroma_restoration.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "bcot/core/violations.h"

namespace bcot {

Status ChromaRestorationOptions::Validate() const {
  std::vector<std::string> violations;
  if (radius_px < 1 || radius_px > 16) violations.push_back("radius_px must be in [1, 16]");
  if (degree < 1 || degree > 4) violations.push_back("degree must be in [1, 4]");
  if (!(ridge_luma_codes2 > 0.0)) violations.push_back("ridge_luma_codes2 must be > 0");
  if (!(misfit_floor_codes2 > 0.0)) violations.push_back("misfit_floor_codes2 must be > 0");
  if (!(isophote_sigma_px >= 0.0 && isophote_sigma_px <= 4.0)) {
    violations.push_back("isophote_sigma_px must be in [0, 4]");
  }
  if (!(hue_slope_codes >= 0.0 && std::isfinite(hue_slope_codes))) {
    violations.push_back("hue_slope_codes must be >= 0 and finite");
  }
  return internal::JoinViolations("chroma restoration", violations);
}

namespace {

constexpr int kMaxDegree = 4;
// Luma features f_k = ((Y − 128) / kLumaScale)^k keep the powers of order one.
constexpr double kLumaScale = 64.0;

// Solves M·a = r for a symmetric positive definite n×n M (n <= kMaxDegree; M's lower triangle
// is read and overwritten by its Cholesky factor).
void CholeskySolve(int n, double m[kMaxDegree][kMaxDegree], const double* r, double* a) {
  for (int j = 0; j < n; ++j) {
    double d = m[j][j];
    for (int k = 0; k < j; ++k) d -= m[j][k] * m[j][k];
    d = std::sqrt(std::max(d, 1e-300));
    m[j][j] = d;
    for (int i = j + 1; i < n; ++i) {
      double v = m[i][j];
      for (int k = 0; k < j; ++k) v -= m[i][k] * m[j][k];
      m[i][j] = v / d;
    }
  }
  double z[kMaxDegree];
  for (int i = 0; i < n; ++i) {
    double v = r[i];
    for (int k = 0; k < i; ++k) v -= m[i][k] * z[k];
    z[i] = v / m[i][i];
  }
  for (int i = n - 1; i >= 0; --i) {
    double v = z[i];
    for (int k = i + 1; k < n; ++k) v -= m[k][i] * a[k];
    a[i] = v / m[i][i];
  }
}

// The mean over each pixel's (2r + 1)² window, the image mirrored at its border.
cv::Mat1f WindowMean(const cv::Mat1f& image, int radius) {
  cv::Mat1f mean;
  cv::boxFilter(image, mean, CV_32F, cv::Size(2 * radius + 1, 2 * radius + 1), cv::Point(-1, -1),
                true, cv::BORDER_REFLECT);
  return mean;
}

cv::Mat1f Product(const cv::Mat1f& a, const cv::Mat1f& b) {
  cv::Mat1f product;
  cv::multiply(a, b, product);
  return product;
}

// `luma` averaged along its isophotes: at each pixel a Gaussian of `sigma` (pixels) along the
// direction across the local gradient, read bilinearly. The direction is the structure tensor's
// (gradients of the luma smoothed by 1 px, the tensor smoothed by 1 px), so that noise does not
// turn it; where the luma is flat any direction serves.
cv::Mat1f AlongIsophotes(const cv::Mat1f& luma, double sigma) {
  constexpr double kTensorSigma = 1.0;
  cv::Mat1f smoothed, gx, gy;
  cv::GaussianBlur(luma, smoothed, cv::Size(), kTensorSigma, kTensorSigma, cv::BORDER_REFLECT);
  cv::Sobel(smoothed, gx, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REFLECT);
  cv::Sobel(smoothed, gy, CV_32F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REFLECT);
  cv::Mat1f jxx = Product(gx, gx), jyy = Product(gy, gy), jxy = Product(gx, gy);
  for (cv::Mat1f* j : {&jxx, &jyy, &jxy}) {
    cv::GaussianBlur(*j, *j, cv::Size(), kTensorSigma, kTensorSigma, cv::BORDER_REFLECT);
  }
  // The tangent (−sin θ, cos θ) of the dominant gradient direction θ = ½·atan2(2·Jxy, Jxx − Jyy).
  cv::Mat1f tangent_x(luma.size()), tangent_y(luma.size());
  for (int y = 0; y < luma.rows; ++y) {
    for (int x = 0; x < luma.cols; ++x) {
      const double theta = 0.5 * std::atan2(2.0 * jxy(y, x), jxx(y, x) - jyy(y, x));
      tangent_x(y, x) = static_cast<float>(-std::sin(theta));
      tangent_y(y, x) = static_cast<float>(std::cos(theta));
    }
  }
  const int reach = static_cast<int>(std::ceil(2.0 * sigma));
  cv::Mat1f sum = cv::Mat1f::zeros(luma.size()), map_x(luma.size()), map_y(luma.size()), sample;
  double weight_sum = 0.0;
  for (int k = -reach; k <= reach; ++k) {
    const double weight = std::exp(-0.5 * (k / sigma) * (k / sigma));
    for (int y = 0; y < luma.rows; ++y) {
      for (int x = 0; x < luma.cols; ++x) {
        map_x(y, x) = static_cast<float>(x + k * tangent_x(y, x));
        map_y(y, x) = static_cast<float>(y + k * tangent_y(y, x));
      }
    }
    cv::remap(luma, sample, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT);
    cv::scaleAdd(sample, weight, sum, sum);
    weight_sum += weight;
  }
  return sum / weight_sum;
}

}  // namespace

cv::Mat3b RestoreSubsampledChroma(const cv::Mat3b& decoded, const ChromaSampling& sampling,
                                  const ChromaRestorationOptions& options) {
  assert(sampling.simulated());
  assert(options.Validate().ok());
  if (!sampling.subsampled() || decoded.empty()) return decoded;
  const int rows = decoded.rows, cols = decoded.cols;
  const int degree = options.degree, radius = options.radius_px;

  // JFIF luma and chroma (without chroma's offset of 128) of the decoded codes.
  cv::Mat1f luma(rows, cols), chroma[2] = {cv::Mat1f(rows, cols), cv::Mat1f(rows, cols)};
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      const cv::Vec3b& p = decoded(y, x);  // B, G, R
      luma(y, x) = static_cast<float>(0.299 * p[2] + 0.587 * p[1] + 0.114 * p[0]);
      chroma[0](y, x) = static_cast<float>(-0.168736 * p[2] - 0.331264 * p[1] + 0.5 * p[0]);
      chroma[1](y, x) = static_cast<float>(0.5 * p[2] - 0.418688 * p[1] - 0.081312 * p[0]);
    }
  }
  // The luma the polynomial reads (header: averaged along the isophotes).
  const cv::Mat1f read_luma = options.isophote_sigma_px > 0.0
                                  ? AlongIsophotes(luma, options.isophote_sigma_px)
                                  : luma;
  // The features f_k at full resolution and passed through the codec's chroma path.
  std::vector<cv::Mat1f> features(degree), paths(degree), path_means(degree);
  for (int k = 0; k < degree; ++k) {
    cv::Mat1d feature(rows, cols);
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) {
        const double t = (read_luma(y, x) - 128.0) / kLumaScale;
        double power = t;
        for (int e = 0; e < k; ++e) power *= t;
        feature(y, x) = power;
      }
    }
    feature.convertTo(features[k], CV_32F);
    ChromaSamplingPath(sampling, &feature);
    feature.convertTo(paths[k], CV_32F);
    path_means[k] = WindowMean(paths[k], radius);
  }
  // Window covariances of the path features (symmetric: the upper triangle is computed).
  std::vector<cv::Mat1f> path_cov(degree * degree);
  for (int i = 0; i < degree; ++i) {
    for (int j = i; j < degree; ++j) {
      path_cov[i * degree + j] =
          WindowMean(Product(paths[i], paths[j]), radius) - Product(path_means[i], path_means[j]);
    }
  }
  const double ridge = options.ridge_luma_codes2 / (kLumaScale * kLumaScale);

  // Per chroma plane: each window's fit, then its misfit-weighted average over the windows
  // holding a pixel, applied to the pixel's own features; and the polynomial's slope dC/dY there.
  cv::Mat1f restored[2], slope[2];
  for (int c = 0; c < 2; ++c) {
    const cv::Mat1f mean_c = WindowMean(chroma[c], radius);
    const cv::Mat1f var_c = WindowMean(Product(chroma[c], chroma[c]), radius) -
                            Product(mean_c, mean_c);
    std::vector<cv::Mat1f> cov_c(degree);
    for (int k = 0; k < degree; ++k) {
      cov_c[k] = WindowMean(Product(paths[k], chroma[c]), radius) - Product(path_means[k], mean_c);
    }
    cv::Mat1f weight(rows, cols), weighted_b(rows, cols);
    std::vector<cv::Mat1f> weighted_a(degree);
    for (int k = 0; k < degree; ++k) weighted_a[k].create(rows, cols);
    double moments[kMaxDegree][kMaxDegree], rhs[kMaxDegree], a[kMaxDegree];
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) {
        for (int i = 0; i < degree; ++i) {
          for (int j = 0; j <= i; ++j) moments[i][j] = path_cov[j * degree + i](y, x);
          moments[i][i] += ridge;
          rhs[i] = cov_c[i](y, x);
        }
        CholeskySolve(degree, moments, rhs, a);
        double b = mean_c(y, x);
        double explained = 0.0;
        for (int k = 0; k < degree; ++k) {
          b -= a[k] * path_means[k](y, x);
          explained += a[k] * rhs[k];
        }
        const double misfit = std::max(0.0, var_c(y, x) - explained);
        const double w = 1.0 / (misfit + options.misfit_floor_codes2);
        weight(y, x) = static_cast<float>(w);
        weighted_b(y, x) = static_cast<float>(w * b);
        for (int k = 0; k < degree; ++k) weighted_a[k](y, x) = static_cast<float>(w * a[k]);
      }
    }
    const cv::Mat1f total = WindowMean(weight, radius);
    const cv::Mat1f b_mean = WindowMean(weighted_b, radius);
    std::vector<cv::Mat1f> a_mean(degree);
    for (int k = 0; k < degree; ++k) a_mean[k] = WindowMean(weighted_a[k], radius);
    restored[c].create(rows, cols);
    slope[c].create(rows, cols);
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) {
        const double t = (read_luma(y, x) - 128.0) / kLumaScale;
        double value = b_mean(y, x), derivative = 0.0, power = 1.0;  // power = t^k
        for (int k = 0; k < degree; ++k) {
          value += a_mean[k](y, x) * features[k](y, x);
          derivative += a_mean[k](y, x) * (k + 1) * power;  // d f_{k+1} / dt = (k + 1)·t^k
          power *= t;
        }
        restored[c](y, x) = static_cast<float>(value / total(y, x));
        slope[c](y, x) = static_cast<float>(derivative / (total(y, x) * kLumaScale));
      }
    }
  }
  // Kept off hue edges (header): the decoded chroma where chroma changes much more than luma.
  if (options.hue_slope_codes > 0.0) {
    const double s0_squared = options.hue_slope_codes * options.hue_slope_codes;
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) {
        const double s_squared =
            slope[0](y, x) * slope[0](y, x) + slope[1](y, x) * slope[1](y, x);
        const double w = s0_squared / (s0_squared + s_squared);
        for (int c = 0; c < 2; ++c) {
          const double blended = w * restored[c](y, x) + (1.0 - w) * chroma[c](y, x);
          restored[c](y, x) = static_cast<float>(blended);
        }
      }
    }
  }
  // Back to BGR codes with the decoded luma (JFIF's inverse matrix).
  cv::Mat3b out(rows, cols);
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      const double l = luma(y, x), cb = restored[0](y, x), cr = restored[1](y, x);
      out(y, x) = cv::Vec3b(cv::saturate_cast<uchar>(l + 1.772 * cb),
                            cv::saturate_cast<uchar>(l - 0.344136 * cb - 0.714136 * cr),
                            cv::saturate_cast<uchar>(l + 1.402 * cr));
    }
  }
  return out;
}

int ChromaRestorationReachPx(const ChromaRestorationOptions& options) {
  // The luma the polynomial reads: with isophote averaging, the direction at the pixel comes from
  // two Gaussians of 1 px (OpenCV's 9-tap kernels, 4 each) and a 3×3 Sobel (1), the walk along
  // it reaches ceil(2σ) and its bilinear read one more.
  const int read_reach =
      options.isophote_sigma_px > 0.0
          ? std::max(4 + 1 + 4, static_cast<int>(std::ceil(2.0 * options.isophote_sigma_px)) + 1)
          : 0;
  // Then the codec's chroma path (a 2-pixel block and the fancy upsampling's reach into the next
  // block, 4 at most), and each window fit and the average over the windows holding a pixel (2r).
  return read_reach + 4 + 2 * options.radius_px;
}

cv::Mat3b RestoreSubsampledChroma(const cv::Mat3b& decoded, const ChromaSampling& sampling,
                                  const ChromaRestorationOptions& options, const cv::Rect& region) {
  const cv::Rect image_rect(0, 0, decoded.cols, decoded.rows);
  const cv::Rect inner = region & image_rect;
  if (!sampling.subsampled() || inner.empty()) return decoded;
  // The crop keeps the codec's block grid: its origin on even coordinates (blocks are at most
  // 2 pixels across and down, ChromaSampling::simulated()).
  const int reach = ChromaRestorationReachPx(options);
  const int x0 = std::max(0, (inner.x - reach) / 2 * 2);
  const int y0 = std::max(0, (inner.y - reach) / 2 * 2);
  const cv::Rect crop =
      cv::Rect(x0, y0, inner.br().x + reach - x0, inner.br().y + reach - y0) & image_rect;
  const cv::Mat3b restored = RestoreSubsampledChroma(decoded(crop).clone(), sampling, options);
  cv::Mat3b out = decoded.clone();
  restored(inner - crop.tl()).copyTo(out(inner));
  return out;
}

}  // namespace bcot

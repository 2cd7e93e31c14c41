#include "bcot/core/chroma_sampling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <vector>

namespace bcot {

std::string ChromaSampling::Name() const {
  if (horizontal == 1 && vertical == 1) return "4:4:4";
  if (horizontal == 2 && vertical == 2) return "4:2:0";
  if (horizontal == 2 && vertical == 1) return "4:2:2";
  if (horizontal == 1 && vertical == 2) return "4:4:0";
  return fmt::format("{}x{}", horizontal, vertical);
}

namespace {

// JFIF's chroma of BGR codes (ITU-R BT.601, full range), without the offset of 128 (which the
// averaging and upsampling carry unchanged).
double Cb(const cv::Vec3d& bgr) { return -0.168736 * bgr[2] - 0.331264 * bgr[1] + 0.5 * bgr[0]; }
double Cr(const cv::Vec3d& bgr) { return 0.5 * bgr[2] - 0.418688 * bgr[1] - 0.081312 * bgr[0]; }

// One line of a chroma plane (`n` values `stride` apart) through the codec along an axis of 2
// pixels per sample, in place: the mean of each pair (pixels 2i, 2i + 1), then libjpeg's fancy
// upsampling, output pixel 2i = 3/4 sample i + 1/4 sample i − 1 and 2i + 1 = 3/4 sample i +
// 1/4 sample i + 1, samples beyond the ends replaced by the end ones. `means` is work space.
void HalveAndUpsample(double* values, int n, int stride, std::vector<double>* means) {
  const int samples = (n + 1) / 2;
  means->resize(samples);
  for (int i = 0; i < samples; ++i) {
    (*means)[i] = 2 * i + 1 < n ? 0.5 * (values[2 * i * stride] + values[(2 * i + 1) * stride])
                                : values[2 * i * stride];
  }
  for (int x = 0; x < n; ++x) {
    const int i = x / 2;
    const int farther = std::clamp(x % 2 == 0 ? i - 1 : i + 1, 0, samples - 1);
    values[x * stride] = 0.75 * (*means)[i] + 0.25 * (*means)[farther];
  }
}

// A chroma plane through the codec: rows, then columns (the averaging and upsampling are
// linear and act on x and y apart).
void ThroughCodec(const ChromaSampling& sampling, cv::Mat1d* plane, std::vector<double>* work) {
  if (sampling.horizontal == 2) {
    for (int y = 0; y < plane->rows; ++y) HalveAndUpsample((*plane)[y], plane->cols, 1, work);
  }
  if (sampling.vertical == 2) {
    const int stride = static_cast<int>(plane->step1());
    for (int x = 0; x < plane->cols; ++x) {
      HalveAndUpsample(plane->ptr<double>(0) + x, plane->rows, stride, work);
    }
  }
}

}  // namespace

cv::Mat3d SimulateChromaSubsampling(const cv::Mat3d& codes, const ChromaSampling& sampling) {
  assert(sampling.simulated());
  cv::Mat1d cb(codes.size()), cr(codes.size());
  for (int y = 0; y < codes.rows; ++y) {
    for (int x = 0; x < codes.cols; ++x) {
      cb(y, x) = Cb(codes(y, x));
      cr(y, x) = Cr(codes(y, x));
    }
  }
  cv::Mat1d cb_out = cb.clone(), cr_out = cr.clone();
  std::vector<double> work;
  ThroughCodec(sampling, &cb_out, &work);
  ThroughCodec(sampling, &cr_out, &work);
  // Luma is kept, so the decoded colour is the input plus the chroma change mapped back to RGB
  // by the inverse of JFIF's matrix.
  cv::Mat3d out(codes.size());
  for (int y = 0; y < codes.rows; ++y) {
    for (int x = 0; x < codes.cols; ++x) {
      const double d_cb = cb_out(y, x) - cb(y, x), d_cr = cr_out(y, x) - cr(y, x);
      const cv::Vec3d& in = codes(y, x);
      const double b = in[0] + 1.772 * d_cb;
      const double g = in[1] - 0.344136 * d_cb - 0.714136 * d_cr;
      const double r = in[2] + 1.402 * d_cr;
      out(y, x) = cv::Vec3d(std::clamp(b, 0.0, 255.0), std::clamp(g, 0.0, 255.0),
                            std::clamp(r, 0.0, 255.0));
    }
  }
  return out;
}

void ChromaSamplingPath(const ChromaSampling& sampling, cv::Mat1d* plane) {
  assert(sampling.simulated());
  std::vector<double> work;
  ThroughCodec(sampling, plane, &work);
}

}  // namespace bcot

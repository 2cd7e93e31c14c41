// How an image file stores colour, and what a JPEG codec's chroma subsampling does to an image.
//
// A JPEG keeps luma (Y) at full resolution and its two chroma planes (Cb, Cr) either at full
// resolution too (4:4:4) or subsampled: 4:2:0 (half resolution across and down, what most
// cameras and codecs write) or 4:2:2 (across only). The encoder averages each block of
// horizontal × vertical pixels' chroma into one sample; libjpeg's decoder brings the samples back
// to full resolution by its "fancy" upsampling (per subsampled axis, 3/4 of the nearer sample and
// 1/4 of the farther one). Luma is untouched, so an edge of colour comes back as a sharp luma
// step and a chroma step blurred over about three pixels whose shape depends on where the edge
// falls in the block grid (which starts at pixel 0, 0). That moves the edges the edge stage
// measures (docs/notes/issue12_jpeg_chroma.md); SimulateChromaSubsampling predicts the move.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace bcot {

struct ChromaSampling {
  // Luma pixels per chroma sample across (horizontal) and down (vertical): 1, 1 for lossless
  // formats, JPEG 4:4:4 and single-channel JPEG; 2, 2 for 4:2:0; 2, 1 for 4:2:2.
  int horizontal = 1;
  int vertical = 1;

  static ChromaSampling Full() { return {1, 1}; }
  static ChromaSampling Jpeg420() { return {2, 2}; }
  static ChromaSampling Jpeg422() { return {2, 1}; }

  bool subsampled() const { return horizontal > 1 || vertical > 1; }
  // Factors of 1 or 2 on each axis: the sampling SimulateChromaSubsampling models (libjpeg
  // decodes other factors without fancy upsampling).
  bool simulated() const {
    return (horizontal == 1 || horizontal == 2) && (vertical == 1 || vertical == 2);
  }
  // "4:4:4", "4:2:0", "4:2:2", "4:4:0", else "<horizontal>x<vertical>".
  std::string Name() const;
  bool operator==(const ChromaSampling& other) const {
    return horizontal == other.horizontal && vertical == other.vertical;
  }
  bool operator!=(const ChromaSampling& other) const { return !(*this == other); }
};

// The BGR codes of `codes` as a JPEG encoder's chroma subsampling (JFIF full-range YCbCr, each
// block's chroma averaged) and libjpeg's decoder (fancy upsampling, back to RGB, clamped to
// [0, 255]) leave them, without quantisation or rounding. `codes` is any patch of an image whose
// pixel (0, 0) lies at a multiple of the factors in that image (so its blocks are the image's);
// beyond its border the patch is continued by its edge blocks, as libjpeg does at an image's.
// `sampling.simulated()` must hold; with 1, 1 the codes come back clamped.
cv::Mat3d SimulateChromaSubsampling(const cv::Mat3d& codes, const ChromaSampling& sampling);

// One plane through the codec's chroma path in place: each block's mean, then libjpeg's fancy
// upsampling back to full resolution (linear; what SimulateChromaSubsampling does to Cb and Cr).
// `plane` is a whole image's or a patch's as for SimulateChromaSubsampling;
// `sampling.simulated()` must hold.
void ChromaSamplingPath(const ChromaSampling& sampling, cv::Mat1d* plane);

}  // namespace bcot

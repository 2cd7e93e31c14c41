// Full-resolution chroma for frames whose codec kept it at a lower resolution, brought back by
// the luma, which the codec keeps at full resolution (docs/notes/issue12_jpeg_chroma.md, "Chroma
// brought back by the luma").
//
// Where a neighbourhood holds the mix of two colours, each pixel's chroma codes are a smooth
// function of its luma codes: in linear light the mix is a line between the two colours, and in
// the sRGB codes JFIF's Y′, Cb, Cr are linear in, that line bends. Within a window of (2r + 1)²
// pixels the restoration models the bend as a polynomial, C(x) = Σ_k a_k·f_k(Y(x)) + b with
// f_k(Y) = ((Y − 128) / 64)^k, k = 1..degree. The codec's chroma path (block means, libjpeg's
// fancy upsampling; ChromaSamplingPath) is linear, so the decoded chroma is the same polynomial of
// the features passed through that path: C_decoded = Σ_k a_k·path(f_k) + b. The a_k, b of every
// window are fitted to the decoded chroma by least squares (a ridge keeps windows whose luma is
// flat at their mean chroma), and each pixel takes the average of the windows that hold it,
// weighted by 1 / (misfit + floor) with misfit the window's mean squared residual, so windows
// whose chroma is no function of luma (three colours, a colour boundary of equal luma) give way to
// those that fit. The pixel's chroma is then that polynomial of its own full-resolution luma.
//
// Two refinements (same note, "The restoration along the isophote, and kept off hue edges"):
// - The luma the polynomial is evaluated at (and fitted with) is first averaged along the local
//   isophote, a Gaussian of isophote_sigma_px along the direction across the luma gradient
//   (structure tensor). Across an edge nothing is averaged, so the restored chroma edge stays as
//   sharp as the luma's; along it the luma noise the polynomial carries into chroma is averaged
//   down (its standard deviation by 1 / sqrt(2·sqrt(π)·σ), 0.53 at σ = 1 px).
// - Where chroma changes much more than luma (|dC/dY|, both planes, codes per code of the
//   polynomial at the pixel's luma), luma says little about where the chroma edge lies and
//   carries its noise into chroma many times over; there the decoded chroma is kept:
//   restored = w·polynomial + (1 − w)·decoded, w = s0² / (s0² + s²), s² = |dC/dY|² summed over
//   Cb and Cr (one weight for both, so that the colour's hue is not split between the two
//   sources), s0 = hue_slope_codes.
//
// On 4:2:0 renders of a saturated object it removes most of the chroma blur that moves an edge
// measured in colour (issue 12's vertical bias). Its own error is the polynomial's fit of the
// sRGB bend, about a code, which it adds where the decoded chroma was right already (an edge
// along the rows at 4:2:2). It is not free of bias: on clean oblique edges between two saturated
// colours, which the decoded frame puts 0.09–0.14 px outside, the edge stage finds the restored
// edge 0.08–0.13 px inside, where the per-line correction (edge_lines.h) is within 0.04 px
// (EdgeImageOfTest prints all three; the cause is not found: a much smaller ridge takes the
// polynomial's own shortfall at the edge's centre out but moves these edges little). Where two
// colours of about equal luma meet (hue edges), luma noise is amplified into chroma; the blend
// above keeps most of that out. The edge stage applies it to its last round only, around the
// object (EdgeRefineOptions::chroma_restoration), and it is off by default
// (docs/notes/issue12_jpeg_chroma.md, "Chroma brought back by the luma" and the sections after).
#pragma once

#include <opencv2/core.hpp>

#include "bcot/core/chroma_sampling.h"
#include "bcot/core/status.h"

namespace bcot {

struct ChromaRestorationOptions {
  // Off by default: it removes most of 4:2:0's vertical bias on a saturated plastic object but
  // costs rotation on small objects (issue12_jpeg_chroma.md).
  bool enabled = false;
  // Window radius r, pixels: a window of (2r + 1)² pixels spans the codec's blur of an edge (the
  // block plus the upsampling's reach: ±2 pixels at 4:2:0) with room for both colours.
  int radius_px = 3;
  // Polynomial degree in luma: 1 is a straight colour line in the codes; the sRGB curve bends the
  // line between a saturated and a grey colour by up to 6 codes, 3 brings that under about 1.3.
  int degree = 3;
  // Ridge on the polynomial's coefficients, in luma codes² (a window whose luma varies by less
  // keeps its mean chroma). It also shrinks the bend of a strong edge's colour curve; smaller
  // values halve a saturated object's depth bias and cost noisy small objects rotation
  // (issue12_jpeg_chroma.md, "The restoration moved into the edge stage").
  double ridge_luma_codes2 = 4.0;
  // Floor of a window's misfit (mean squared chroma residual, codes²) in its weight.
  double misfit_floor_codes2 = 0.1;
  // σ of the Gaussian along the isophote the luma is averaged with before the polynomial reads
  // it, pixels; 0 reads each pixel's own luma.
  double isophote_sigma_px = 1.0;
  // s0 of the blend with the decoded chroma (header): the chroma change per luma change, codes
  // per code, at which restored and decoded chroma weigh the same; 0 keeps the restored chroma
  // everywhere.
  double hue_slope_codes = 2.0;

  Status Validate() const;
};

// `decoded` (BGR codes) with its chroma restored as the header describes; `sampling` is how the
// file stored chroma (sampling.simulated() must hold; with 1, 1 the image is returned as is).
// Luma is kept: each pixel's JFIF Y′ of the result equals the decoded one up to rounding and
// clamping.
cv::Mat3b RestoreSubsampledChroma(const cv::Mat3b& decoded, const ChromaSampling& sampling,
                                  const ChromaRestorationOptions& options);

// As above, but only the pixels of `region` (clipped to the image) restored, the others kept as
// decoded; the work is that of a crop of `region` grown by ChromaRestorationReachPx(options) on
// each side, and the restored pixels equal those of the whole image's restoration (up to a code
// of float rounding).
cv::Mat3b RestoreSubsampledChroma(const cv::Mat3b& decoded, const ChromaSampling& sampling,
                                  const ChromaRestorationOptions& options, const cv::Rect& region);

// How far (pixels) a restored pixel reads the decoded image: the fit windows and their average
// (2r), the codec's chroma path (a block and the upsampling's reach), the isophote averaging (the
// structure tensor's smoothing and the Gaussian along the isophote).
int ChromaRestorationReachPx(const ChromaRestorationOptions& options);

}  // namespace bcot

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
// On a two-colour edge this removes most of the chroma blur that moves an edge measured in colour
// (issue 12's vertical bias on 4:2:0 JPEG renders of a saturated object). Its own error is the
// polynomial's fit of the sRGB bend, about a code, which it adds where the decoded chroma was
// right already (an edge along the rows at 4:2:2). Where two colours of about equal luma meet
// (hue edges), luma noise is amplified into chroma: on small objects with such edges it costs
// rotation, so it is off by default (docs/notes/issue12_jpeg_chroma.md, "Chroma brought back by
// the luma").
#pragma once

#include <opencv2/core.hpp>

#include "bcot/core/chroma_sampling.h"
#include "bcot/core/status.h"

namespace bcot {

struct ChromaRestorationOptions {
  // Off by default: it removes most of 4:2:0's vertical bias on a saturated plastic object but
  // costs rotation on small objects whose edges are mostly hue (issue12_jpeg_chroma.md).
  bool enabled = false;
  // Window radius r, pixels: a window of (2r + 1)² pixels spans the codec's blur of an edge (the
  // block plus the upsampling's reach: ±2 pixels at 4:2:0) with room for both colours.
  int radius_px = 3;
  // Polynomial degree in luma: 1 is a straight colour line in the codes; the sRGB curve bends the
  // line between a saturated and a grey colour by up to 6 codes, 3 brings that under about 1.3.
  int degree = 3;
  // Ridge on the polynomial's coefficients, in luma codes² (a window whose luma varies by less
  // keeps its mean chroma).
  double ridge_luma_codes2 = 4.0;
  // Floor of a window's misfit (mean squared chroma residual, codes²) in its weight.
  double misfit_floor_codes2 = 0.1;

  Status Validate() const;
};

// `decoded` (BGR codes) with its chroma restored as the header describes; `sampling` is how the
// file stored chroma (sampling.simulated() must hold; with 1, 1 the image is returned as is).
// Luma is kept: each pixel's JFIF Y′ of the result equals the decoded one up to rounding and
// clamping.
cv::Mat3b RestoreSubsampledChroma(const cv::Mat3b& decoded, const ChromaSampling& sampling,
                                  const ChromaRestorationOptions& options);

}  // namespace bcot

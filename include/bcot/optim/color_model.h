// Per-view colour models: foreground/background RGB histograms that give every pixel the
// posteriors P_f(x), P_b(x) of the region energy (DESIGN.md "Region energy", eq. 5–6, and
// "Colour model"; paper §3.2 after RBOT).
//
// Posteriors. With h_f, h_b the normalised histograms (likelihoods p(y | foreground),
// p(y | background), each summing to 1) and y the pixel's colour bin:
//
//   P_f(y) = h_f(y) / (h_f(y) + h_b(y)),   P_b(y) = 1 − P_f(y),   both ½ when h_f = h_b = 0.
//
// This is RBOT's P_f = h_f / (η_f h_f + η_b h_b) with equal priors η_f = η_b = ½, rescaled so
// that P_f + P_b = 1. We choose the normalised form on purpose: the region energy
// F = −log(He·P_f + (1 − He)·P_b) only depends on the ratio h_f/h_b through its pose
// gradient, but its value enters the Gauss-Newton weights of both residual forms (√(2F) needs
// F ≥ 0, the IRLS form weighs by 1/F). Normalised posteriors keep He·P_f + (1 − He)·P_b in
// [0, 1], so F ≥ 0 and its scale does not depend on how large the sampled areas were.
//
// Temporal blending. The first Update sets the histograms, every later one blends
// h ← (1 − α)·h + α·h_new with α = learning_rate_foreground / _background (RBOT: 0.1 / 0.2).
//
// Two kinds (ColorModelOptions::kind):
//   global: one histogram pair per view. Foreground samples are the pixels inside the
//           rendered silhouette, background samples the pixels outside it within
//           background_band_px of it.
//   local:  RBOT's temporally consistent local colour histograms (tclc). Circular regions of
//           radius local_region_radius_px centred on contour points (one every
//           local_region_spacing_px along the contour), each with its own histogram pair
//           learned from the pixels inside it (mask → foreground, else background). A region
//           is anchored to the model point (O_t) of the contour point that created it; a
//           later contour point reuses the region with the nearest anchor within
//           local_anchor_fraction × object diameter, so the same part of the object finds its
//           own histograms again in later frames (temporal consistency). A pixel's
//           posterior is the average of P_f over the regions of the last Update covering it;
//           pixels no region covers fall back to a global model kept alongside.
//           A region's foreground histogram describes its part of the object and follows the
//           anchor. Its background histogram describes what lies behind that part in the
//           image, which changes when the part moves across the image (a turning object).
//           With local_background_memory = image, the old background histogram keeps the
//           weight (1 − α_b)·o, where o is the overlap of the region's disc now and at its
//           last update, as a share of the disc's area (docs/method.md, colour models):
//             o(d) = (2/π)·(acos(u) − u·√(1 − u²)),  u = d / (2·radius),  0 for d ≥ 2·radius.
//           A region where it was last time blends as RBOT's; one that moved by a diameter
//           or more forgets the old background. With `object`, every region blends with
//           α_b wherever it moved, as in RBOT.
//           Memory: 2·bins³ floats per region ever seen (256 KiB at 32 bins).
//
// Image: 8-bit, 3 channels, any channel order as long as it is the same in Update and
// ForegroundPosteriors. Thread safety: const methods may run concurrently; Update may not.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "bcot/core/status.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/sparse_viewpoint_model.h"

namespace bcot {

enum class ColorModelKind { kGlobal, kLocal };

// What a local region's background histogram remembers of earlier frames (see above).
enum class LocalBackgroundMemory {
  kImage,   // the share of the old histogram is scaled by the overlap of the region's discs
  kObject,  // RBOT: blended with learning_rate_background wherever the region moved
};

struct ColorModelOptions {
  ColorModelKind kind = ColorModelKind::kGlobal;
  // Kind of the model the full-resolution (level 0) rounds read their posteriors from; the
  // coarse pyramid levels, which bring the pose into the capture range, use `kind`. Unset
  // ("same") = one model of `kind` for everything. Both models learn from every frame.
  // Rationale: the global model has the wider capture range, the local one (learned along
  // the contour) separates the object from similar clutter elsewhere in the image and so
  // places the final contour more precisely (DESIGN.md "Colour model"). Measured with
  // scripts/bench_precision.sh (90° binocular, 960×768, 4 objects, annotation setting): mean
  // rotation error 0.103° → 0.064°, translation 0.069/0.045/0.036 → 0.029/0.036/0.033 mm;
  // real BCOT Cat (scripts/bench_real_bcot.sh): 5°5cm 83.3 → 90.0 %. Costs ~1.6× the time.
  std::optional<ColorModelKind> refine_kind = ColorModelKind::kLocal;
  // Histogram bins per RGB channel; must divide 256 (1, 2, 4, ..., 256). bins³ bins in all.
  int bins_per_channel = 32;
  // Temporal blending weights of new histograms, in (0, 1]; 1 = forget the past.
  double learning_rate_foreground = 0.1;
  double learning_rate_background = 0.2;
  // Global model (and the local model's fallback): background samples are pixels outside the
  // silhouette within this distance (px) of it; > 0.
  int background_band_px = 40;
  // Both models: pixels within this distance (px) of the silhouette boundary are not sampled
  // on either side, so mixed (anti-aliased, blurred) edge pixels and
  // a pose a few pixels off do not teach one side the other's colours; >= 0.
  double sample_margin_px = 2.0;
  // Local model: radius (px) of the circular regions; > 0.
  double local_region_radius_px = 40.0;
  // Local model: arc-length spacing (px) of region centres along the contour; > 0.
  double local_region_spacing_px = 20.0;
  // Local model: a contour point reuses the region whose anchor model point is within this
  // fraction of the object diameter (nearest first), else it creates one; in (0, 1].
  double local_anchor_fraction = 0.05;
  // Local model: what a region's background histogram remembers. `image` keeps a turning
  // object's regions from taking a same-coloured object they move next to for the object
  // (docs/notes/issue12_small_objects.md: diffuse small bunny 0.998° → 0.512°, 2 → 0 lost).
  LocalBackgroundMemory local_background_memory = LocalBackgroundMemory::kImage;

  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// A normalised foreground/background histogram pair with temporal blending.
class ColorHistograms {
 public:
  explicit ColorHistograms(int bins_per_channel);

  int Bin(const cv::Vec3b& color) const;
  // Builds normalised histograms from the given sample bins and sets (first call) or blends
  // them in. A side without samples keeps its previous histogram. Returns false (no change)
  // when both sides are empty.
  bool Update(const std::vector<int>& foreground_bins, const std::vector<int>& background_bins,
              double learning_rate_foreground, double learning_rate_background);
  // P_f for a bin (½ when never seen by either side or before the first Update).
  double ForegroundPosterior(int bin) const;
  // True when both sides have been learned at least once.
  bool initialized() const { return foreground_initialized_ && background_initialized_; }
  const std::vector<float>& foreground() const { return foreground_; }
  const std::vector<float>& background() const { return background_; }

 private:
  int bins_per_channel_;
  int bin_width_;
  // log2 of bins_per_channel_ and bin_width_ (both powers of two): Bin shifts, not divides.
  int bins_shift_;
  int width_shift_;
  std::vector<float> foreground_;
  std::vector<float> background_;
  bool foreground_initialized_ = false;
  bool background_initialized_ = false;
};

class ColorModel {
 public:
  virtual ~ColorModel() = default;
  // Learns from `image` (camera size) with the object at `silhouette` (mask and contour of
  // the same view). Sets the histograms on the first call, blends afterwards.
  virtual void Update(const cv::Mat3b& image, const Silhouette& silhouette) = 0;
  // Learns from `image` without a silhouette: along the normals of `contour`, the object's
  // contour at its pose with the extents of the silhouette on either side (a sparse viewpoint
  // model's points projected into the view; see internal::SampleContourLines for which pixels).
  // Sets or blends like Update. An empty contour changes nothing but a local model's active
  // regions (none).
  virtual void UpdateAlongContour(const cv::Mat3b& image,
                                  const std::vector<ProjectedContourPoint>& contour) = 0;
  // P_f at each pixel (integer coordinates inside the image; CHECKed). P_b = 1 − P_f.
  virtual std::vector<double> ForegroundPosteriors(
      const cv::Mat3b& image, const std::vector<Eigen::Vector2i>& pixels) const = 0;
  // True once an Update saw both foreground and background samples.
  virtual bool initialized() const = 0;
  // True when Update reads the silhouette's contour; false when the mask is all it needs (the
  // caller may then pass a silhouette without contour, see RenderSilhouetteMask).
  virtual bool UsesContour() const = 0;
};

namespace internal {
class BoundaryDistances;  // color_model.cc

// The samples of UpdateAlongContour, line by line: codes 2·bin + 1 (foreground) or 2·bin
// (background). Line i's inside samples are codes [line_begin[i], line_outside[i]), at distances
// t = first_t, first_t + 1, ... from its contour point along −normal; its outside samples are
// [line_outside[i], line_begin[i + 1]), at the same distances along +normal.
struct ContourLineSamples {
  std::vector<Eigen::Vector2d> line_pixels;   // each line's contour point
  std::vector<Eigen::Vector2d> line_normals;  // its outward normal, unit
  std::vector<int> line_begin;                // one more than lines: the last is codes.size()
  std::vector<int> line_outside;
  int first_t = 1;
  std::vector<int> codes;
};

// The lines are `contour`'s points, with lines interpolated between neighbours on the same
// contour so that they are at most 0.5 px apart (sparser lines leave colours of a noisy
// background unseen, where P_f is ½). Along each line's outward normal n,
// one sample per pixel step at distances
// t = ⌊sample_margin_px⌋ + 1, + 2, ... from the contour point p: the pixel nearest p − t·n is
// foreground while t ≤ min(inside − sample_margin_px, background_band_px), the pixel nearest
// p + t·n background while t ≤ min(outside − sample_margin_px, background_band_px), each side
// stopping at the image's border. As on a silhouette, no pixel within the margin of the boundary
// is sampled, nor one beyond the band; unlike it, the interior deeper than the band is not
// sampled (M3T learns its histograms from its correspondence lines alike), and a pixel two lines
// reach is sampled twice. `binner` gives the bins (every histogram of a model bins alike).
ContourLineSamples SampleContourLines(const cv::Mat3b& image,
                                      const std::vector<ProjectedContourPoint>& contour,
                                      const ColorModelOptions& options,
                                      const ColorHistograms& binner);
}  // namespace internal

class GlobalColorModel final : public ColorModel {
 public:
  // `options` must be valid (CHECKed).
  explicit GlobalColorModel(const ColorModelOptions& options);
  void Update(const cv::Mat3b& image, const Silhouette& silhouette) override;
  void UpdateAlongContour(const cv::Mat3b& image,
                          const std::vector<ProjectedContourPoint>& contour) override;
  std::vector<double> ForegroundPosteriors(
      const cv::Mat3b& image, const std::vector<Eigen::Vector2i>& pixels) const override;
  bool initialized() const override { return histograms_.initialized(); }
  bool UsesContour() const override { return false; }
  const ColorHistograms& histograms() const { return histograms_; }

 private:
  friend class LocalColorModel;
  // Update from boundary distances of a (non-empty) mask the caller computed on a box grown by
  // at least background_band_px + 1, and the box's samples (internal::SampleCodes; the local
  // model shares its own).
  void Update(const internal::BoundaryDistances& distances, const cv::Mat1i& codes);
  // Update from the samples of SampleContourLines (binned like histograms_).
  void Update(const internal::ContourLineSamples& samples);

  ColorModelOptions options_;
  ColorHistograms histograms_;
};

class LocalColorModel final : public ColorModel {
 public:
  // `options` must be valid (CHECKed); `object_diameter_mm` > 0 scales the anchor radius.
  LocalColorModel(const ColorModelOptions& options, double object_diameter_mm);
  void Update(const cv::Mat3b& image, const Silhouette& silhouette) override;
  // The regions are centred on contour points at least local_region_spacing_px from every
  // earlier centre (in the contour's order; along a smooth contour about the arc-length spacing
  // of Update) and learn, as in Update, from the samples within their disc.
  void UpdateAlongContour(const cv::Mat3b& image,
                          const std::vector<ProjectedContourPoint>& contour) override;
  std::vector<double> ForegroundPosteriors(
      const cv::Mat3b& image, const std::vector<Eigen::Vector2i>& pixels) const override;
  bool initialized() const override { return fallback_.initialized(); }
  bool UsesContour() const override { return true; }
  // The global model kept alongside (the posteriors of pixels no region covers).
  const GlobalColorModel& fallback() const { return fallback_; }

  // Regions of the last Update (centre in the image) and the number ever learned.
  struct ActiveRegion {
    Eigen::Vector2d centre;  // image position (the contour point)
    int region = 0;          // index into the learned regions
  };
  const std::vector<ActiveRegion>& active_regions() const { return active_; }
  int num_regions() const { return static_cast<int>(regions_.size()); }
  // The histograms of learned region `region` (ActiveRegion::region; CHECKed).
  const ColorHistograms& region_histograms(int region) const;

 private:
  struct Region {
    Eigen::Vector3d anchor_in_template;
    ColorHistograms histograms;
    Eigen::Vector2d last_centre;  // image position at the region's last update
  };

  // Which active regions' discs can reach a pixel: a grid of square cells over the active
  // discs' bounding box, each cell listing, in increasing order, the indices into active_ of
  // the discs that reach one of its pixels. ForegroundPosteriors then tests a pixel against a
  // handful of discs instead of all of them, in the same order (the same sums).
  struct CoverGrid {
    static constexpr int kCellPx = 16;
    Eigen::Vector2i origin = Eigen::Vector2i::Zero();  // first pixel of cell (0, 0)
    int cols = 0;
    int rows = 0;
    std::vector<std::vector<int>> cells;  // row-major
    // The list of the cell holding `pixel`; null outside the grid.
    const std::vector<int>* Cell(const Eigen::Vector2i& pixel) const;
  };
  // cover_ for active_ (after each Update).
  void BuildCoverGrid();
  // The learned region whose anchor is nearest `point_in_object` within anchor_radius_mm_, or −1.
  int NearestRegion(const Eigen::Vector3d& point_in_object) const;
  // Appends a region anchored at `anchor_in_template`, last seen at `centre`; its index.
  int NewRegion(const Eigen::Vector3d& anchor_in_template, const Eigen::Vector2d& centre);
  // Blends region `region`'s histograms with its samples at `centre`, the background's rate
  // following local_background_memory.
  void LearnRegion(int region, const Eigen::Vector2d& centre, const std::vector<int>& foreground,
                   const std::vector<int>& background);

  ColorModelOptions options_;
  double anchor_radius_mm_;
  GlobalColorModel fallback_;
  std::vector<Region> regions_;
  std::vector<ActiveRegion> active_;
  CoverGrid cover_;
};

// Area shared by two discs of `radius` (> 0) whose centres are `distance` (>= 0) apart, as a
// share of one disc's area: 1 at distance 0, 0 from 2·radius on.
double DiscOverlapFraction(double distance, double radius);

// The options of the refinement model: `options` with kind = refine_kind (unset: unchanged).
ColorModelOptions RefineColorModelOptions(const ColorModelOptions& options);

// The model `options.kind` asks for. `options` must be valid (CHECKed).
std::unique_ptr<ColorModel> MakeColorModel(const ColorModelOptions& options,
                                           double object_diameter_mm);

// The colour models of one view: the model of the coarse levels (`options.kind`) and, when
// `options.refine_kind` differs, the one of the full-resolution rounds
// (RefineColorModelOptions). Both learn from every Update. A global coarse model with a local
// refinement is the local model's own fallback (LocalColorModel::fallback(): the same options
// but the kind, so the same histograms), so one update and one set of boundary distances
// serve both.
class ViewColorModels {
 public:
  // `options` must be valid (CHECKed); `object_diameter_mm` as for LocalColorModel.
  ViewColorModels(const ColorModelOptions& options, double object_diameter_mm);

  void Update(const cv::Mat3b& image, const Silhouette& silhouette);
  void UpdateAlongContour(const cv::Mat3b& image,
                          const std::vector<ProjectedContourPoint>& contour);
  const ColorModel& coarse() const { return *coarse_; }
  // Null when the full-resolution rounds read the coarse model.
  const ColorModel* refine() const { return refine_.get(); }
  // True when Update needs the silhouette's contour (see ColorModel::UsesContour).
  bool UsesContour() const;

 private:
  std::unique_ptr<ColorModel> own_coarse_;  // null when the coarse model is refine_'s fallback
  std::unique_ptr<ColorModel> refine_;
  const ColorModel* coarse_ = nullptr;  // own_coarse_ or refine_'s fallback (both on the heap)
};

}  // namespace bcot

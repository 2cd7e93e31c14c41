#include "bcot/optim/color_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "bcot/core/se3.h"
#include "bcot/core/violations.h"

namespace bcot {

Status ColorModelOptions::Validate() const {
  std::vector<std::string> violations;
  if (kind != ColorModelKind::kGlobal && kind != ColorModelKind::kLocal) {
    violations.push_back(fmt::format("kind = {}, must be global or local", static_cast<int>(kind)));
  }
  if (refine_kind.has_value() && *refine_kind != ColorModelKind::kGlobal &&
      *refine_kind != ColorModelKind::kLocal) {
    violations.push_back(fmt::format("refine_kind = {}, must be same, global or local",
                                     static_cast<int>(*refine_kind)));
  }
  if (local_background_memory != LocalBackgroundMemory::kImage &&
      local_background_memory != LocalBackgroundMemory::kObject) {
    violations.push_back(fmt::format("local_background_memory = {}, must be image or object",
                                     static_cast<int>(local_background_memory)));
  }
  if (bins_per_channel < 1 || bins_per_channel > 256 || 256 % bins_per_channel != 0) {
    violations.push_back(fmt::format("bins_per_channel = {}, must divide 256 (1, 2, 4, ..., 256)",
                                     bins_per_channel));
  }
  if (!(learning_rate_foreground > 0.0 && learning_rate_foreground <= 1.0)) {
    violations.push_back(
        fmt::format("learning_rate_foreground = {}, must be in (0, 1]", learning_rate_foreground));
  }
  if (!(learning_rate_background > 0.0 && learning_rate_background <= 1.0)) {
    violations.push_back(
        fmt::format("learning_rate_background = {}, must be in (0, 1]", learning_rate_background));
  }
  if (background_band_px <= 0) {
    violations.push_back(fmt::format("background_band_px = {}, must be > 0", background_band_px));
  }
  if (!(sample_margin_px >= 0.0) || !std::isfinite(sample_margin_px)) {
    violations.push_back(
        fmt::format("sample_margin_px = {}, must be finite and >= 0", sample_margin_px));
  }
  if (!(local_region_radius_px > 0.0) || !std::isfinite(local_region_radius_px)) {
    violations.push_back(
        fmt::format("local_region_radius_px = {}, must be finite and > 0", local_region_radius_px));
  }
  if (!(local_region_spacing_px > 0.0) || !std::isfinite(local_region_spacing_px)) {
    violations.push_back(fmt::format("local_region_spacing_px = {}, must be finite and > 0",
                                     local_region_spacing_px));
  }
  if (!(local_anchor_fraction > 0.0 && local_anchor_fraction <= 1.0)) {
    violations.push_back(
        fmt::format("local_anchor_fraction = {}, must be in (0, 1]", local_anchor_fraction));
  }
  return internal::JoinViolations("color_model", violations);
}

// ---------------------------------------------------------------------------------------------
// ColorHistograms

ColorHistograms::ColorHistograms(int bins_per_channel)
    : bins_per_channel_(bins_per_channel),
      bin_width_(256 / bins_per_channel),
      bins_shift_(0),
      width_shift_(0) {
  BCOT_CHECK(bins_per_channel >= 1 && bins_per_channel <= 256 && 256 % bins_per_channel == 0);
  while ((1 << bins_shift_) < bins_per_channel_) ++bins_shift_;
  while ((1 << width_shift_) < bin_width_) ++width_shift_;
  const size_t size = static_cast<size_t>(bins_per_channel) * bins_per_channel * bins_per_channel;
  foreground_.assign(size, 0.0f);
  background_.assign(size, 0.0f);
}

int ColorHistograms::Bin(const cv::Vec3b& color) const {
  return ((color[0] >> width_shift_) << (2 * bins_shift_)) |
         ((color[1] >> width_shift_) << bins_shift_) | (color[2] >> width_shift_);
}

namespace {

// Sets (first time) or blends the normalised histogram of `bins` into `histogram`.
void BlendHistogram(const std::vector<int>& bins, double learning_rate, bool* initialized,
                    std::vector<float>* histogram) {
  if (bins.empty()) return;
  const float rate = *initialized ? static_cast<float>(learning_rate) : 1.0f;
  const float keep = 1.0f - rate;
  const float weight = rate / static_cast<float>(bins.size());
  for (float& value : *histogram) value *= keep;
  for (int bin : bins) (*histogram)[bin] += weight;
  *initialized = true;
}

}  // namespace

bool ColorHistograms::Update(const std::vector<int>& foreground_bins,
                             const std::vector<int>& background_bins,
                             double learning_rate_foreground, double learning_rate_background) {
  if (foreground_bins.empty() && background_bins.empty()) return false;
  BlendHistogram(foreground_bins, learning_rate_foreground, &foreground_initialized_, &foreground_);
  BlendHistogram(background_bins, learning_rate_background, &background_initialized_, &background_);
  return true;
}

double ColorHistograms::ForegroundPosterior(int bin) const {
  const double f = foreground_[bin];
  const double b = background_[bin];
  const double sum = f + b;
  return sum > 0.0 ? f / sum : 0.5;
}

// ---------------------------------------------------------------------------------------------
// BoundaryDistances

namespace internal {

// Where each pixel of `box()` lies against the silhouette boundary: whether it is within
// margin_px of the other side (of an inside pixel, the nearest outside one; of an outside pixel,
// the nearest inside one), and of an outside pixel its distance to the nearest inside one. box()
// is the mask's bounding box grown by grow_px (>= 1) and clipped to the image; the results are
// those of the whole image (every inside pixel is in the box, and the box's ring of outside
// pixels is nearer to any inside pixel than anything beyond it), at the cost of the box only.
// The inside test is an erosion by the disc of pixel offsets within margin_px (the same
// squared-integer distances an exact transform compares), so only the outside needs a distance
// transform.
class BoundaryDistances {
 public:
  BoundaryDistances(const cv::Mat1b& mask, int grow_px, double margin_px) : margin_(margin_px) {
    BCOT_CHECK(grow_px >= 1 && margin_px >= 0.0);
    const cv::Rect bounds = cv::boundingRect(mask);
    box_ = cv::Rect(bounds.x - grow_px, bounds.y - grow_px, bounds.width + 2 * grow_px,
                    bounds.height + 2 * grow_px) &
           cv::Rect(0, 0, mask.cols, mask.rows);
    const cv::Mat1b inside = mask(box_);
    // distanceTransform: distance of every non-zero pixel to the nearest zero one.
    cv::distanceTransform(inside == 0, to_inside_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    const int reach = static_cast<int>(std::floor(margin_px));
    cv::Mat1b disc(2 * reach + 1, 2 * reach + 1, static_cast<unsigned char>(0));
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        if (std::sqrt(static_cast<float>(dx * dx + dy * dy)) <= margin_) {
          disc(dy + reach, dx + reach) = 1;
        }
      }
    }
    // Beyond the image every pixel counts as inside, as the distance transform takes it.
    cv::erode(inside, clear_inside_, disc, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT,
              cv::Scalar(255));
  }

  const cv::Rect& box() const { return box_; }

  // (x, y) in image coordinates inside box(); `inside`: the mask's value there.
  bool NearOtherSide(int x, int y, bool inside) const {
    return inside ? clear_inside_(y - box_.y, x - box_.x) == 0 : ToInside(x, y) <= margin_;
  }
  // (x, y) an outside pixel of box().
  float ToInside(int x, int y) const { return to_inside_(y - box_.y, x - box_.x); }

 private:
  cv::Rect box_;
  float margin_;
  cv::Mat1b clear_inside_;  // non-zero: an inside pixel farther than the margin from outside
  cv::Mat1f to_inside_;
};

// Every pixel of `distances.box()` as a sample: 2·bin + 1 inside the mask, 2·bin outside, −1
// within the margin of the other side (not sampled). Read once per pixel here, however many of
// the local model's overlapping discs hold it.
cv::Mat1i SampleCodes(const cv::Mat3b& image, const cv::Mat1b& mask,
                      const BoundaryDistances& distances, const ColorHistograms& binner) {
  const cv::Rect& box = distances.box();
  cv::Mat1i codes(box.size());
  for (int y = box.y; y < box.y + box.height; ++y) {
    const cv::Vec3b* colors = image.ptr<cv::Vec3b>(y);
    const unsigned char* inside = mask.ptr<unsigned char>(y);
    int* code = codes.ptr<int>(y - box.y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      const bool is_inside = inside[x] != 0;
      code[x - box.x] = distances.NearOtherSide(x, y, is_inside)
                            ? -1
                            : (binner.Bin(colors[x]) << 1) | static_cast<int>(is_inside);
    }
  }
  return codes;
}

namespace {

// Most distance between neighbouring lines after DensifyContourLines (px).
constexpr double kLineSpacingPx = 0.5;

// `contour` with lines added between neighbours so that consecutive lines are at most
// kLineSpacingPx apart: between points i and i + 1 whose distance g is larger than that and at
// most twice the median distance of neighbours (so on the same contour: the points are evenly
// spaced along each contour, and a jump to the next contour is longer) and whose normals differ
// by less than 60°, ⌈g / kLineSpacingPx⌉ − 1 lines at even steps, pixel and normal interpolated,
// the extents those of the nearer of the two. (The smaller of the two extents cuts the lines
// beside a concavity short and leaves its background unseen: on the spool scene of
// color_model_test.cc the local model's mean P_f 4–30 px outside was 0.09 with it, 0.027 with
// the nearer one's; lines 1 px apart: 0.048.)
std::vector<ProjectedContourPoint> DensifyContourLines(
    const std::vector<ProjectedContourPoint>& contour) {
  if (contour.size() < 3) return contour;
  std::vector<double> gaps;
  for (size_t i = 0; i + 1 < contour.size(); ++i) {
    gaps.push_back((contour[i + 1].pixel - contour[i].pixel).norm());
  }
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double max_gap = 2.0 * sorted[sorted.size() / 2];
  std::vector<ProjectedContourPoint> dense;
  dense.reserve(contour.size() * static_cast<size_t>(std::max(1.0, std::ceil(max_gap))));
  for (size_t i = 0; i < contour.size(); ++i) {
    dense.push_back(contour[i]);
    if (i + 1 == contour.size()) break;
    const ProjectedContourPoint& a = contour[i];
    const ProjectedContourPoint& b = contour[i + 1];
    if (gaps[i] <= kLineSpacingPx || gaps[i] > max_gap || a.normal.dot(b.normal) < 0.5) continue;
    const int steps = static_cast<int>(std::ceil(gaps[i] / kLineSpacingPx));
    for (int k = 1; k < steps; ++k) {
      const double f = static_cast<double>(k) / steps;
      ProjectedContourPoint between = a;
      between.pixel = (1.0 - f) * a.pixel + f * b.pixel;
      between.normal = ((1.0 - f) * a.normal + f * b.normal).normalized();
      between.inside_px = f < 0.5 ? a.inside_px : b.inside_px;
      between.outside_px = f < 0.5 ? a.outside_px : b.outside_px;
      dense.push_back(between);
    }
  }
  return dense;
}

}  // namespace

ContourLineSamples SampleContourLines(const cv::Mat3b& image,
                                      const std::vector<ProjectedContourPoint>& contour,
                                      const ColorModelOptions& options,
                                      const ColorHistograms& binner) {
  ContourLineSamples samples;
  const int first = static_cast<int>(std::floor(options.sample_margin_px)) + 1;
  samples.first_t = first;
  const double band = options.background_band_px;
  for (const ProjectedContourPoint& point : DensifyContourLines(contour)) {
    samples.line_pixels.push_back(point.pixel);
    samples.line_normals.push_back(point.normal);
    samples.line_begin.push_back(static_cast<int>(samples.codes.size()));
    for (const bool inside : {true, false}) {
      if (!inside) samples.line_outside.push_back(static_cast<int>(samples.codes.size()));
      const double extent = inside ? point.inside_px : point.outside_px;
      const double last = std::min(extent - options.sample_margin_px, band);  // extent may be +∞
      const Eigen::Vector2d step = inside ? -point.normal : point.normal;
      for (int t = first; t <= last; ++t) {
        // The nearest pixel (std::lround's rounding of halves away from zero differs only at
        // exact halves, and costs a library call per sample).
        const Eigen::Vector2d at = point.pixel + t * step;
        const int x = static_cast<int>(std::floor(at.x() + 0.5));
        const int y = static_cast<int>(std::floor(at.y() + 0.5));
        if (x < 0 || y < 0 || x >= image.cols || y >= image.rows) break;
        samples.codes.push_back((binner.Bin(image(y, x)) << 1) | static_cast<int>(inside));
      }
    }
  }
  samples.line_begin.push_back(static_cast<int>(samples.codes.size()));
  return samples;
}

}  // namespace internal

// ---------------------------------------------------------------------------------------------
// GlobalColorModel

GlobalColorModel::GlobalColorModel(const ColorModelOptions& options)
    : options_(options), histograms_(options.bins_per_channel) {
  BCOT_CHECK(options.Validate().ok());
}

void GlobalColorModel::Update(const cv::Mat3b& image, const Silhouette& silhouette) {
  BCOT_CHECK(image.size() == silhouette.mask.size());
  if (cv::countNonZero(silhouette.mask) == 0) return;
  const internal::BoundaryDistances distances(silhouette.mask, options_.background_band_px + 1,
                                              options_.sample_margin_px);
  Update(distances, internal::SampleCodes(image, silhouette.mask, distances, histograms_));
}

// A box grown further than band + 1 adds only pixels farther than `band` from the silhouette,
// which are not sampled, and leaves the others' distances and their row-major order as they
// are: the histograms are the same.
void GlobalColorModel::Update(const internal::BoundaryDistances& distances,
                              const cv::Mat1i& codes) {
  const int band = options_.background_band_px;
  const cv::Rect& box = distances.box();
  std::vector<int> foreground_bins;
  std::vector<int> background_bins;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const int* code = codes.ptr<int>(y - box.y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      const int sample = code[x - box.x];
      if (sample < 0) continue;
      if (sample & 1) {
        foreground_bins.push_back(sample >> 1);
      } else if (distances.ToInside(x, y) <= static_cast<float>(band)) {
        background_bins.push_back(sample >> 1);
      }
    }
  }
  histograms_.Update(foreground_bins, background_bins, options_.learning_rate_foreground,
                     options_.learning_rate_background);
}

void GlobalColorModel::UpdateAlongContour(const cv::Mat3b& image,
                                          const std::vector<ProjectedContourPoint>& contour) {
  Update(internal::SampleContourLines(image, contour, options_, histograms_));
}

void GlobalColorModel::Update(const internal::ContourLineSamples& samples) {
  std::vector<int> foreground_bins;
  std::vector<int> background_bins;
  for (const int sample : samples.codes) {
    (sample & 1 ? foreground_bins : background_bins).push_back(sample >> 1);
  }
  histograms_.Update(foreground_bins, background_bins, options_.learning_rate_foreground,
                     options_.learning_rate_background);
}

std::vector<double> GlobalColorModel::ForegroundPosteriors(
    const cv::Mat3b& image, const std::vector<Eigen::Vector2i>& pixels) const {
  std::vector<double> posteriors;
  posteriors.reserve(pixels.size());
  for (const Eigen::Vector2i& pixel : pixels) {
    BCOT_CHECK(pixel.x() >= 0 && pixel.y() >= 0 && pixel.x() < image.cols &&
               pixel.y() < image.rows);
    posteriors.push_back(
        histograms_.ForegroundPosterior(histograms_.Bin(image(pixel.y(), pixel.x()))));
  }
  return posteriors;
}

// ---------------------------------------------------------------------------------------------
// LocalColorModel

double DiscOverlapFraction(double distance, double radius) {
  BCOT_CHECK(radius > 0.0 && distance >= 0.0);
  const double u = distance / (2.0 * radius);
  if (u >= 1.0) return 0.0;
  return 2.0 / kPi * (std::acos(u) - u * std::sqrt(1.0 - u * u));
}

LocalColorModel::LocalColorModel(const ColorModelOptions& options, double object_diameter_mm)
    : options_(options),
      anchor_radius_mm_(options.local_anchor_fraction * object_diameter_mm),
      fallback_(options) {
  BCOT_CHECK(object_diameter_mm > 0.0 && std::isfinite(object_diameter_mm));
}

void LocalColorModel::Update(const cv::Mat3b& image, const Silhouette& silhouette) {
  BCOT_CHECK(image.size() == silhouette.mask.size());
  if (cv::countNonZero(silhouette.mask) == 0) {
    active_.clear();
    BuildCoverGrid();
    return;
  }
  std::vector<bool> is_active(regions_.size(), false);
  const double radius = options_.local_region_radius_px;
  const int reach = static_cast<int>(std::ceil(radius));
  // Pixels within the sample margin of the silhouette boundary are mixed (anti-aliased,
  // blurred) and not sampled, as in the global model. Every sampled pixel lies within `reach`
  // of a contour point, so within reach + 2 px of the mask's bounding box (the box's side).
  // One set of boundary distances serves the fallback's update and this one.
  const internal::BoundaryDistances distances(silhouette.mask,
                                              std::max(reach + 2, options_.background_band_px + 1),
                                              options_.sample_margin_px);
  // Every histogram of the model bins alike: the fallback's bins the samples.
  const cv::Mat1i codes =
      internal::SampleCodes(image, silhouette.mask, distances, fallback_.histograms());
  fallback_.Update(distances, codes);
  active_.clear();
  const cv::Rect& box = distances.box();
  std::vector<int> foreground_bins;
  std::vector<int> background_bins;
  double arc_since_centre = 0.0;
  for (size_t i = 0; i < silhouette.contour.size(); ++i) {
    const ContourPoint& point = silhouette.contour[i];
    const bool new_contour = i == 0 || silhouette.contour[i - 1].contour_id != point.contour_id;
    if (!new_contour) {
      arc_since_centre += (point.pixel - silhouette.contour[i - 1].pixel).norm();
      if (arc_since_centre < options_.local_region_spacing_px) continue;
    }
    arc_since_centre = 0.0;
    // The region with the nearest anchor within the radius, else a new one.
    int region = NearestRegion(point.point_in_object);
    if (region >= 0 && is_active[region]) continue;
    foreground_bins.clear();
    background_bins.clear();
    const int cx = static_cast<int>(std::lround(point.pixel.x()));
    const int cy = static_cast<int>(std::lround(point.pixel.y()));
    for (int y = std::max(box.y, cy - reach); y <= std::min(box.br().y - 1, cy + reach); ++y) {
      const int* code = codes.ptr<int>(y - box.y);
      for (int x = std::max(box.x, cx - reach); x <= std::min(box.br().x - 1, cx + reach); ++x) {
        if ((Eigen::Vector2d(x, y) - point.pixel).squaredNorm() > radius * radius) continue;
        const int sample = code[x - box.x];
        if (sample < 0) continue;
        (sample & 1 ? foreground_bins : background_bins).push_back(sample >> 1);
      }
    }
    if (region < 0) {
      region = NewRegion(point.point_in_object, point.pixel);
      is_active.push_back(false);
    }
    LearnRegion(region, point.pixel, foreground_bins, background_bins);
    is_active[region] = true;
    active_.push_back({point.pixel, region});
  }
  BuildCoverGrid();
}

void LocalColorModel::UpdateAlongContour(const cv::Mat3b& image,
                                         const std::vector<ProjectedContourPoint>& contour) {
  active_.clear();
  if (contour.empty()) {
    BuildCoverGrid();
    return;
  }
  const internal::ContourLineSamples samples =
      internal::SampleContourLines(image, contour, options_, fallback_.histograms());
  fallback_.Update(samples);
  // The centres first (regions found or created as in Update), then the samples of each disc.
  const double spacing_squared =
      options_.local_region_spacing_px * options_.local_region_spacing_px;
  std::vector<bool> is_active(regions_.size(), false);
  for (const ProjectedContourPoint& point : contour) {
    const bool near_a_centre =
        std::any_of(active_.begin(), active_.end(), [&](const ActiveRegion& active) {
          return (active.centre - point.pixel).squaredNorm() < spacing_squared;
        });
    if (near_a_centre) continue;
    int region = NearestRegion(point.point_in_object);
    if (region >= 0 && is_active[region]) continue;
    if (region < 0) {
      region = NewRegion(point.point_in_object, point.pixel);
      is_active.push_back(false);
    }
    is_active[region] = true;
    active_.push_back({point.pixel, region});
  }
  BuildCoverGrid();
  // Each region takes the samples of each line that lie within its disc. Along a line with
  // contour point c and normal n, the point c + s·n is within the radius ρ of the centre m for
  // s in [−d·n − h, −d·n + h], d = c − m, h = √((d·n)² − |d|² + ρ²) (no such s when the root's
  // argument is negative); outside samples sit at s = t, inside ones at s = −t.
  const double radius = options_.local_region_radius_px;
  std::vector<std::vector<int>> foreground_bins(active_.size());
  std::vector<std::vector<int>> background_bins(active_.size());
  // The samples [begin, end) of one side at distances t_low..t_high to region r.
  auto take = [&](int begin, int end, int t_low, int t_high, size_t r) {
    const int from = begin + std::max(0, t_low - samples.first_t);
    const int to = std::min(end, begin + t_high - samples.first_t + 1);
    for (int i = from; i < to; ++i) {
      const int sample = samples.codes[i];
      (sample & 1 ? foreground_bins : background_bins)[r].push_back(sample >> 1);
    }
  };
  for (size_t line = 0; line < samples.line_pixels.size(); ++line) {
    const Eigen::Vector2d& c = samples.line_pixels[line];
    const Eigen::Vector2d& n = samples.line_normals[line];
    for (size_t r = 0; r < active_.size(); ++r) {
      const Eigen::Vector2d d = c - active_[r].centre;
      const double dn = d.dot(n);
      const double argument = dn * dn - d.squaredNorm() + radius * radius;
      if (argument < 0.0) continue;
      const double h = std::sqrt(argument);
      const double s_low = -dn - h, s_high = -dn + h;
      take(samples.line_begin[line], samples.line_outside[line],
           static_cast<int>(std::ceil(-s_high)), static_cast<int>(std::floor(-s_low)), r);
      take(samples.line_outside[line], samples.line_begin[line + 1],
           static_cast<int>(std::ceil(s_low)), static_cast<int>(std::floor(s_high)), r);
    }
  }
  for (size_t r = 0; r < active_.size(); ++r) {
    LearnRegion(active_[r].region, active_[r].centre, foreground_bins[r], background_bins[r]);
  }
}

int LocalColorModel::NewRegion(const Eigen::Vector3d& anchor_in_template,
                               const Eigen::Vector2d& centre) {
  regions_.push_back({anchor_in_template, ColorHistograms(options_.bins_per_channel), centre});
  return static_cast<int>(regions_.size()) - 1;
}

int LocalColorModel::NearestRegion(const Eigen::Vector3d& point_in_object) const {
  int region = -1;
  double best_squared = anchor_radius_mm_ * anchor_radius_mm_;
  for (size_t r = 0; r < regions_.size(); ++r) {
    const double d2 = (regions_[r].anchor_in_template - point_in_object).squaredNorm();
    if (d2 <= best_squared) {
      best_squared = d2;
      region = static_cast<int>(r);
    }
  }
  return region;
}

void LocalColorModel::LearnRegion(int region, const Eigen::Vector2d& centre,
                                  const std::vector<int>& foreground,
                                  const std::vector<int>& background) {
  Region& learned = regions_[region];
  double background_rate = options_.learning_rate_background;
  if (options_.local_background_memory == LocalBackgroundMemory::kImage) {
    const double overlap =
        DiscOverlapFraction((centre - learned.last_centre).norm(), options_.local_region_radius_px);
    background_rate = 1.0 - (1.0 - background_rate) * overlap;
  }
  learned.histograms.Update(foreground, background, options_.learning_rate_foreground,
                            background_rate);
  learned.last_centre = centre;
}

void LocalColorModel::BuildCoverGrid() {
  cover_ = CoverGrid{};
  if (active_.empty()) return;
  constexpr int kCell = CoverGrid::kCellPx;
  const double radius = options_.local_region_radius_px;
  Eigen::Vector2d low = active_.front().centre, high = low;
  for (const ActiveRegion& region : active_) {
    low = low.cwiseMin(region.centre);
    high = high.cwiseMax(region.centre);
  }
  // Every pixel within `radius` of a centre lies in [first, last].
  const Eigen::Vector2i first((low.array() - radius).floor().cast<int>());
  const Eigen::Vector2i last((high.array() + radius).ceil().cast<int>());
  cover_.origin = first;
  cover_.cols = (last.x() - first.x()) / kCell + 1;
  cover_.rows = (last.y() - first.y()) / kCell + 1;
  cover_.cells.resize(static_cast<size_t>(cover_.cols) * cover_.rows);
  for (size_t r = 0; r < active_.size(); ++r) {
    const Eigen::Vector2d& centre = active_[r].centre;
    const Eigen::Vector2d relative = centre - first.cast<double>();
    const int col_begin =
        std::max(0, static_cast<int>(std::floor((relative.x() - radius) / kCell)));
    const int col_end =
        std::min(cover_.cols - 1, static_cast<int>(std::floor((relative.x() + radius) / kCell)));
    const int row_begin =
        std::max(0, static_cast<int>(std::floor((relative.y() - radius) / kCell)));
    const int row_end =
        std::min(cover_.rows - 1, static_cast<int>(std::floor((relative.y() + radius) / kCell)));
    for (int row = row_begin; row <= row_end; ++row) {
      for (int col = col_begin; col <= col_end; ++col) {
        // The cell's pixels span [corner, corner + kCell − 1]; the point of that rectangle
        // nearest the centre is within the radius iff one of its pixels may be.
        const Eigen::Vector2d corner =
            (first + Eigen::Vector2i(col * kCell, row * kCell)).cast<double>();
        const Eigen::Vector2d nearest =
            centre.cwiseMax(corner).cwiseMin(corner + Eigen::Vector2d::Constant(kCell - 1));
        if ((nearest - centre).squaredNorm() <= radius * radius) {
          cover_.cells[static_cast<size_t>(row) * cover_.cols + col].push_back(static_cast<int>(r));
        }
      }
    }
  }
}

const ColorHistograms& LocalColorModel::region_histograms(int region) const {
  BCOT_CHECK(region >= 0 && region < num_regions());
  return regions_[region].histograms;
}

const std::vector<int>* LocalColorModel::CoverGrid::Cell(const Eigen::Vector2i& pixel) const {
  const Eigen::Vector2i relative = pixel - origin;
  if (relative.x() < 0 || relative.y() < 0) return nullptr;
  const int col = relative.x() / kCellPx, row = relative.y() / kCellPx;
  if (col >= cols || row >= rows) return nullptr;
  return &cells[static_cast<size_t>(row) * cols + col];
}

std::vector<double> LocalColorModel::ForegroundPosteriors(
    const cv::Mat3b& image, const std::vector<Eigen::Vector2i>& pixels) const {
  // The fallback's posterior only where no active region covers the pixel.
  std::vector<double> posteriors(pixels.size());
  const double radius_squared = options_.local_region_radius_px * options_.local_region_radius_px;
  std::vector<const ColorHistograms*> histograms;
  histograms.reserve(active_.size());
  for (const ActiveRegion& region : active_) {
    const ColorHistograms& h = regions_[region.region].histograms;
    histograms.push_back(h.initialized() ? &h : nullptr);
  }
  const ColorHistograms& global = fallback_.histograms();  // every histogram bins alike
  for (size_t p = 0; p < pixels.size(); ++p) {
    BCOT_CHECK(pixels[p].x() >= 0 && pixels[p].y() >= 0 && pixels[p].x() < image.cols &&
               pixels[p].y() < image.rows);
    const int bin = global.Bin(image(pixels[p].y(), pixels[p].x()));
    double sum = 0.0;
    int count = 0;
    if (const std::vector<int>* candidates = cover_.Cell(pixels[p])) {
      const Eigen::Vector2d pixel = pixels[p].cast<double>();
      for (const int r : *candidates) {
        if (histograms[r] == nullptr) continue;
        if ((pixel - active_[r].centre).squaredNorm() > radius_squared) continue;
        sum += histograms[r]->ForegroundPosterior(bin);
        ++count;
      }
    }
    posteriors[p] = count > 0 ? sum / count : global.ForegroundPosterior(bin);
  }
  return posteriors;
}

ColorModelOptions RefineColorModelOptions(const ColorModelOptions& options) {
  ColorModelOptions refine = options;
  if (options.refine_kind.has_value()) refine.kind = *options.refine_kind;
  refine.refine_kind.reset();
  return refine;
}

std::unique_ptr<ColorModel> MakeColorModel(const ColorModelOptions& options,
                                           double object_diameter_mm) {
  BCOT_CHECK(options.Validate().ok());
  if (options.kind == ColorModelKind::kLocal) {
    return std::make_unique<LocalColorModel>(options, object_diameter_mm);
  }
  return std::make_unique<GlobalColorModel>(options);
}

ViewColorModels::ViewColorModels(const ColorModelOptions& options, double object_diameter_mm) {
  const ColorModelOptions refine = RefineColorModelOptions(options);
  if (refine.kind != options.kind) refine_ = MakeColorModel(refine, object_diameter_mm);
  if (options.kind == ColorModelKind::kGlobal && refine.kind == ColorModelKind::kLocal) {
    coarse_ = &static_cast<const LocalColorModel&>(*refine_).fallback();
  } else {
    own_coarse_ = MakeColorModel(options, object_diameter_mm);
    coarse_ = own_coarse_.get();
  }
}

void ViewColorModels::Update(const cv::Mat3b& image, const Silhouette& silhouette) {
  if (own_coarse_ != nullptr) own_coarse_->Update(image, silhouette);
  if (refine_ != nullptr) refine_->Update(image, silhouette);
}

void ViewColorModels::UpdateAlongContour(const cv::Mat3b& image,
                                         const std::vector<ProjectedContourPoint>& contour) {
  if (own_coarse_ != nullptr) own_coarse_->UpdateAlongContour(image, contour);
  if (refine_ != nullptr) refine_->UpdateAlongContour(image, contour);
}

bool ViewColorModels::UsesContour() const {
  return coarse_->UsesContour() || (refine_ != nullptr && refine_->UsesContour());
}

}  // namespace bcot

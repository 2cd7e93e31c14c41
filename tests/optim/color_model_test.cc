#include "bcot/optim/color_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "region_test_scene.h"

namespace bcot {
namespace {

TEST(ColorModelOptionsTest, ValidateListsEveryViolation) {
  EXPECT_TRUE(ColorModelOptions().Validate().ok());
  ColorModelOptions options;
  options.bins_per_channel = 30;
  options.learning_rate_foreground = 0.0;
  options.learning_rate_background = 1.5;
  options.background_band_px = -3;
  options.local_region_radius_px = -1.0;
  options.local_region_spacing_px = 0.0;
  options.local_anchor_fraction = 2.0;
  options.local_background_memory = static_cast<LocalBackgroundMemory>(7);
  test::ExpectErrorNaming(
      options.Validate(), StatusCode::kInvalidConfig,
      {"color_model: ", "bins_per_channel = 30, must divide 256",
       "learning_rate_foreground = 0, must be in (0, 1]",
       "learning_rate_background = 1.5, must be in (0, 1]", "background_band_px = -3, must be > 0",
       "local_region_radius_px = -1", "local_region_spacing_px = 0",
       "local_anchor_fraction = 2, must be in (0, 1]",
       "local_background_memory = 7, must be image or object"});
  for (int bins : {1, 2, 8, 32, 256}) {
    options = ColorModelOptions();
    options.bins_per_channel = bins;
    EXPECT_TRUE(options.Validate().ok()) << bins;
  }
}

TEST(ColorHistogramsTest, PosteriorsAndTemporalBlending) {
  ColorHistograms histograms(4);
  EXPECT_FALSE(histograms.initialized());
  EXPECT_EQ(histograms.Bin(cv::Vec3b(0, 0, 0)), 0);
  EXPECT_EQ(histograms.Bin(cv::Vec3b(255, 255, 255)), 63);
  EXPECT_EQ(histograms.Bin(cv::Vec3b(64, 0, 130)), 16 + 2);
  EXPECT_DOUBLE_EQ(histograms.ForegroundPosterior(5), 0.5);  // nothing learned yet

  // First update sets: h_f = {0: 1}, h_b = {0: ½, 1: ½}.
  ASSERT_TRUE(histograms.Update({0, 0}, {0, 1}, 0.1, 0.2));
  EXPECT_TRUE(histograms.initialized());
  EXPECT_FLOAT_EQ(histograms.foreground()[0], 1.0f);
  EXPECT_FLOAT_EQ(histograms.background()[1], 0.5f);
  EXPECT_NEAR(histograms.ForegroundPosterior(0), 1.0 / 1.5, 1e-7);
  EXPECT_DOUBLE_EQ(histograms.ForegroundPosterior(1), 0.0);
  EXPECT_DOUBLE_EQ(histograms.ForegroundPosterior(7), 0.5);  // unseen colour

  // Second update blends with the learning rates: h ← (1 − α)·h + α·h_new.
  ASSERT_TRUE(histograms.Update({2}, {3}, 0.1, 0.2));
  EXPECT_FLOAT_EQ(histograms.foreground()[0], 0.9f);
  EXPECT_FLOAT_EQ(histograms.foreground()[2], 0.1f);
  EXPECT_FLOAT_EQ(histograms.background()[0], 0.4f);
  EXPECT_FLOAT_EQ(histograms.background()[3], 0.2f);
  EXPECT_NEAR(histograms.ForegroundPosterior(0), 0.9 / 1.3, 1e-6);

  // A side without samples keeps its histogram; no samples at all changes nothing.
  ASSERT_TRUE(histograms.Update({}, {3}, 0.1, 1.0));
  EXPECT_FLOAT_EQ(histograms.foreground()[0], 0.9f);
  EXPECT_FLOAT_EQ(histograms.background()[3], 1.0f);
  EXPECT_FALSE(histograms.Update({}, {}, 0.1, 0.2));
}

class ColorModelSceneTest : public test::SpoolImageTest {
 protected:
  void SetUp() override {
    SpoolImageTest::SetUp();
    silhouette_ = SilhouetteAt(cam_from_objcentre_);
  }

  Silhouette SilhouetteAt(const Eigen::Isometry3d& cam_from_objcentre) const {
    return RenderSilhouette(*caster_, camera_,
                            cam_from_objcentre * mesh_->objcentre_from_template());
  }

  // Mean P_f over pixels well inside (> 3 px) and over pixels 4..30 px outside the silhouette.
  void MeanPosteriors(const ColorModel& model, double* inside, double* outside) const {
    cv::Mat1f distance_outside, distance_inside;
    cv::distanceTransform(silhouette_.mask == 0, distance_outside, cv::DIST_L2, 5);
    cv::distanceTransform(silhouette_.mask != 0, distance_inside, cv::DIST_L2, 5);
    std::vector<Eigen::Vector2i> inside_pixels, outside_pixels;
    for (int y = 0; y < image_.rows; y += 2) {
      for (int x = 0; x < image_.cols; x += 2) {
        if (distance_inside(y, x) > 3.0f) inside_pixels.emplace_back(x, y);
        const float d = distance_outside(y, x);
        if (d > 4.0f && d < 30.0f) outside_pixels.emplace_back(x, y);
      }
    }
    ASSERT_GT(inside_pixels.size(), 1000u);
    ASSERT_GT(outside_pixels.size(), 1000u);
    auto mean = [](const std::vector<double>& values) {
      double sum = 0.0;
      for (double v : values) sum += v;
      return sum / static_cast<double>(values.size());
    };
    *inside = mean(model.ForegroundPosteriors(image_, inside_pixels));
    *outside = mean(model.ForegroundPosteriors(image_, outside_pixels));
  }

  // P_f above 0.95 on average well inside, below 0.05 outside (MeanPosteriors).
  void ExpectDiscriminates(const ColorModel& model) const {
    ASSERT_TRUE(model.initialized());
    double inside = 0.0, outside = 0.0;
    MeanPosteriors(model, &inside, &outside);
    EXPECT_GT(inside, 0.95);
    EXPECT_LT(outside, 0.05);
  }

  Silhouette silhouette_;
};

TEST_F(ColorModelSceneTest, GlobalPosteriorsDiscriminateObjectAndBackground) {
  GlobalColorModel model{ColorModelOptions()};
  EXPECT_FALSE(model.initialized());
  model.Update(image_, silhouette_);
  ExpectDiscriminates(model);
}

TEST_F(ColorModelSceneTest, GlobalModelIgnoresAnEmptySilhouette) {
  GlobalColorModel model{ColorModelOptions()};
  Silhouette empty;
  empty.mask = cv::Mat1b::zeros(image_.size());
  model.Update(image_, empty);
  EXPECT_FALSE(model.initialized());
  const std::vector<double> posteriors = model.ForegroundPosteriors(image_, {{10, 10}});
  EXPECT_DOUBLE_EQ(posteriors[0], 0.5);
}

TEST_F(ColorModelSceneTest, LocalPosteriorsDiscriminateAndRegionsPersist) {
  ColorModelOptions options;
  options.kind = ColorModelKind::kLocal;
  const std::unique_ptr<ColorModel> model = MakeColorModel(options, mesh_->diameter());
  auto* local = dynamic_cast<LocalColorModel*>(model.get());
  ASSERT_NE(local, nullptr);
  model->Update(image_, silhouette_);
  ASSERT_TRUE(model->initialized());
  const int active = static_cast<int>(local->active_regions().size());
  EXPECT_GT(active, 10);
  EXPECT_EQ(local->num_regions(), active);
  for (const auto& region : local->active_regions()) {
    EXPECT_TRUE(camera_.InImage(region.centre));
  }
  ExpectDiscriminates(*model);

  // The same pose again finds the same regions (anchored to model points); a small motion
  // mostly reuses them (temporal consistency).
  model->Update(image_, silhouette_);
  EXPECT_EQ(local->num_regions(), active);
  const Eigen::Isometry3d moved =
      cam_from_objcentre_ * ExpSE3((Vector6d() << 1.0, 0.5, 0.0, 0.0, 0.02, 0.01).finished());
  model->Update(image_, SilhouetteAt(moved));
  EXPECT_LT(local->num_regions(), active + active / 4);
}

// A pixel's local posterior is the mean P_f of the active regions whose disc holds it, in the
// order of the active regions (the model looks them up in a grid of cells; this sums over all of
// them), and the global fallback's where none does: exactly, at every pixel of the image, for
// radii below, near and above the grid's cell size, after a move that activates other regions.
TEST_F(ColorModelSceneTest, LocalPosteriorsAverageTheRegionsCoveringEachPixel) {
  std::vector<Eigen::Vector2i> pixels;
  for (int y = 0; y < image_.rows; ++y) {
    for (int x = 0; x < image_.cols; ++x) pixels.emplace_back(x, y);
  }
  const Eigen::Isometry3d moved =
      cam_from_objcentre_ * ExpSE3((Vector6d() << 4.0, -3.0, 0.0, 0.1, 0.0, 0.2).finished());
  for (const double radius : {7.3, 16.0, 40.0, 95.5}) {
    SCOPED_TRACE(radius);
    ColorModelOptions options;
    options.kind = ColorModelKind::kLocal;
    options.local_region_radius_px = radius;
    LocalColorModel model(options, mesh_->diameter());
    model.Update(image_, silhouette_);
    model.Update(image_, SilhouetteAt(moved));
    ASSERT_GT(model.active_regions().size(), 10u);
    const std::vector<double> posteriors = model.ForegroundPosteriors(image_, pixels);
    const ColorHistograms& global = model.fallback().histograms();
    int covered = 0;
    for (size_t p = 0; p < pixels.size(); ++p) {
      const int bin = global.Bin(image_(pixels[p].y(), pixels[p].x()));
      double sum = 0.0;
      int count = 0;
      for (const LocalColorModel::ActiveRegion& region : model.active_regions()) {
        const ColorHistograms& histograms = model.region_histograms(region.region);
        if (!histograms.initialized()) continue;
        if ((pixels[p].cast<double>() - region.centre).squaredNorm() > radius * radius) continue;
        sum += histograms.ForegroundPosterior(bin);
        ++count;
      }
      covered += count > 0;
      const double expected = count > 0 ? sum / count : global.ForegroundPosterior(bin);
      ASSERT_EQ(posteriors[p], expected) << "pixel " << pixels[p].transpose();
    }
    EXPECT_GT(covered, 100);
    EXPECT_LT(covered, static_cast<int>(pixels.size()));
  }
}

// The samples along a contour line: from ⌊margin⌋ + 1 px on, one per pixel step, the inside up
// to its extent less the margin, the outside up to the band (its extent is unbounded), in order,
// each side stopping at the image's border; bins and sides in the codes.
TEST(SampleContourLinesTest, SamplesEachSideWithinItsExtentTheBandAndTheImage) {
  cv::Mat3b image(48, 64);
  cv::RNG rng(3);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  ColorModelOptions options;
  options.sample_margin_px = 2.0;
  options.background_band_px = 6;
  const ColorHistograms binner(options.bins_per_channel);
  ProjectedContourPoint point;
  point.pixel = Eigen::Vector2d(30.3, 20.6);
  point.normal = Eigen::Vector2d(0.6, 0.8);
  point.inside_px = 7.5;
  point.outside_px = std::numeric_limits<double>::infinity();
  ProjectedContourPoint at_border = point;  // its outside leaves the image after 2 steps
  at_border.pixel = Eigen::Vector2d(58.0, 20.0);
  at_border.normal = Eigen::Vector2d(1.0, 0.0);
  at_border.inside_px = 3.2;  // 3.2 − 2 < 3: no inside sample
  const internal::ContourLineSamples samples =
      internal::SampleContourLines(image, {point, at_border}, options, binner);
  std::vector<int> expected_codes;
  auto expect = [&](const Eigen::Vector2d& at, bool inside) {
    const cv::Vec3b color =
        image(static_cast<int>(std::lround(at.y())), static_cast<int>(std::lround(at.x())));
    expected_codes.push_back((binner.Bin(color) << 1) | static_cast<int>(inside));
  };
  for (int t = 3; t <= 5; ++t) expect(point.pixel - t * point.normal, true);
  for (int t = 3; t <= 6; ++t) expect(point.pixel + t * point.normal, false);
  for (int t = 3; t <= 5; ++t) expect(at_border.pixel + t * at_border.normal, false);
  EXPECT_EQ(samples.codes, expected_codes);
  EXPECT_EQ(samples.first_t, 3);
  EXPECT_EQ(samples.line_begin, (std::vector<int>{0, 7, 10}));
  EXPECT_EQ(samples.line_outside, (std::vector<int>{3, 7}));
  EXPECT_EQ(samples.line_normals[0], point.normal);
  ASSERT_EQ(samples.line_pixels.size(), 2u);
  EXPECT_EQ(samples.line_pixels[1], at_border.pixel);
}

// Between neighbours on one contour the lines are filled in 0.5 px apart, each with the extents
// of the nearer neighbour; a jump to another contour (more than twice the median distance of
// neighbours) is not filled.
TEST(SampleContourLinesTest, FillsTheLinesBetweenNeighboursOfOneContour) {
  cv::Mat3b image(48, 64, cv::Vec3b(10, 20, 30));
  ColorModelOptions options;
  options.sample_margin_px = 2.0;
  options.background_band_px = 6;
  std::vector<ProjectedContourPoint> contour;
  for (const auto& [x, inside] : std::vector<std::pair<double, double>>{
           {10.0, 4.0}, {12.0, 10.0}, {14.0, 10.0}, {40.0, 10.0}}) {
    ProjectedContourPoint point;
    point.pixel = Eigen::Vector2d(x, 20.0);
    point.normal = Eigen::Vector2d(0.0, -1.0);  // outward is up, the inside below
    point.inside_px = inside;
    point.outside_px = std::numeric_limits<double>::infinity();
    contour.push_back(point);
  }
  const internal::ContourLineSamples samples = internal::SampleContourLines(
      image, contour, options, ColorHistograms(options.bins_per_channel));
  // Lines at x = 10, 10.5, ..., 14 and 40. Inside (t = 3..6 px) on all but x = 10 and 10.5,
  // whose nearer neighbour reaches only 4 px inside (4 − margin < 3); outside on every line.
  ASSERT_EQ(samples.line_pixels.size(), 10u);
  ASSERT_EQ(samples.line_begin.size(), 11u);
  for (size_t line = 0; line < 10; ++line) {
    const double x = line < 9 ? 10.0 + 0.5 * static_cast<double>(line) : 40.0;
    EXPECT_EQ(samples.line_pixels[line], Eigen::Vector2d(x, 20.0)) << line;
    int inside = 0, outside = 0;
    for (int s = samples.line_begin[line]; s < samples.line_begin[line + 1]; ++s) {
      (samples.codes[s] & 1 ? inside : outside) += 1;
      EXPECT_EQ((samples.codes[s] & 1) != 0, s < samples.line_outside[line]);
    }
    EXPECT_EQ(inside, line < 2 ? 0 : 4) << line;
    EXPECT_EQ(outside, 4) << line;
  }
}

// The scene's exact contour as a viewpoint model would give it: every third point, with the
// extents over which the mask keeps its value along the normal (0.25 px steps).
std::vector<ProjectedContourPoint> ContourLinesOf(const Silhouette& silhouette) {
  auto extent = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& direction, bool inside) {
    for (double t = 0.25; t < 300.0; t += 0.25) {
      const Eigen::Vector2d at = from + t * direction;
      const int x = static_cast<int>(std::lround(at.x())),
                y = static_cast<int>(std::lround(at.y()));
      if (x < 0 || y < 0 || x >= silhouette.mask.cols || y >= silhouette.mask.rows) break;
      if ((silhouette.mask(y, x) != 0) != inside) return t;
    }
    return std::numeric_limits<double>::infinity();
  };
  std::vector<ProjectedContourPoint> lines;
  for (size_t i = 0; i < silhouette.contour.size(); i += 3) {
    const ContourPoint& point = silhouette.contour[i];
    ProjectedContourPoint line;
    line.pixel = point.pixel;
    line.normal = point.normal;
    line.point_in_object = point.point_in_object;
    line.inside_px = extent(point.pixel, -point.normal, true);
    line.outside_px = extent(point.pixel, point.normal, false);
    lines.push_back(line);
  }
  return lines;
}

// Learned along the contour's lines instead of from the silhouette, both models tell the object
// from the background as well; the local model's centres are at least the spacing apart, about
// as many as along the silhouette's contour, and found again at the same pose.
TEST_F(ColorModelSceneTest, ModelsLearnedAlongTheContourLinesDiscriminateLikeTheSilhouette) {
  const std::vector<ProjectedContourPoint> lines = ContourLinesOf(silhouette_);
  ASSERT_GT(lines.size(), 50u);
  GlobalColorModel global{ColorModelOptions()};
  global.UpdateAlongContour(image_, lines);
  ExpectDiscriminates(global);

  ColorModelOptions options;
  options.kind = ColorModelKind::kLocal;
  LocalColorModel local(options, mesh_->diameter());
  local.UpdateAlongContour(image_, lines);
  ExpectDiscriminates(local);
  LocalColorModel from_silhouette(options, mesh_->diameter());
  from_silhouette.Update(image_, silhouette_);
  const auto& active = local.active_regions();
  const double expected = static_cast<double>(from_silhouette.active_regions().size());
  EXPECT_GT(static_cast<double>(active.size()), 0.7 * expected);
  EXPECT_LT(static_cast<double>(active.size()), 1.3 * expected);
  for (size_t a = 0; a < active.size(); ++a) {
    EXPECT_TRUE(local.region_histograms(active[a].region).initialized()) << a;
    for (size_t b = 0; b < a; ++b) {
      EXPECT_GE((active[a].centre - active[b].centre).norm(), options.local_region_spacing_px);
    }
  }
  const int regions = local.num_regions();
  const size_t active_count = active.size();
  local.UpdateAlongContour(image_, lines);
  EXPECT_EQ(local.num_regions(), regions);
  EXPECT_EQ(local.active_regions().size(), active_count);

  // No contour: nothing learned, no active region.
  local.UpdateAlongContour(image_, {});
  EXPECT_TRUE(local.active_regions().empty());
  GlobalColorModel unlearned{ColorModelOptions()};
  unlearned.UpdateAlongContour(image_, {});
  EXPECT_FALSE(unlearned.initialized());
}

// Along the contour a local region learns from the samples whose point (the line's point at
// their distance, before rounding to a pixel) lies within its disc: the same histograms as a
// brute-force test of every sample against every active disc, in the same order.
TEST_F(ColorModelSceneTest, RegionsAlongTheContourLearnTheSamplesInTheirDiscs) {
  const std::vector<ProjectedContourPoint> lines = ContourLinesOf(silhouette_);
  ColorModelOptions options;
  options.kind = ColorModelKind::kLocal;
  options.local_region_radius_px = 23.5;
  LocalColorModel model(options, mesh_->diameter());
  model.UpdateAlongContour(image_, lines);
  const internal::ContourLineSamples samples =
      internal::SampleContourLines(image_, lines, options, model.fallback().histograms());
  ASSERT_GT(model.active_regions().size(), 10u);
  const double radius_squared = options.local_region_radius_px * options.local_region_radius_px;
  int partial_lines = 0;
  for (const LocalColorModel::ActiveRegion& region : model.active_regions()) {
    std::vector<int> foreground, background;
    for (size_t line = 0; line < samples.line_pixels.size(); ++line) {
      int taken = 0, total = 0;
      for (int i = samples.line_begin[line]; i < samples.line_begin[line + 1]; ++i) {
        const bool inside = i < samples.line_outside[line];
        const int t =
            samples.first_t + i - (inside ? samples.line_begin[line] : samples.line_outside[line]);
        const Eigen::Vector2d at =
            samples.line_pixels[line] + (inside ? -t : t) * samples.line_normals[line];
        ++total;
        if ((at - region.centre).squaredNorm() > radius_squared) continue;
        ++taken;
        (inside ? foreground : background).push_back(samples.codes[i] >> 1);
      }
      partial_lines += taken > 0 && taken < total;
    }
    ColorHistograms expected(options.bins_per_channel);
    expected.Update(foreground, background, 1.0, 1.0);
    const ColorHistograms& learned = model.region_histograms(region.region);
    EXPECT_EQ(learned.foreground(), expected.foreground());
    EXPECT_EQ(learned.background(), expected.background());
  }
  EXPECT_GT(partial_lines, 100);  // lines that cross a disc's rim are cut, not taken whole
}

// A global coarse model beside a local refinement is the local model's own fallback: the same
// posteriors as a global model learned on its own, after every update. Other combinations keep
// one model per kind, and no refinement model when the kinds agree.
TEST_F(ColorModelSceneTest, ViewColorModelsShareTheGlobalModelWithTheLocalOne) {
  ColorModelOptions options;  // global, refined by local
  ViewColorModels models(options, mesh_->diameter());
  ASSERT_NE(models.refine(), nullptr);
  EXPECT_NE(dynamic_cast<const LocalColorModel*>(models.refine()), nullptr);
  EXPECT_EQ(&models.coarse(), &static_cast<const LocalColorModel*>(models.refine())->fallback());
  EXPECT_TRUE(models.UsesContour());
  GlobalColorModel alone(options);
  std::vector<Eigen::Vector2i> pixels;
  for (int y = 0; y < image_.rows; y += 3) {
    for (int x = 0; x < image_.cols; x += 3) pixels.emplace_back(x, y);
  }
  const Eigen::Isometry3d moved =
      cam_from_objcentre_ * ExpSE3((Vector6d() << 2.0, 1.0, 0.0, 0.05, 0.1, 0.0).finished());
  for (const Silhouette& silhouette : {silhouette_, SilhouetteAt(moved)}) {
    models.Update(image_, silhouette);
    alone.Update(image_, silhouette);
    EXPECT_EQ(models.coarse().ForegroundPosteriors(image_, pixels),
              alone.ForegroundPosteriors(image_, pixels));
  }

  options.refine_kind.reset();
  const ViewColorModels single(options, mesh_->diameter());
  EXPECT_EQ(single.refine(), nullptr);
  EXPECT_NE(dynamic_cast<const GlobalColorModel*>(&single.coarse()), nullptr);
  EXPECT_FALSE(single.UsesContour());

  options.kind = ColorModelKind::kLocal;
  options.refine_kind = ColorModelKind::kGlobal;
  const ViewColorModels swapped(options, mesh_->diameter());
  EXPECT_NE(dynamic_cast<const LocalColorModel*>(&swapped.coarse()), nullptr);
  EXPECT_NE(dynamic_cast<const GlobalColorModel*>(swapped.refine()), nullptr);
}

// The global model samples the inside pixels farther than sample_margin_px from any outside
// pixel and the outside pixels within (margin, band] of the nearest inside one (Euclidean
// distances between pixel centres, the image's edge not counting as outside): the same bins,
// in the same order, as a brute-force search over every pixel pair, for a mask that is cut by
// the image border and has a hole, at integer and fractional margins.
TEST(GlobalColorModelTest, SamplesByExactBoundaryDistances) {
  cv::Mat1b mask(48, 64, static_cast<unsigned char>(0));
  cv::ellipse(mask, cv::Point(20, 10), cv::Size(22, 14), 15.0, 0.0, 360.0, cv::Scalar(255), -1);
  cv::circle(mask, cv::Point(18, 12), 4, cv::Scalar(0), -1);
  cv::RNG rng(7);
  cv::Mat3b image(mask.size());
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  Silhouette silhouette;
  silhouette.mask = mask;
  for (double margin : {0.0, 1.0, 2.0, 2.5, 3.2}) {
    SCOPED_TRACE(margin);
    ColorModelOptions options;
    options.sample_margin_px = margin;
    options.background_band_px = 7;
    GlobalColorModel model(options);
    model.Update(image, silhouette);
    std::vector<int> foreground, background;
    ColorHistograms expected(options.bins_per_channel);
    for (int y = 0; y < mask.rows; ++y) {
      for (int x = 0; x < mask.cols; ++x) {
        const bool inside = mask(y, x) != 0;
        int nearest_squared = -1;
        for (int v = 0; v < mask.rows; ++v) {
          for (int u = 0; u < mask.cols; ++u) {
            if ((mask(v, u) != 0) == inside) continue;
            const int d2 = (u - x) * (u - x) + (v - y) * (v - y);
            if (nearest_squared < 0 || d2 < nearest_squared) nearest_squared = d2;
          }
        }
        const double distance = std::sqrt(static_cast<double>(nearest_squared));
        if (nearest_squared < 0 || distance <= margin) continue;
        if (inside) {
          foreground.push_back(expected.Bin(image(y, x)));
        } else if (distance <= options.background_band_px) {
          background.push_back(expected.Bin(image(y, x)));
        }
      }
    }
    ASSERT_FALSE(foreground.empty());
    ASSERT_FALSE(background.empty());
    expected.Update(foreground, background, options.learning_rate_foreground,
                    options.learning_rate_background);
    EXPECT_EQ(model.histograms().foreground(), expected.foreground());
    EXPECT_EQ(model.histograms().background(), expected.background());
  }
}

TEST(DiscOverlapFractionTest, MatchesACountOfGridPoints) {
  EXPECT_DOUBLE_EQ(DiscOverlapFraction(0.0, 5.0), 1.0);
  EXPECT_DOUBLE_EQ(DiscOverlapFraction(10.0, 5.0), 0.0);
  EXPECT_DOUBLE_EQ(DiscOverlapFraction(25.0, 5.0), 0.0);
  // Against the share of a fine grid's points in a disc of radius 1 that are also in the disc
  // moved by d.
  for (double d : {0.1, 0.5, 1.0, 1.5, 1.9}) {
    const int n = 1000;
    int in_first = 0, in_both = 0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double x = -1.0 + (i + 0.5) * 2.0 / n, y = -1.0 + (j + 0.5) * 2.0 / n;
        if (x * x + y * y > 1.0) continue;
        ++in_first;
        if ((x - d) * (x - d) + y * y <= 1.0) ++in_both;
      }
    }
    EXPECT_NEAR(DiscOverlapFraction(d, 1.0), static_cast<double>(in_both) / in_first, 2e-3) << d;
    EXPECT_NEAR(DiscOverlapFraction(3.0 * d, 3.0), DiscOverlapFraction(d, 1.0), 1e-12) << d;
  }
}

// One local region, anchored to one model point, learned with the object at A and then with it
// at B, 100 px further right, where a patch of the object's colour stands 5 px beside it.
class LocalBackgroundMemoryTest : public ::testing::Test {
 protected:
  static constexpr int kWidth = 200, kHeight = 120;
  const cv::Vec3b kGrey{128, 128, 128};
  const cv::Vec3b kBlue{200, 60, 20};

  cv::Mat3b Image(int object_x) const {
    cv::Mat3b image(kHeight, kWidth, kGrey);
    image(cv::Rect(object_x, 50, 20, 20)).setTo(kBlue);
    image(cv::Rect(165, 40, 20, 40)).setTo(kBlue);  // the distractor
    return image;
  }
  static Silhouette SquareAt(int object_x) {
    Silhouette silhouette;
    silhouette.mask = cv::Mat1b::zeros(kHeight, kWidth);
    silhouette.mask(cv::Rect(object_x, 50, 20, 20)).setTo(255);
    ContourPoint point;
    point.pixel = Eigen::Vector2d(object_x + 20, 60);  // the square's right side
    point.normal = Eigen::Vector2d(1, 0);
    point.point_in_object = Eigen::Vector3d::Zero();
    silhouette.contour.push_back(point);
    return silhouette;
  }
  static LocalColorModel Model(LocalBackgroundMemory memory) {
    ColorModelOptions options;
    options.kind = ColorModelKind::kLocal;
    options.local_background_memory = memory;
    return LocalColorModel(options, 100.0);
  }
  // P_f of the distractor's colour after learning at A then B (or at B alone).
  double DistractorPosterior(LocalBackgroundMemory memory, bool learn_at_a) const {
    LocalColorModel model = Model(memory);
    if (learn_at_a) model.Update(Image(20), SquareAt(20));
    model.Update(Image(120), SquareAt(120));
    EXPECT_EQ(model.num_regions(), 1);
    return model.ForegroundPosteriors(Image(120), {{170, 60}})[0];
  }
};

TEST_F(LocalBackgroundMemoryTest, ARegionThatMovedAcrossTheImageForgetsItsOldBackground) {
  const double fresh = DistractorPosterior(LocalBackgroundMemory::kImage, false);
  EXPECT_GT(fresh, 0.5);  // the distractor shares the object's colour,
  EXPECT_LT(fresh, 0.9);  // but the background around B holds it too
  // Moved by more than a diameter: the background learned at A has no share any more.
  EXPECT_NEAR(DistractorPosterior(LocalBackgroundMemory::kImage, true), fresh, 1e-6);
  // RBOT's memory keeps 80 % of A's grey background, so the distractor looks like the object.
  EXPECT_GT(DistractorPosterior(LocalBackgroundMemory::kObject, true), 0.95);
}

TEST_F(LocalBackgroundMemoryTest, ARegionThatStayedBlendsAsRbot) {
  // At B the background holds the distractor with a share s of the samples: P_f = 1/(1 + s)
  // of its colour when learned from that frame alone.
  const double fresh = DistractorPosterior(LocalBackgroundMemory::kImage, false);
  const double share = 1.0 / fresh - 1.0;
  for (LocalBackgroundMemory memory :
       {LocalBackgroundMemory::kImage, LocalBackgroundMemory::kObject}) {
    LocalColorModel model = Model(memory);
    // First at B without the distractor, then at B with it: the region did not move, so both
    // memories blend the new background with α_b = 0.2, h_b(blue) = 0.2·s.
    cv::Mat3b without = Image(120);
    without(cv::Rect(165, 40, 20, 40)).setTo(kGrey);
    model.Update(without, SquareAt(120));
    model.Update(Image(120), SquareAt(120));
    EXPECT_NEAR(model.ForegroundPosteriors(Image(120), {{170, 60}})[0], 1.0 / (1.0 + 0.2 * share),
                1e-6);
  }
}

TEST(ColorModelFactoryTest, MakesTheRequestedKind) {
  ColorModelOptions options;
  EXPECT_NE(dynamic_cast<GlobalColorModel*>(MakeColorModel(options, 100.0).get()), nullptr);
  options.kind = ColorModelKind::kLocal;
  EXPECT_NE(dynamic_cast<LocalColorModel*>(MakeColorModel(options, 100.0).get()), nullptr);
}

TEST(ColorModelFactoryTest, RefineOptionsSwitchOnlyTheKind) {
  ColorModelOptions options;
  options.bins_per_channel = 16;
  options.refine_kind.reset();
  EXPECT_EQ(RefineColorModelOptions(options).kind, ColorModelKind::kGlobal);
  options.refine_kind = ColorModelKind::kLocal;
  const ColorModelOptions refine = RefineColorModelOptions(options);
  EXPECT_EQ(refine.kind, ColorModelKind::kLocal);
  EXPECT_FALSE(refine.refine_kind.has_value());
  EXPECT_EQ(refine.bins_per_channel, 16);
  EXPECT_NE(dynamic_cast<LocalColorModel*>(MakeColorModel(refine, 100.0).get()), nullptr);
}

}  // namespace
}  // namespace bcot

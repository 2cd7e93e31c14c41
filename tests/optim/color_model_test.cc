#include "bcot/optim/color_model.h"

#include <gtest/gtest.h>

#include <cmath>
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

  Silhouette silhouette_;
};

TEST_F(ColorModelSceneTest, GlobalPosteriorsDiscriminateObjectAndBackground) {
  GlobalColorModel model{ColorModelOptions()};
  EXPECT_FALSE(model.initialized());
  model.Update(image_, silhouette_);
  ASSERT_TRUE(model.initialized());
  double inside = 0.0, outside = 0.0;
  MeanPosteriors(model, &inside, &outside);
  EXPECT_GT(inside, 0.95);
  EXPECT_LT(outside, 0.05);
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
  double inside = 0.0, outside = 0.0;
  MeanPosteriors(*model, &inside, &outside);
  EXPECT_GT(inside, 0.95);
  EXPECT_LT(outside, 0.05);

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

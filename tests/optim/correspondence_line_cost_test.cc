#include "bcot/optim/correspondence_line_cost.h"

#include <ceres/gradient_checker.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bcot/optim/color_model.h"
#include "bcot/optim/correspondence_lines.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/optim/se3_manifold.h"
#include "bcot/render/sparse_viewpoint_model.h"
#include "region_test_scene.h"
#include "test_util.h"

namespace bcot {
namespace {

using test::GradientScenarios;
using test::Scenario;
using test::ScenarioCamera;
using test::SeededTwist;
using ::testing::HasSubstr;

class CorrespondenceLineTest : public test::SpoolCasterTest {
 protected:
  // Lines at T0 = `rig_from_objcentre0`, the colour model learned at T0 from `image`.
  static CorrespondenceLines MakeLines(const Camera& camera, const cv::Mat3b& image,
                                       const Eigen::Isometry3d& rig_from_objcentre0,
                                       const CorrespondenceLineOptions& options = {}) {
    const Eigen::Isometry3d cam_from_template =
        test::TestCamFromRig() * rig_from_objcentre0 * mesh_->objcentre_from_template();
    const Silhouette silhouette =
        RenderSilhouette(*caster_, camera, cam_from_template, RegionTemplateOptions().contour);
    GlobalColorModel color_model{ColorModelOptions()};
    color_model.Update(image, silhouette);
    StatusOr<CorrespondenceLines> lines =
        BuildCorrespondenceLines(*caster_, camera, test::TestCamFromRig(), rig_from_objcentre0,
                                 image, color_model, silhouette, options);
    BCOT_CHECK(lines.ok());
    return std::move(lines).value();
  }
};

TEST(CorrespondenceLineOptionsTest, ValidateListsEveryViolation) {
  EXPECT_TRUE(CorrespondenceLineOptions().Validate().ok());
  CorrespondenceLineOptions options;
  options.num_lines = 0;
  options.half_length_px = 0.5;
  options.amplitude = 0.5;
  options.max_sigma_px = 0.1;
  options.weight = -1.0;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"num_lines = 0", "half_length_px = 0.5", "amplitude = 0.5",
                           "max_sigma_px = 0.1", "weight = -1"});
}

TEST(FrameProblemOptionsTest, SparseEnergyNeedsAPositiveLineWeight) {
  FrameProblemOptions options;
  options.energy = RegionEnergy::kDense;
  options.lines.weight = 0.0;
  EXPECT_TRUE(options.Validate().ok());  // dense: the lines are unused
  options.energy = RegionEnergy::kCombined;
  const Status status = options.Validate();
  ASSERT_EQ(status.code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(status.message(), HasSubstr("lines.weight = 0"));
}

// A clean, blurred step at +1.3 px: the distribution's mean finds it to a small fraction of a
// pixel and its σ is below the ambiguity limit; no contrast gives a flat (wide) distribution;
// an all-foreground line peaks at its end and is rejected.
TEST(ContourDistributionTest, LocatesAStepAndFlagsAmbiguousLines) {
  const CorrespondenceLineOptions options;
  const double first = -10.0;
  std::vector<double> step, flat, foreground;
  for (int k = 0; k <= 20; ++k) {
    const double s = first + k;
    step.push_back(0.5 - 0.4 * std::tanh((s - 1.3) / 0.8));
    flat.push_back(0.5);
    foreground.push_back(0.9);
  }
  double mean = 0.0, sigma = 0.0;
  ASSERT_TRUE(ContourDistribution(step, first, options, &mean, &sigma));
  EXPECT_NEAR(mean, 1.3, 0.05);
  EXPECT_LT(sigma, options.max_sigma_px);
  ContourDistribution(flat, first, options, &mean, &sigma);
  EXPECT_GT(sigma, options.max_sigma_px);
  EXPECT_FALSE(ContourDistribution(foreground, first, options, &mean, &sigma));
}

// The distribution is the normalised p(d) ∝ Π_k [h_f·P_f + h_b·P_b] of the header: against a
// direct Σ_k log evaluation on random lines (seeded), including long lines whose products
// need renormalising and a near-½ amplitude.
TEST(ContourDistributionTest, MatchesTheSumOfLogTermsDefinition) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    CorrespondenceLineOptions options;
    options.scale_px = trial % 3 == 0 ? 2.0 : 1.0;
    options.hypothesis_subdivisions = 1 + trial % 4;
    options.amplitude = trial % 5 == 0 ? 0.4999 : 0.42;
    const int n = 3 + (trial * 37) % 300;
    std::vector<double> p_foreground(n);
    for (double& p : p_foreground) p = trial % 2 == 0 ? uniform(rng) : std::round(uniform(rng));
    const double first = -0.5 * n * options.scale_px;
    const double h = options.scale_px;
    const double step = h / options.hypothesis_subdivisions;
    const int num_hypotheses = (n - 3) * options.hypothesis_subdivisions + 1;
    std::vector<double> log_likelihood(num_hypotheses, 0.0);
    for (int j = 0; j < num_hypotheses; ++j) {
      const double d = first + h + j * step;
      for (int k = 0; k < n; ++k) {
        const double h_f =
            0.5 - options.amplitude * std::tanh((first + k * h - d) / (2.0 * options.slope_px));
        log_likelihood[j] +=
            std::log(h_f * p_foreground[k] + (1.0 - h_f) * (1.0 - p_foreground[k]));
      }
    }
    const double max_log = *std::max_element(log_likelihood.begin(), log_likelihood.end());
    double total = 0.0, first_moment = 0.0, second_moment = 0.0;
    for (int j = 0; j < num_hypotheses; ++j) {
      const double p = std::exp(log_likelihood[j] - max_log);
      const double d = first + h + j * step;
      total += p;
      first_moment += p * d;
      second_moment += p * d * d;
    }
    const double expected_mean = first_moment / total;
    const double expected_sigma =
        std::sqrt(std::max(0.0, second_moment / total - expected_mean * expected_mean));
    double mean = 0.0, sigma = 0.0;
    ContourDistribution(p_foreground, first, options, &mean, &sigma);
    EXPECT_NEAR(mean, expected_mean, 1e-7 * n) << "trial " << trial;
    EXPECT_NEAR(sigma, expected_sigma, 1e-5 * (1.0 + expected_sigma)) << "trial " << trial;
  }
}

// At the true pose the lines find the rendered boundary where the model puts it: μ ≈ 0.
TEST_F(CorrespondenceLineTest, LinesAtTheTruthMeasureNoOffset) {
  const Scenario scenario = GradientScenarios()[0];
  const Camera camera = ScenarioCamera(scenario);
  const cv::Mat3b image = test::RenderTestImage(*caster_, camera, scenario.cam_from_objcentre);
  const CorrespondenceLines lines =
      MakeLines(camera, image, test::RigFromObjcentre(scenario.cam_from_objcentre));
  ASSERT_GT(lines.lines.size(), 150u);
  std::vector<double> offsets;
  double signed_sum = 0.0;
  for (const CorrespondenceLine& line : lines.lines) {
    offsets.push_back(std::abs(line.mean_px));
    signed_sum += line.mean_px;
  }
  std::printf("mean signed mu %.3f px\n", signed_sum / offsets.size());
  std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
  std::printf("%zu lines of %d (short %d, off image %d, ambiguous %d), median |mu| %.3f px\n",
              lines.lines.size(), lines.candidates, lines.rejected_short, lines.rejected_off_image,
              lines.rejected_ambiguous, offsets[offsets.size() / 2]);
  EXPECT_LT(offsets[offsets.size() / 2], 0.2);
}

// Seen exactly from one of a sparse viewpoint model's viewpoints, at the model's distance, the
// lines along the model's points measure the boundary where the model puts it, like the lines
// along the rendered contour, and as many of them are kept.
TEST_F(CorrespondenceLineTest, LinesAlongAViewpointModelAtTheTruthMeasureNoOffset) {
  SparseViewpointModelOptions model_options;
  model_options.sphere_subdivisions = 2;
  model_options.image_size_px = 300;
  const SparseViewpointModel model = SparseViewpointModel::Build(*caster_, model_options);
  const Camera camera("test", 640, 480, 900.0, 900.0, 319.5, 239.5);
  const double distance =
      model_options.distance_factor * 0.5 * (mesh_->bbox_max() - mesh_->bbox_min()).norm();
  for (int index : {3, 50, 120}) {
    const Eigen::Isometry3d cam_from_template =
        LookAtCamFromObject(model.centre(), model.viewpoint(index).direction, distance);
    ASSERT_EQ(model.Nearest(cam_from_template), index);
    const Eigen::Isometry3d cam_from_objcentre =
        cam_from_template * mesh_->objcentre_from_template().inverse();
    const Eigen::Isometry3d rig_from_objcentre = test::RigFromObjcentre(cam_from_objcentre);
    const cv::Mat3b image = test::RenderTestImage(*caster_, camera, cam_from_objcentre);
    const Silhouette silhouette =
        RenderSilhouette(*caster_, camera, cam_from_template, RegionTemplateOptions().contour);
    GlobalColorModel color_model{ColorModelOptions()};
    color_model.Update(image, silhouette);
    const StatusOr<CorrespondenceLines> rendered =
        BuildCorrespondenceLines(*caster_, camera, test::TestCamFromRig(), rig_from_objcentre,
                                 image, color_model, silhouette);
    const StatusOr<CorrespondenceLines> from_model = BuildCorrespondenceLines(
        *caster_, camera, test::TestCamFromRig(), rig_from_objcentre, image, color_model,
        model.Project(index, camera, cam_from_template));
    ASSERT_TRUE(rendered.ok() && from_model.ok());
    std::vector<double> offsets;
    for (const CorrespondenceLine& line : from_model->lines) {
      offsets.push_back(std::abs(line.mean_px));
      // The model's anchor is its point's own projection.
      EXPECT_LT((line.projection0 - line.centre).norm(), 1e-9);
    }
    ASSERT_GT(offsets.size(), 0.9 * rendered->lines.size()) << "viewpoint " << index;
    std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
    EXPECT_LT(offsets[offsets.size() / 2], 0.2) << "viewpoint " << index;
  }
}

TEST(FrameProblemOptionsTest, ViewpointModelNeedsTheSparseEnergy) {
  FrameProblemOptions options;
  options.lines_from_viewpoint_model = true;
  options.energy = RegionEnergy::kSparse;
  EXPECT_TRUE(options.Validate().ok());
  options.energy = RegionEnergy::kCombined;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"lines_from_viewpoint_model = true", "energy = sparse"});
}

// ceres::GradientChecker through the Se3Manifold at the four poses of STYLE.md.
TEST_F(CorrespondenceLineTest, GradientCheckerAcceptsTheAnalyticJacobian) {
  Se3Manifold manifold;
  std::vector<const ceres::Manifold*> manifolds = {&manifold};
  ceres::NumericDiffOptions numeric_options;
  std::mt19937 rng(43);
  for (const Scenario& scenario : GradientScenarios()) {
    const Camera camera = ScenarioCamera(scenario);
    const cv::Mat3b image = test::RenderTestImage(*caster_, camera, scenario.cam_from_objcentre);
    const Eigen::Isometry3d rig_from_objcentre0 =
        test::RigFromObjcentre(scenario.cam_from_objcentre) * ExpSE3(SeededTwist(rng, 0.01, 2.0));
    auto lines =
        std::make_shared<const CorrespondenceLines>(MakeLines(camera, image, rig_from_objcentre0));
    ASSERT_GT(lines->lines.size(), 50u) << scenario.name;
    const CorrespondenceLineCostFunction cost(camera, test::TestCamFromRig(), lines, 0.7);
    ceres::GradientChecker checker(&cost, &manifolds, numeric_options);
    double worst = 0.0;
    for (int probe = 0; probe < 3; ++probe) {
      PoseParameters x =
          ToPoseParameters(rig_from_objcentre0 * ExpSE3(SeededTwist(rng, 0.02, 3.0)));
      const double* parameters[] = {x.data()};
      ceres::GradientChecker::ProbeResults results;
      EXPECT_TRUE(checker.Probe(parameters, 1e-6, &results))
          << scenario.name << " probe " << probe << ": max relative error "
          << results.maximum_relative_error << "\n"
          << results.error_log.substr(0, 2000);
      worst = std::max(worst, results.maximum_relative_error);
    }
    std::printf("[ %s ] %zu lines, worst relative Jacobian error %.2e\n", scenario.name.c_str(),
                lines->lines.size(), worst);
  }
}

// A cost over a range of the lines (the edge stage's block per line) gives exactly the rows of
// the cost over all of them: residuals and Jacobian (the latter to rounding: the ambient
// Jacobian is one matrix product over the block's rows, vectorised differently per row count).
TEST_F(CorrespondenceLineTest, LineRangesGiveTheRowsOfTheWholeCost) {
  const Scenario scenario = GradientScenarios().front();  // a copy: the list is a temporary
  const Camera camera = ScenarioCamera(scenario);
  const cv::Mat3b image = test::RenderTestImage(*caster_, camera, scenario.cam_from_objcentre);
  const Eigen::Isometry3d rig_from_objcentre0 = test::RigFromObjcentre(scenario.cam_from_objcentre);
  auto lines =
      std::make_shared<const CorrespondenceLines>(MakeLines(camera, image, rig_from_objcentre0));
  const int n = static_cast<int>(lines->lines.size());
  ASSERT_GT(n, 10);
  std::mt19937 rng(7);
  PoseParameters x = ToPoseParameters(rig_from_objcentre0 * ExpSE3(SeededTwist(rng, 0.02, 3.0)));
  const double* parameters[] = {x.data()};
  const CorrespondenceLineCostFunction whole(camera, test::TestCamFromRig(), lines, 0.7);
  std::vector<double> residuals(n), jacobian(n * kPoseAmbientSize);
  double* jacobians[] = {jacobian.data()};
  ASSERT_TRUE(whole.Evaluate(parameters, residuals.data(), jacobians));
  for (const auto& [first, count] : {std::pair{0, 1}, std::pair{n - 1, 1}, std::pair{3, 5}}) {
    const CorrespondenceLineCostFunction part(camera, test::TestCamFromRig(), lines, 0.7, first,
                                              count);
    ASSERT_EQ(part.num_residuals(), count);
    std::vector<double> part_residuals(count), part_jacobian(count * kPoseAmbientSize);
    double* part_jacobians[] = {part_jacobian.data()};
    ASSERT_TRUE(part.Evaluate(parameters, part_residuals.data(), part_jacobians));
    for (int i = 0; i < count; ++i) {
      EXPECT_EQ(part_residuals[i], residuals[first + i]) << first << "+" << i;
      for (int k = 0; k < kPoseAmbientSize; ++k) {
        const double expected = jacobian[(first + i) * kPoseAmbientSize + k];
        EXPECT_NEAR(part_jacobian[i * kPoseAmbientSize + k], expected,
                    1e-12 * (1.0 + std::abs(expected)));
      }
    }
  }
  // The default range is every line.
  EXPECT_EQ(
      CorrespondenceLineCostFunction(camera, test::TestCamFromRig(), lines, 1.0, 4).num_residuals(),
      n - 4);
}

class SparseEnergyConvergenceTest : public test::BunnyCasterTest,
                                    public ::testing::WithParamInterface<RegionEnergy> {};

// The acceptance test of the joint solver (multi_view_tracker_test.cc: binocular, 90° apart,
// 5° / 10 mm → < 0.1° / 0.2 mm with the annotation setting), run with the sparse and the
// combined energy at the same tolerances. And camera 0 alone, where depth and the rotations
// that move the silhouette little are weakly observed: < 0.5° / 1 mm. The dense energy, run
// through this same test on this scene, lands at 0.17–0.24° / 0.20–0.73 mm for these seeds
// (sparse measured 0.05–0.39° / 0.10–0.57 mm, combined 0.09–0.28° / 0.10–0.41 mm).
TEST_P(SparseEnergyConvergenceTest, RecoversAPerturbedFrame) {
  const test::BinocularScene scene;
  const std::vector<cv::Mat3b> images =
      test::RenderViews(*caster_, scene, scene.rig_from_objcentre, 11);
  MultiViewTrackerOptions options;
  options.frame.energy = GetParam();
  for (bool binocular : {true, false}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      std::vector<TrackedView> views = {{scene.camera0, scene.cam0_from_rig, 1.0}};
      if (binocular) views.push_back({scene.camera1, scene.cam1_from_rig, 1.0});
      StatusOr<std::unique_ptr<MultiViewTracker>> tracker =
          MultiViewTracker::Create(*caster_, std::move(views), options);
      ASSERT_TRUE(tracker.ok()) << tracker.status().message();
      Eigen::Isometry3d pose = test::Perturb(scene.rig_from_objcentre, seed);
      const std::vector<cv::Mat3b> used(images.begin(), images.begin() + (binocular ? 2 : 1));
      const StatusOr<FrameSummary> summary = (*tracker)->Initialize(used, &pose);
      ASSERT_TRUE(summary.ok()) << summary.status().message();
      std::printf("%s %s seed %u: %s, %d rounds, lines %d, error %.4f deg %.4f mm\n",
                  RegionEnergyName(GetParam()), binocular ? "binocular" : "monocular", seed,
                  FrameTerminationName(summary->termination), summary->rounds,
                  summary->views[0].lines, test::RotationErrorDeg(pose, scene.rig_from_objcentre),
                  test::TranslationErrorMm(pose, scene.rig_from_objcentre));
      EXPECT_TRUE(summary->usable()) << summary->message;
      EXPECT_GT(summary->views[0].lines, 100);
      EXPECT_THAT(pose, test::PoseNear(scene.rig_from_objcentre, binocular ? 0.1 : 0.5,
                                       binocular ? 0.2 : 1.0))
          << (binocular ? "binocular" : "monocular") << " seed " << seed;
    }
  }
}

// The same acceptance test, binocular, with the region rounds' lines along a sparse viewpoint
// model (a coarse one, 642 viewpoints about 8° apart, for the test's time; the edge stage
// renders the exact contour), the colour models learned from the rendered silhouette or along
// the model's contour.
TEST_F(SparseEnergyConvergenceTest, RecoversAPerturbedFrameFromAViewpointModel) {
  const test::BinocularScene scene;
  const std::vector<cv::Mat3b> images =
      test::RenderViews(*caster_, scene, scene.rig_from_objcentre, 11);
  SparseViewpointModelOptions model_options;
  model_options.sphere_subdivisions = 3;
  model_options.image_size_px = 300;
  // Built on demand, as the tracker makes it: the two views ask for viewpoints concurrently.
  const auto model = std::make_shared<const SparseViewpointModel>(
      SparseViewpointModel::BuildOnDemand(*caster_, model_options));
  MultiViewTrackerOptions options;
  options.frame.energy = RegionEnergy::kSparse;
  options.frame.lines_from_viewpoint_model = true;
  for (unsigned seed : {1u, 2u, 3u}) {
    options.color_samples =
        seed == 3u ? ColorSampleSource::kSilhouette : ColorSampleSource::kViewpointModel;
    StatusOr<std::unique_ptr<MultiViewTracker>> tracker = MultiViewTracker::Create(
        *caster_,
        {{scene.camera0, scene.cam0_from_rig, 1.0}, {scene.camera1, scene.cam1_from_rig, 1.0}},
        options, std::nullopt, model);
    ASSERT_TRUE(tracker.ok()) << tracker.status().message();
    Eigen::Isometry3d pose = test::Perturb(scene.rig_from_objcentre, seed);
    const StatusOr<FrameSummary> summary = (*tracker)->Initialize(images, &pose);
    ASSERT_TRUE(summary.ok()) << summary.status().message();
    std::printf(
        "viewpoint model seed %u, colours from the %s: %s, lines %d, error %.4f deg "
        "%.4f mm\n",
        seed, seed == 3u ? "silhouette" : "model", FrameTerminationName(summary->termination),
        summary->views[0].lines, test::RotationErrorDeg(pose, scene.rig_from_objcentre),
        test::TranslationErrorMm(pose, scene.rig_from_objcentre));
    EXPECT_TRUE(summary->usable()) << summary->message;
    EXPECT_GT(summary->views[0].lines, 100);
    EXPECT_THAT(pose, test::PoseNear(scene.rig_from_objcentre, 0.1, 0.2)) << "seed " << seed;
  }
  // Only the viewpoints near the two cameras' directions were rendered.
  EXPECT_GT(model->num_built(), 0);
  EXPECT_LT(model->num_built(), model->size() / 2);
}

INSTANTIATE_TEST_SUITE_P(Energies, SparseEnergyConvergenceTest,
                         ::testing::Values(RegionEnergy::kSparse, RegionEnergy::kCombined),
                         [](const ::testing::TestParamInfo<RegionEnergy>& info) {
                           return std::string(RegionEnergyName(info.param));
                         });

}  // namespace
}  // namespace bcot

#include "bcot/optim/frame_problem.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>

#include "region_test_scene.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

TEST(FrameProblemOptionsTest, DefaultsAreValid) {
  EXPECT_TRUE(FrameProblemOptions().Validate().ok());
}

TEST(FrameProblemOptionsTest, ValidateListsEveryViolation) {
  FrameProblemOptions options;
  options.rounds = 0;
  options.iterations = -1;
  options.pyramid_levels = 9;
  options.round_tolerance_mm = -1.0;
  options.coarse_check_min_shift_px = -3.0;
  options.region.band_px = 0.0;
  options.cost.heaviside_slope = -2.0;
  options.edge.redescending_rounds = -1;
  options.edge.redescending_scale = 0.0;
  test::ExpectErrorNaming(
      options.Validate(), StatusCode::kInvalidConfig,
      {"rounds = 0", "iterations = -1", "pyramid_levels = 9", "round_tolerance_mm = -1",
       "coarse_check_min_shift_px = -3", "band_px = 0", "heaviside_slope = -2",
       "redescending_rounds = -1", "redescending_scale = 0"});
}

class FrameProblemTest : public test::BunnyCasterTest {
 protected:
  // Teaches `model` the colours of `image`, seen by `camera` at `cam_from_rig`, with the object
  // at the truth of `scene`.
  static void LearnAtTruth(const test::BinocularScene& scene, const Camera& camera,
                           const Eigen::Isometry3d& cam_from_rig, const cv::Mat3b& image,
                           GlobalColorModel* model) {
    model->Update(image, RenderSilhouette(*caster_, camera,
                                          cam_from_rig * scene.rig_from_objcentre *
                                              mesh_->objcentre_from_template()));
  }

  // The scene's two views rendered at the truth with noise seed `seed`, and a global colour
  // model per view, learned there when `learned` says so (else left empty).
  struct SceneViews {
    test::BinocularScene scene;
    std::vector<cv::Mat3b> images;
    GlobalColorModel model0{ColorModelOptions()};
    GlobalColorModel model1{ColorModelOptions()};
    std::vector<FrameView> Views(double weight0 = 1.0, double weight1 = 1.0) const {
      return {{&scene.camera0, scene.cam0_from_rig, &images[0], &model0, weight0},
              {&scene.camera1, scene.cam1_from_rig, &images[1], &model1, weight1}};
    }
  };
  static std::unique_ptr<SceneViews> RenderScene(uint64_t seed, bool learn0 = true,
                                                 bool learn1 = true) {
    auto views = std::make_unique<SceneViews>();
    const test::BinocularScene& scene = views->scene;
    views->images = test::RenderViews(*caster_, scene, scene.rig_from_objcentre, seed);
    if (learn0)
      LearnAtTruth(scene, scene.camera0, scene.cam0_from_rig, views->images[0], &views->model0);
    if (learn1)
      LearnAtTruth(scene, scene.camera1, scene.cam1_from_rig, views->images[1], &views->model1);
    return views;
  }
};

// Starting at the truth with colour models learned there, the solve stays within the energy's
// own bias (pixel sampling, noise) of it and lowers the energy.
TEST_F(FrameProblemTest, StartingAtTheTruthStaysThere) {
  const std::unique_ptr<SceneViews> views = RenderScene(41);
  const test::BinocularScene& scene = views->scene;
  const FrameProblem problem(*caster_, FrameProblemOptions());
  Eigen::Isometry3d pose = scene.rig_from_objcentre;
  const FrameSummary summary = problem.Solve(views->Views(), &pose);
  ASSERT_TRUE(summary.usable()) << summary.message;
  EXPECT_GE(summary.rounds, 1);
  EXPECT_GT(summary.iterations, 0);
  EXPECT_THAT(pose, test::PoseNear(scene.rig_from_objcentre, 0.1, 0.1));
  ASSERT_EQ(summary.views.size(), 2u);
  EXPECT_GT(summary.views[0].energy, 0.0);
  EXPECT_GT(summary.views[1].energy, 0.0);
  EXPECT_NEAR(summary.final_energy, summary.views[0].energy + summary.views[1].energy,
              1e-9 * summary.final_energy);
}

// The views of a round (templates, edge lines) are linearised concurrently and added to the
// problem in view order, so the threads available change nothing, bit for bit.
TEST_F(FrameProblemTest, ViewsSolvedConcurrentlyGiveTheOneThreadResult) {
  const std::unique_ptr<SceneViews> views = RenderScene(43);
  const test::BinocularScene& scene = views->scene;
  FrameProblemOptions options;
  ASSERT_TRUE(options.edge.enabled);  // the edge stage's views run concurrently too
  const FrameProblem problem(*caster_, options);
  const Eigen::Isometry3d start =
      scene.rig_from_objcentre *
      Eigen::Isometry3d(Eigen::Translation3d(1.5, -1.0, 2.0) *
                        Eigen::AngleAxisd(0.03, Eigen::Vector3d(1, 2, 3).normalized()));
  auto solve = [&](int threads, Eigen::Isometry3d* pose) {
    *pose = start;
    FrameSummary summary;
    tbb::task_arena arena(threads);
    arena.execute([&] { summary = problem.Solve(views->Views(), pose); });
    return summary;
  };
  Eigen::Isometry3d one_thread, two_threads;
  const FrameSummary one = solve(1, &one_thread);
  const FrameSummary two = solve(2, &two_threads);
  ASSERT_TRUE(one.usable()) << one.message;
  ASSERT_TRUE(two.usable()) << two.message;
  EXPECT_TRUE(one_thread.matrix() == two_threads.matrix()) << one_thread.matrix() << "\n"
                                                           << two_threads.matrix();
  EXPECT_EQ(one.final_energy, two.final_energy);
  EXPECT_EQ(one.iterations, two.iterations);
  ASSERT_EQ(one.views.size(), two.views.size());
  for (size_t v = 0; v < one.views.size(); ++v) {
    EXPECT_EQ(one.views[v].pixels, two.views[v].pixels);
    EXPECT_GT(one.views[v].edge_lines, 0);
    EXPECT_EQ(one.views[v].edge_lines, two.views[v].edge_lines);
  }
  EXPECT_THAT(one_thread, test::PoseNear(scene.rig_from_objcentre, 0.1, 0.1));
}

TEST_F(FrameProblemTest, ObjectOutsideEveryViewIsNotVisibleAndLeavesThePose) {
  const test::BinocularScene scene;
  const cv::Mat3b image(scene.camera0.height, scene.camera0.width, cv::Vec3b(40, 90, 160));
  GlobalColorModel model{ColorModelOptions()};
  Eigen::Isometry3d behind = scene.rig_from_objcentre;
  behind.translation().z() = -500.0;  // behind camera 0
  Eigen::Isometry3d pose = behind;
  const FrameProblem problem(*caster_, FrameProblemOptions());
  const FrameSummary summary =
      problem.Solve({{&scene.camera0, scene.cam0_from_rig, &image, &model, 1.0}}, &pose);
  EXPECT_EQ(summary.termination, FrameTermination::kNotVisible);
  EXPECT_FALSE(summary.usable());
  EXPECT_THAT(summary.message, HasSubstr("outside every view"));
  EXPECT_TRUE(pose.isApprox(behind));
}

TEST_F(FrameProblemTest, ZeroWeightViewContributesNothing) {
  const std::unique_ptr<SceneViews> views = RenderScene(31, true, /*learn1=*/false);
  FrameProblemOptions options;
  options.rounds = 1;
  const FrameProblem problem(*caster_, options);
  Eigen::Isometry3d pose = views->scene.rig_from_objcentre;
  const FrameSummary summary = problem.Solve(views->Views(1.0, 0.0), &pose);
  ASSERT_TRUE(summary.usable()) << summary.message;
  EXPECT_GT(summary.views[0].pixels, 0);
  EXPECT_EQ(summary.views[1].pixels, 0);
  EXPECT_EQ(summary.views[1].energy, 0.0);
}

// The coarse check (frame_problem.h). The coarse levels get an inverted colour model (the
// object's colours counted as background and the rest as foreground), a stand-in for any
// coarse energy whose minimum lies elsewhere than the object: they pull the pose far away. The
// level-0 model is right, so the energy per term is lower at the start, the rounds start there
// and end at the truth; without the check they start from the coarse result and stay lost.
TEST_F(FrameProblemTest, CoarseLevelsPulledAwayAreRejectedByTheLevel0Energy) {
  const test::BinocularScene scene;
  const Eigen::Isometry3d& truth = scene.rig_from_objcentre;
  const cv::Mat3b image =
      test::RenderTestImage(*caster_, scene.camera0, scene.cam0_from_rig * truth, 7);
  const Silhouette silhouette = RenderSilhouette(
      *caster_, scene.camera0, scene.cam0_from_rig * truth * mesh_->objcentre_from_template());
  GlobalColorModel level0_model{ColorModelOptions()};
  level0_model.Update(image, silhouette);
  Silhouette inverted = silhouette;
  inverted.mask = 255 - silhouette.mask;
  GlobalColorModel coarse_model{ColorModelOptions()};
  coarse_model.Update(image, inverted);

  const Eigen::Isometry3d start =
      truth * Eigen::Isometry3d(Eigen::Translation3d(0.5, -0.5, 0.0) *
                                Eigen::AngleAxisd(0.01, Eigen::Vector3d(1, 2, 3).normalized()));
  // `min_shift_px` < 0: the check off.
  auto solve = [&](double min_shift_px, Eigen::Isometry3d* pose) {
    FrameProblemOptions options;
    options.rounds = 1;
    options.edge.enabled = false;
    options.coarse_check = min_shift_px >= 0.0;
    options.coarse_check_min_shift_px = std::max(min_shift_px, 0.0);
    EXPECT_EQ(options.pyramid_levels, 3);
    *pose = start;
    return FrameProblem(*caster_, options)
        .Solve({{&scene.camera0, scene.cam0_from_rig, &image, &coarse_model, 1.0, &level0_model}},
               pose);
  };
  Eigen::Isometry3d unchecked, checked, skipped;
  const FrameSummary unchecked_summary = solve(-1.0, &unchecked);
  const FrameSummary checked_summary = solve(3.0, &checked);
  // The coarse levels moved the object by far less than this: the check is skipped.
  const FrameSummary skipped_summary = solve(1e6, &skipped);
  for (const FrameSummary* summary : {&unchecked_summary, &checked_summary, &skipped_summary}) {
    ASSERT_TRUE(summary->usable()) << summary->message;
  }
  EXPECT_FALSE(unchecked_summary.coarse_checked || unchecked_summary.coarse_rejected);
  EXPECT_TRUE(checked_summary.coarse_checked && checked_summary.coarse_rejected);
  EXPECT_FALSE(skipped_summary.coarse_checked || skipped_summary.coarse_rejected);
  // One view: the rotation and the position across the line of sight (camera 0 is the rig
  // frame), not the depth, which one view measures less well.
  EXPECT_LT(RotationDistanceDeg(checked.linear(), truth.linear()), 0.5);
  EXPECT_LT((checked.translation() - truth.translation()).head<2>().norm(), 0.5);
  EXPECT_GT(RotationDistanceDeg(unchecked.linear(), truth.linear()), 10.0);
  EXPECT_TRUE(skipped.isApprox(unchecked, 1e-12));
}

}  // namespace
}  // namespace bcot

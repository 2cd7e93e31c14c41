#include "bcot/optim/frame_problem.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
  options.region.band_px = 0.0;
  options.cost.heaviside_slope = -2.0;
  const Status status = options.Validate();
  ASSERT_EQ(status.code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(status.message(), HasSubstr("rounds = 0"));
  EXPECT_THAT(status.message(), HasSubstr("iterations = -1"));
  EXPECT_THAT(status.message(), HasSubstr("pyramid_levels = 9"));
  EXPECT_THAT(status.message(), HasSubstr("round_tolerance_mm = -1"));
  EXPECT_THAT(status.message(), HasSubstr("band_px = 0"));
  EXPECT_THAT(status.message(), HasSubstr("heaviside_slope = -2"));
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
};

// Starting at the truth with colour models learned there, the solve stays within the energy's
// own bias (pixel sampling, noise) of it and lowers the energy.
TEST_F(FrameProblemTest, StartingAtTheTruthStaysThere) {
  const test::BinocularScene scene;
  const std::vector<cv::Mat3b> images =
      test::RenderViews(*caster_, scene, scene.rig_from_objcentre, 41);
  GlobalColorModel model0{ColorModelOptions()};
  GlobalColorModel model1{ColorModelOptions()};
  LearnAtTruth(scene, scene.camera0, scene.cam0_from_rig, images[0], &model0);
  LearnAtTruth(scene, scene.camera1, scene.cam1_from_rig, images[1], &model1);
  const FrameProblem problem(*caster_, FrameProblemOptions());
  Eigen::Isometry3d pose = scene.rig_from_objcentre;
  const FrameSummary summary =
      problem.Solve({{&scene.camera0, scene.cam0_from_rig, &images[0], &model0, 1.0},
                     {&scene.camera1, scene.cam1_from_rig, &images[1], &model1, 1.0}},
                    &pose);
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
  const test::BinocularScene scene;
  const std::vector<cv::Mat3b> images =
      test::RenderViews(*caster_, scene, scene.rig_from_objcentre, 31);
  GlobalColorModel model0{ColorModelOptions()};
  GlobalColorModel model1{ColorModelOptions()};
  LearnAtTruth(scene, scene.camera0, scene.cam0_from_rig, images[0], &model0);
  FrameProblemOptions options;
  options.rounds = 1;
  const FrameProblem problem(*caster_, options);
  Eigen::Isometry3d pose = scene.rig_from_objcentre;
  const FrameSummary summary =
      problem.Solve({{&scene.camera0, scene.cam0_from_rig, &images[0], &model0, 1.0},
                     {&scene.camera1, scene.cam1_from_rig, &images[1], &model1, 0.0}},
                    &pose);
  ASSERT_TRUE(summary.usable()) << summary.message;
  EXPECT_GT(summary.views[0].pixels, 0);
  EXPECT_EQ(summary.views[1].pixels, 0);
  EXPECT_EQ(summary.views[1].energy, 0.0);
}

}  // namespace
}  // namespace bcot

#include "bcot/render/symmetry_detection.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>

#include "test_meshes.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

std::optional<RotationalSymmetry> Detect(const Mesh& mesh,
                                         std::vector<SymmetryCandidate>* candidates = nullptr) {
  const RayCaster caster(mesh);
  StatusOr<std::optional<RotationalSymmetry>> found =
      DetectRotationalSymmetry(caster, SymmetryDetectionOptions(), candidates);
  EXPECT_TRUE(found.ok()) << found.status().message();
  // The numbers docs/method.md quotes ("Symmetric objects").
  for (const SymmetryCandidate& candidate :
       candidates != nullptr ? *candidates : std::vector<SymmetryCandidate>()) {
    std::printf("candidate: moment gap %.2g, silhouette displacement %.2g of the diameter\n",
                candidate.moment_gap, candidate.displacement);
  }
  return found.ok() ? *found : std::nullopt;
}

TEST(SymmetryDetectionTest, FindsACylindersAxisOffTheOrigin) {
  // A 64-sided cylinder along z, tilted and moved away from the template origin.
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.linear() = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1.0, 2.0, 0.5).normalized()).matrix();
  moved.translation() = Eigen::Vector3d(30.0, -12.0, 55.0);
  const Mesh cylinder = test::MakeCylinder(20.0, 35.0, 64).Transformed(moved);
  std::vector<SymmetryCandidate> candidates;
  const std::optional<RotationalSymmetry> symmetry = Detect(cylinder, &candidates);
  ASSERT_TRUE(symmetry.has_value());
  const Eigen::Vector3d axis = moved.linear() * Eigen::Vector3d::UnitZ();
  EXPECT_GT(std::abs(symmetry->axis.dot(axis)), 1.0 - 1e-9);
  // The point lies on the axis.
  EXPECT_LT((symmetry->point - moved.translation()).cross(axis).norm(), 1e-6);
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_LT(candidates[0].displacement, 1e-3);
}

TEST(SymmetryDetectionTest, FindsTheSpoolAndRejectsTheGearBunnyAndBox) {
  const StatusOr<Mesh> spool = Mesh::Load(test::SourcePath("data/meshes/spool.off"), 100.0);
  ASSERT_TRUE(spool.ok());
  EXPECT_TRUE(Detect(*spool).has_value());

  // The pinion's moments about its axis agree (an n-fold part), so it is a candidate; its
  // teeth show in the silhouettes.
  const StatusOr<Mesh> pinion = Mesh::Load(test::SourcePath("data/meshes/pinion.off"), 100.0);
  ASSERT_TRUE(pinion.ok());
  std::vector<SymmetryCandidate> candidates;
  EXPECT_FALSE(Detect(*pinion, &candidates).has_value());
  ASSERT_FALSE(candidates.empty());
  for (const SymmetryCandidate& candidate : candidates) {
    EXPECT_GT(candidate.displacement, 10.0 * SymmetryDetectionOptions().tolerance);
  }

  const StatusOr<Mesh> bunny = Mesh::Load(test::SourcePath("data/meshes/bunny.obj"), 1000.0);
  ASSERT_TRUE(bunny.ok());
  EXPECT_FALSE(Detect(*bunny, &candidates).has_value());
  EXPECT_TRUE(candidates.empty());  // three distinct moments: nothing rendered

  // A cube's three moments agree: three candidates, none symmetric.
  EXPECT_FALSE(Detect(test::MakeBox(20.0), &candidates).has_value());
  EXPECT_EQ(candidates.size(), 3u);
}

TEST(SymmetryDetectionTest, FewFacetsAreVisible) {
  // An 8-sided prism is not a body of revolution at this tolerance.
  std::vector<SymmetryCandidate> candidates;
  EXPECT_FALSE(Detect(test::MakeCylinder(20.0, 35.0, 8), &candidates).has_value());
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_GT(candidates[0].displacement, SymmetryDetectionOptions().tolerance);
}

TEST(SymmetryDetectionTest, ValidateNamesEveryViolation) {
  SymmetryDetectionOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.moment_tolerance = 0.0;
  options.tolerance = 0.5;
  options.image_px = 10;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"moment_tolerance = 0", "tolerance = 0.5", "image_px = 10"});
}

}  // namespace
}  // namespace bcot

#include "bcot/render/sparse_viewpoint_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "test_meshes.h"
#include "test_util.h"

namespace bcot {
namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

// Small and quick: 42 viewpoints of 200 px.
SparseViewpointModelOptions SmallOptions() {
  SparseViewpointModelOptions options;
  options.sphere_subdivisions = 1;
  options.points_per_viewpoint = 120;
  options.image_size_px = 200;
  return options;
}

double HalfDiagonal(const Mesh& mesh) { return 0.5 * (mesh.bbox_max() - mesh.bbox_min()).norm(); }

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegPerRad;
}

TEST(GeodesicSphereTest, CountsAndCoverage) {
  std::mt19937 rng(7);
  for (int k = 0; k <= 3; ++k) {
    const std::vector<Eigen::Vector3d> directions = GeodesicSphere(k);
    ASSERT_EQ(directions.size(), 10u * (1u << (2 * k)) + 2u) << "k = " << k;
    for (const Eigen::Vector3d& d : directions) EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    // Every direction lies within the circumradius of its spherical triangle, which is below the
    // triangle's longest edge, itself at most the icosahedron's edge (63.43°) over 2^k.
    const double bound_deg = 63.44 / (1 << k);
    double covering_deg = 0.0;
    for (int trial = 0; trial < 500; ++trial) {
      const Eigen::Vector3d u = test::RandomUnitVector(rng);
      double nearest = 180.0;
      for (const Eigen::Vector3d& d : directions) nearest = std::min(nearest, AngleDeg(u, d));
      covering_deg = std::max(covering_deg, nearest);
    }
    EXPECT_LT(covering_deg, bound_deg) << "k = " << k;
    // No two directions coincide.
    double closest_pair_deg = 180.0;
    for (size_t i = 0; i < directions.size(); ++i) {
      for (size_t j = i + 1; j < directions.size(); ++j) {
        closest_pair_deg = std::min(closest_pair_deg, AngleDeg(directions[i], directions[j]));
      }
    }
    EXPECT_GT(closest_pair_deg, 0.5 * bound_deg) << "k = " << k;
  }
}

TEST(SparseViewpointModelOptionsTest, ListsEveryViolation) {
  SparseViewpointModelOptions options;
  EXPECT_TRUE(options.Validate().ok());
  options.sphere_subdivisions = 7;
  options.points_per_viewpoint = 0;
  options.distance_factor = 1.0;
  options.image_size_px = 32;
  test::ExpectErrorNaming(options.Validate(), StatusCode::kInvalidConfig,
                          {"sphere_subdivisions = 7", "points_per_viewpoint = 0",
                           "distance_factor = 1", "image_size_px = 32"});
}

// Seen from one of its viewpoints, at the model's distance and with any roll, the model's
// projected points lie on the exact contour, with its normals.
TEST(SparseViewpointModelTest, ProjectedPointsLieOnTheExactContour) {
  const Mesh torus = test::MakeTorus(40.0, 12.0, 96, 48);
  const RayCaster caster(torus);
  const SparseViewpointModelOptions options = SmallOptions();
  const SparseViewpointModel model = SparseViewpointModel::Build(caster, options);
  ASSERT_EQ(model.size(), 42);
  const Camera camera("test", 640, 512, 900.0, 900.0, 319.5, 255.5);
  const double distance = options.distance_factor * HalfDiagonal(torus);
  for (int index : {0, 7, 23, 41}) {
    const Viewpoint& viewpoint = model.viewpoint(index);
    ASSERT_GE(viewpoint.points.size(), 100u);
    const Eigen::Isometry3d cam_from_template =
        LookAtCamFromObject(model.centre(), viewpoint.direction, distance, 0.3 * index);
    EXPECT_EQ(model.Nearest(cam_from_template), index);
    ContourOptions contour_options;
    contour_options.sample_spacing_px = 0.25;
    const std::vector<ContourPoint> exact =
        caster.ExtractContour(camera, cam_from_template, contour_options);
    const std::vector<ProjectedContourPoint> projected =
        model.Project(index, camera, cam_from_template);
    ASSERT_EQ(projected.size(), viewpoint.points.size());
    double worst_px = 0.0, worst_normal_deg = 0.0;
    int compared = 0;
    for (const ProjectedContourPoint& p : projected) {
      // Where the silhouette is thinner than a correspondence line's shortest side
      // (CorrespondenceLineOptions::min_side_px, 3 px) the two contours may trace a sliver
      // differently (parts thinner than the coarse step); no line is built there.
      if (std::min(p.inside_px, p.outside_px) < 3.0) continue;
      ++compared;
      const ContourPoint* nearest = nullptr;
      double nearest_px = std::numeric_limits<double>::infinity();
      for (const ContourPoint& c : exact) {
        const double d = (c.pixel - p.pixel).norm();
        if (d < nearest_px) {
          nearest_px = d;
          nearest = &c;
        }
      }
      worst_px = std::max(worst_px, nearest_px);
      worst_normal_deg =
          std::max(worst_normal_deg,
                   std::acos(std::clamp(nearest->normal.dot(p.normal), -1.0, 1.0)) * kDegPerRad);
    }
    EXPECT_GT(compared, 90) << "viewpoint " << index;
    // Half the exact contour's sample spacing plus the two contours' bisection precision.
    EXPECT_LT(worst_px, 0.2) << "viewpoint " << index;
    // The normals of a 96 × 48 facet torus turn by 3.75° per facet.
    EXPECT_LT(worst_normal_deg, 6.0) << "viewpoint " << index;
  }
}

// Seen along its axis, a torus's outer contour has the tube (2·minor) inside and nothing
// outside; the hole's contour has the tube inside and the hole (2·(major − minor)) outside.
TEST(SparseViewpointModelTest, ExtentsAlongTheAxisOfATorus) {
  const double major = 40.0, minor = 12.0;
  SparseViewpointModelOptions options = SmallOptions();
  options.sphere_subdivisions = 0;
  const Eigen::Vector3d axis = GeodesicSphere(0)[0];
  Eigen::Isometry3d rotate = Eigen::Isometry3d::Identity();
  rotate.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
  const Mesh torus = test::MakeTorus(major, minor, 96, 48).Transformed(rotate);
  const RayCaster caster(torus);
  const SparseViewpointModel model = SparseViewpointModel::Build(caster, options);
  int outer = 0, hole = 0;
  for (const ViewpointContourPoint& p : model.viewpoint(0).points) {
    const Eigen::Vector3d point = p.point.cast<double>() - model.centre();
    const double from_axis = (point - point.dot(axis) * axis).norm();
    // The virtual camera is 8 half-diagonals away: perspective moves the contours by < 3 %.
    EXPECT_NEAR(p.inside_mm, 2.0 * minor, 0.05 * 2.0 * minor);
    if (from_axis > major) {
      ++outer;
      EXPECT_EQ(p.outside_mm, std::numeric_limits<float>::infinity());
    } else {
      ++hole;
      EXPECT_NEAR(p.outside_mm, 2.0 * (major - minor), 0.05 * 2.0 * (major - minor));
    }
    EXPECT_LT(std::abs(p.normal.cast<double>().dot(axis)), 1e-6);
  }
  EXPECT_GT(outer, 30);
  EXPECT_GT(hole, 15);
}

TEST(SparseViewpointModelTest, SerializeRoundTripAndBadFiles) {
  const Mesh box = test::MakeBox(Eigen::Vector3d(20.0, 12.0, 7.0));
  const RayCaster caster(box);
  SparseViewpointModelOptions options = SmallOptions();
  options.sphere_subdivisions = 0;
  const SparseViewpointModel model = SparseViewpointModel::Build(caster, options);
  const std::string key = SparseViewpointModel::CacheKey(box, options);
  EXPECT_EQ(model.key(), key);
  const std::string bytes = model.Serialize();

  StatusOr<SparseViewpointModel> read = SparseViewpointModel::Deserialize(bytes, key, "m.bin");
  ASSERT_TRUE(read.ok()) << read.status().message();
  ASSERT_EQ(read->size(), model.size());
  EXPECT_EQ(read->centre(), model.centre());
  for (int i = 0; i < model.size(); ++i) {
    EXPECT_EQ(read->viewpoint(i).direction, model.viewpoint(i).direction);
    ASSERT_EQ(read->viewpoint(i).points.size(), model.viewpoint(i).points.size());
    for (size_t j = 0; j < model.viewpoint(i).points.size(); ++j) {
      const ViewpointContourPoint& a = model.viewpoint(i).points[j];
      const ViewpointContourPoint& b = read->viewpoint(i).points[j];
      EXPECT_EQ(a.point, b.point);
      EXPECT_EQ(a.normal, b.normal);
      EXPECT_EQ(a.inside_mm, b.inside_mm);
      EXPECT_EQ(a.outside_mm, b.outside_mm);
    }
  }

  // Another mesh or other options give another key, and the file is refused.
  SparseViewpointModelOptions other = options;
  other.points_per_viewpoint += 1;
  const std::string other_key = SparseViewpointModel::CacheKey(box, other);
  EXPECT_NE(other_key, key);
  EXPECT_NE(SparseViewpointModel::CacheKey(test::MakeBox(20.0), options), key);
  test::ExpectErrorNaming(SparseViewpointModel::Deserialize(bytes, other_key, "m.bin").status(),
                          StatusCode::kInvalidInput, {"m.bin", "expected " + other_key});
  test::ExpectErrorNaming(SparseViewpointModel::Deserialize("not a model", key, "m.bin").status(),
                          StatusCode::kInvalidInput, {"m.bin", "not a sparse viewpoint model"});
  // Every truncation is an error, never a crash or a partial model.
  for (size_t length : {size_t{10}, size_t{40}, bytes.size() / 2, bytes.size() - 1}) {
    test::ExpectErrorNaming(
        SparseViewpointModel::Deserialize(bytes.substr(0, length), key, "m.bin").status(),
        StatusCode::kInvalidInput, {"m.bin"});
  }
  test::ExpectErrorNaming(SparseViewpointModel::Deserialize(bytes + "x", key, "m.bin").status(),
                          StatusCode::kInvalidInput, {"m.bin", "1 bytes after"});
}

// A model built on demand has its directions at once and builds a viewpoint only when it is
// used, once, whichever threads ask for it; each is the one Build() makes.
TEST(SparseViewpointModelTest, OnDemandBuildsEachUsedViewpointOnceAsBuildDoes) {
  const Mesh torus = test::MakeTorus(40.0, 12.0, 48, 24);
  const RayCaster caster(torus);
  const SparseViewpointModelOptions options = SmallOptions();
  const SparseViewpointModel built = SparseViewpointModel::Build(caster, options);
  EXPECT_EQ(built.num_built(), built.size());

  const SparseViewpointModel lazy = SparseViewpointModel::BuildOnDemand(caster, options);
  ASSERT_EQ(lazy.size(), built.size());
  EXPECT_EQ(lazy.num_built(), 0);
  EXPECT_EQ(lazy.key(), built.key());
  const Eigen::Isometry3d cam_from_template =
      LookAtCamFromObject(torus.bbox_center(), Eigen::Vector3d(0.3, -0.5, 0.8).normalized(), 300.0);
  const int nearest = lazy.Nearest(cam_from_template);
  EXPECT_EQ(nearest, built.Nearest(cam_from_template));
  EXPECT_EQ(lazy.num_built(), 0);

  // Eight threads ask for the same three viewpoints at once.
  const std::vector<int> used = {nearest, (nearest + 1) % lazy.size(), (nearest + 7) % lazy.size()};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&lazy, &used, t] {
      for (size_t k = 0; k < used.size(); ++k) lazy.viewpoint(used[(k + t) % used.size()]);
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(lazy.num_built(), 3);
  for (const int i : used) {
    const Viewpoint& a = lazy.viewpoint(i);
    const Viewpoint& b = built.viewpoint(i);
    EXPECT_EQ(a.direction, b.direction);
    ASSERT_EQ(a.points.size(), b.points.size()) << "viewpoint " << i;
    ASSERT_FALSE(a.points.empty());
    for (size_t k = 0; k < a.points.size(); ++k) {
      EXPECT_EQ(a.points[k].point, b.points[k].point);
      EXPECT_EQ(a.points[k].normal, b.points[k].normal);
      EXPECT_EQ(a.points[k].inside_mm, b.points[k].inside_mm);
      EXPECT_EQ(a.points[k].outside_mm, b.points[k].outside_mm);
    }
  }
  // Serialize builds the rest: the same bytes as the model built at once.
  EXPECT_EQ(lazy.Serialize(), built.Serialize());
  EXPECT_EQ(lazy.num_built(), lazy.size());
}

}  // namespace
}  // namespace bcot

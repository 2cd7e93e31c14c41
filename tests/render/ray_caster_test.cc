#include "bcot/render/ray_caster.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include "test_meshes.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

// ---------------------------------------------------------------------------------------------
// Procedural meshes and analytic references
// ---------------------------------------------------------------------------------------------

Camera TestCamera() { return Camera("test", 640, 512, 600.0, 600.0, 320.0, 256.0); }

Camera DistortedCamera() {
  Camera camera = TestCamera();
  camera.distortion = {-0.25, 0.08, 0.0015, -0.001, -0.01};
  return camera;
}

Eigen::Isometry3d CamFromObject(
    const Eigen::Vector3d& translation_mm,
    const Eigen::AngleAxisd& rotation = Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitX())) {
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
  cam_from_object.linear() = rotation.toRotationMatrix();
  cam_from_object.translation() = translation_mm;
  return cam_from_object;
}

// Icosahedron subdivided `subdivisions` times, vertices on the sphere of `radius` (mm).
Mesh MakeIcosphere(double radius, int subdivisions) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> vertices = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                           {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                           {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<Eigen::Vector3i> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& v : vertices) v.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      vertices.push_back((vertices[a] + vertices[b]).normalized());
      const int index = static_cast<int>(vertices.size()) - 1;
      midpoint.emplace(key, index);
      return index;
    };
    std::vector<Eigen::Vector3i> finer;
    finer.reserve(4 * faces.size());
    for (const auto& f : faces) {
      const int ab = middle(f[0], f[1]);
      const int bc = middle(f[1], f[2]);
      const int ca = middle(f[2], f[0]);
      finer.emplace_back(f[0], ab, ca);
      finer.emplace_back(f[1], bc, ab);
      finer.emplace_back(f[2], ca, bc);
      finer.emplace_back(ab, bc, ca);
    }
    faces = std::move(finer);
  }
  std::vector<Eigen::Vector3f> scaled;
  for (const auto& v : vertices) scaled.push_back((radius * v).cast<float>());
  return Mesh::FromArrays(std::move(scaled), std::move(faces));
}

// Radius of the largest origin-centred ball inside a convex mesh (min distance to face planes):
// the tessellated sphere lies between this ball and its circumscribed one.
double InscribedRadius(const Mesh& mesh) {
  double radius = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3i& t : mesh.triangles()) {
    const Eigen::Vector3d a = mesh.vertices()[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices()[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices()[t[2]].cast<double>();
    radius = std::min(radius, std::abs((b - a).cross(c - a).normalized().dot(a)));
  }
  return radius;
}

// A closed square frame in the xy plane: outer half side `outer`, square hole of half side
// `inner`, thickness 2·`half_thickness` along z. Watertight (16 vertices, 32 triangles).
Mesh MakeSquareFrame(double outer, double inner, double half_thickness) {
  const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  std::vector<Eigen::Vector3f> vertices;
  for (double z : {-half_thickness, half_thickness}) {
    for (double half : {outer, inner}) {
      for (const auto& c : corners) vertices.emplace_back(c[0] * half, c[1] * half, z);
    }
  }
  // Rings of 4 vertices: front outer 0, front inner 4, back outer 8, back inner 12.
  std::vector<Eigen::Vector3i> triangles;
  auto band = [&](int ring_a, int ring_b) {
    for (int k = 0; k < 4; ++k) {
      const int k1 = (k + 1) % 4;
      triangles.emplace_back(ring_a + k, ring_a + k1, ring_b + k1);
      triangles.emplace_back(ring_a + k, ring_b + k1, ring_b + k);
    }
  };
  band(0, 4);   // front face
  band(8, 12);  // back face
  band(0, 8);   // outer wall
  band(4, 12);  // inner wall
  return Mesh::FromArrays(std::move(vertices), std::move(triangles));
}

using test::MakeBox;
using test::MakeTorus;

Mesh SpoolMesh() {
  const StatusOr<Mesh> spool = Mesh::Load(test::SourcePath("data/meshes/spool.off"));
  BCOT_CHECK(spool.ok());
  return spool->Transformed(spool->objcentre_from_template(), 150.0 / spool->diameter());
}

// Distance (mm) from a sphere's centre to the camera ray through `pixel`, minus the radius:
// zero exactly on the sphere's silhouette (also off-axis and through lens distortion, where
// the silhouette is not a circle), negative inside it.
double SilhouetteFunction(const Camera& camera, const Eigen::Vector3d& centre_in_cam, double radius,
                          const Eigen::Vector2d& pixel) {
  const Eigen::Vector3d ray = camera.PixelToRay(pixel).normalized();
  return (centre_in_cam - centre_in_cam.dot(ray) * ray).norm() - radius;
}

// Signed offset (px) along `normal` from `pixel` to the analytic silhouette of the sphere.
double OffsetToSphereSilhouette(const Camera& camera, const Eigen::Vector3d& centre_in_cam,
                                double radius, const Eigen::Vector2d& pixel,
                                const Eigen::Vector2d& normal) {
  double inside = -2.0;
  double outside = 2.0;
  auto f = [&](double d) {
    return SilhouetteFunction(camera, centre_in_cam, radius, pixel + d * normal);
  };
  if (!(f(inside) < 0.0 && f(outside) > 0.0)) return std::numeric_limits<double>::infinity();
  for (int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (inside + outside);
    (f(middle) < 0.0 ? inside : outside) = middle;
  }
  return 0.5 * (inside + outside);
}

double ReprojectionErrorPx(const Camera& camera, const Eigen::Isometry3d& cam_from_object,
                           const ContourPoint& point) {
  return (camera.Project(cam_from_object * point.point_in_object) - point.pixel).norm();
}

int CountNonZero(const cv::Mat1b& mask) { return mask.empty() ? 0 : cv::countNonZero(mask); }

// ---------------------------------------------------------------------------------------------
// Options
// ---------------------------------------------------------------------------------------------

TEST(RenderOptionsTest, DefaultsAreValid) {
  EXPECT_TRUE(RenderOptions().Validate().ok());
  EXPECT_TRUE(ContourOptions().Validate().ok());
}

TEST(RenderOptionsTest, ListsEveryViolation) {
  RenderOptions render;
  render.roi = cv::Rect(0, 0, -4, 10);
  render.margin_px = -1;
  render.samples_per_axis = 0;
  test::ExpectErrorNaming(
      render.Validate(), StatusCode::kInvalidConfig,
      {"roi", "margin_px = -1, must be >= 0", "samples_per_axis = 0, must be in [1, 16]"});

  ContourOptions contour;
  contour.coarse_step_px = 0;
  contour.sample_spacing_px = -1.0;
  contour.precision_px = 0.0;
  contour.margin_px = -2;
  test::ExpectErrorNaming(
      contour.Validate(), StatusCode::kInvalidConfig,
      {"coarse_step_px = 0, must be >= 1", "sample_spacing_px = -1",
       "precision_px = 0, must be in [1e-6, 0.5]", "margin_px = -2, must be >= 0"});
}

// ---------------------------------------------------------------------------------------------
// Render
// ---------------------------------------------------------------------------------------------

class SphereTest : public ::testing::Test {
 protected:
  static constexpr double kRadius = 50.0;
  static constexpr double kDistance = 500.0;
  // Six subdivisions: 81,920 triangles; the polyhedron is within 0.003 px of the sphere here.
  SphereTest() : mesh_(MakeIcosphere(kRadius, 6)), caster_(mesh_) {
    inscribed_radius_ = InscribedRadius(mesh_);
  }
  // On-axis silhouette radius (px) of a ball of radius r at distance Z: f·r / sqrt(Z² − r²).
  static double SilhouetteRadiusPx(double r) {
    return 600.0 * r / std::sqrt(kDistance * kDistance - r * r);
  }

  Mesh mesh_;
  RayCaster caster_;
  double inscribed_radius_ = 0.0;
};

TEST_F(SphereTest, TessellationIsFine) {
  EXPECT_GT(inscribed_radius_, kRadius * (1.0 - 1e-4));
  EXPECT_LT(SilhouetteRadiusPx(kRadius) - SilhouetteRadiusPx(inscribed_radius_), 0.01);
}

TEST_F(SphereTest, OnAxisDepthNormalAndArea) {
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({0, 0, kDistance});
  const RenderedView view = caster_.Render(camera, cam_from_object);
  const double r = SilhouetteRadiusPx(kRadius);

  // The default roi is the projected bounding box (±f·R/(Z−R) = ±66.7 px) plus 2 px.
  EXPECT_EQ(view.roi, cv::Rect(320 - 69, 256 - 69, 139, 139));
  ASSERT_EQ(view.mask.size(), view.roi.size());
  ASSERT_EQ(view.depth.size(), view.roi.size());

  // Centre pixel (320, 256) is on the optical axis: depth Z − R up to the tessellation.
  const int row = 256 - view.roi.y;
  const int col = 320 - view.roi.x;
  ASSERT_EQ(view.mask(row, col), 255);
  EXPECT_GE(view.depth(row, col), kDistance - kRadius - 1e-3);
  EXPECT_LE(view.depth(row, col), kDistance - inscribed_radius_ + 1e-3);
  const cv::Vec3f normal = view.normal_in_cam(row, col);
  EXPECT_NEAR(cv::norm(normal), 1.0, 1e-5);
  EXPECT_LT(normal[2], -0.999);  // faces the camera, within one facet's tilt
  const cv::Vec3f point = view.point_in_object(row, col);
  EXPECT_NEAR(point[2], view.depth(row, col) - kDistance, 1e-3);  // object z = camera z − Z
  EXPECT_GE(view.triangle_id(row, col), 0);

  // Area: pixel count vs π r² (pixel quantisation of a 60 px circle: well below 1 %).
  const double area = CountNonZero(view.mask);
  EXPECT_NEAR(area / (kPi * r * r), 1.0, 0.01);

  // Silhouette radius along the image axes: the extreme mask pixels.
  int min_col = view.mask.cols, max_col = -1;
  for (int c = 0; c < view.mask.cols; ++c) {
    if (view.mask(row, c)) {
      min_col = std::min(min_col, c);
      max_col = std::max(max_col, c);
    }
  }
  EXPECT_EQ(max_col + view.roi.x, 320 + static_cast<int>(std::floor(r)));
  EXPECT_EQ(min_col + view.roi.x, 320 - static_cast<int>(std::floor(r)));

  // Missed pixels carry the documented fill values.
  EXPECT_EQ(view.mask(0, 0), 0);
  EXPECT_EQ(view.depth(0, 0), 0.0f);
  EXPECT_EQ(view.triangle_id(0, 0), -1);
  EXPECT_EQ(view.normal_in_cam(0, 0), cv::Vec3f(0, 0, 0));
}

// Poses and cameras far beyond any real scene make rays Embree cannot take (it asserts and aborts
// on components beyond ~1.8e18). They are not cast: the object is simply not seen.
TEST_F(SphereTest, AbsurdPosesAndCamerasRenderNothingInsteadOfAborting) {
  const Camera camera = TestCamera();
  for (const double distance : {1e17, 1e20, 1e39, 1e308}) {
    const RenderedView view = caster_.Render(camera, CamFromObject({0, 0, distance}));
    EXPECT_EQ(cv::countNonZero(view.mask), 0) << distance;
    EXPECT_TRUE(caster_.ExtractContour(camera, CamFromObject({distance, 0, kDistance})).empty())
        << distance;
  }
  Camera tiny_focal = camera;
  tiny_focal.fy = 1e-300;
  const RenderedView view = caster_.Render(tiny_focal, CamFromObject({0, 0, kDistance}));
  EXPECT_LT(cv::countNonZero(view.mask), camera.width * camera.height);
}

TEST_F(SphereTest, SupersampledAreaAndCoverageMatchOneSample) {
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({23.0, -17.0, kDistance});
  RenderOptions one;
  one.roi = caster_.ProjectedBoundingBox(camera, cam_from_object, 2);
  RenderOptions four = one;
  four.samples_per_axis = 4;
  const RenderedView view1 = caster_.Render(camera, cam_from_object, one);
  const RenderedView view4 = caster_.Render(camera, cam_from_object, four);
  ASSERT_EQ(view4.mask.rows, 4 * view1.mask.rows);
  ASSERT_EQ(view4.mask.cols, 4 * view1.mask.cols);
  EXPECT_EQ(view4.samples_per_axis, 4);

  // Coverage per pixel from the 4×4 sub-samples.
  cv::Mat1f coverage;
  cv::resize(cv::Mat1f(view4.mask) / 255.0f, coverage, view1.mask.size(), 0, 0, cv::INTER_AREA);
  // Interior and exterior pixels (all 3×3 neighbours alike at 1×) are fully covered / empty.
  int interior = 0;
  for (int r = 1; r + 1 < view1.mask.rows; ++r) {
    for (int c = 1; c + 1 < view1.mask.cols; ++c) {
      const int sum = cv::countNonZero(view1.mask(cv::Rect(c - 1, r - 1, 3, 3)));
      if (sum == 9) {
        EXPECT_FLOAT_EQ(coverage(r, c), 1.0f) << r << "," << c;
        ++interior;
      } else if (sum == 0) {
        EXPECT_FLOAT_EQ(coverage(r, c), 0.0f) << r << "," << c;
      }
    }
  }
  EXPECT_GT(interior, 1000);
  // Total areas agree; the supersampled one is closer to the analytic ellipse area, which for
  // this small offset is within 0.3 % of the on-axis π r².
  const double area1 = CountNonZero(view1.mask);
  const double area4 = CountNonZero(view4.mask) / 16.0;
  EXPECT_NEAR(area4 / area1, 1.0, 0.01);
  const double r = SilhouetteRadiusPx(kRadius);
  EXPECT_NEAR(area4 / (kPi * r * r), 1.0, 0.005);

  // Sub-sample (i, j) of pixel (u, v) sits at (u − ½ + (i + ½)/4, v − ½ + (j + ½)/4): check
  // the documented convention against single rays along the boundary.
  int checked = 0;
  for (int r4 = 0; r4 < view4.mask.rows; r4 += 3) {
    for (int c4 = 0; c4 < view4.mask.cols; c4 += 3) {
      const Eigen::Vector2d position(view4.roi.x - 0.5 + (c4 + 0.5) / 4.0,
                                     view4.roi.y - 0.5 + (r4 + 0.5) / 4.0);
      const bool hit = caster_.Intersect(camera, cam_from_object, position).has_value();
      EXPECT_EQ(hit, view4.mask(r4, c4) == 255) << position.transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST_F(SphereTest, RenderAgreesWithSingleRays) {
  for (const Camera& camera : {TestCamera(), DistortedCamera()}) {
    const Eigen::Isometry3d cam_from_object = CamFromObject(
        {-140.0, 90.0, 600.0}, Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
    const RenderedView view = caster_.Render(camera, cam_from_object);
    ASSERT_FALSE(view.roi.empty());
    int hits = 0;
    for (int r = 0; r < view.mask.rows; ++r) {
      for (int c = 0; c < view.mask.cols; ++c) {
        const Eigen::Vector2d pixel(view.roi.x + c, view.roi.y + r);
        if ((r * 7 + c * 3) % 11 != 0) continue;  // a deterministic subset
        const auto hit = caster_.Intersect(camera, cam_from_object, pixel);
        ASSERT_EQ(hit.has_value(), view.mask(r, c) == 255) << pixel.transpose();
        if (!hit) continue;
        ++hits;
        const cv::Vec3f p = view.point_in_object(r, c);
        const Eigen::Vector3d point_in_object(p[0], p[1], p[2]);
        EXPECT_LT((point_in_object - *hit).norm(), 1e-3);
        const Eigen::Vector3d point_in_cam = cam_from_object * point_in_object;
        // t along (x, y, 1) is camera z, with distortion too.
        EXPECT_NEAR(view.depth(r, c), point_in_cam.z(), 1e-3);
        // The point projects back onto the pixel centre it was rendered for.
        EXPECT_LT((camera.Project(point_in_cam) - pixel).norm(), 1e-3);
        // On the sphere surface, and the normal faces the camera.
        EXPECT_NEAR(point_in_object.norm(), kRadius, kRadius - inscribed_radius_ + 1e-3);
        const cv::Vec3f n = view.normal_in_cam(r, c);
        EXPECT_LT(Eigen::Vector3d(n[0], n[1], n[2]).dot(point_in_cam), 0.0);
      }
    }
    EXPECT_GT(hits, 500);
  }
}

TEST_F(SphereTest, RenderIntoReusedViewEqualsFreshRender) {
  const Camera camera = TestCamera();
  RenderOptions options;
  options.roi = cv::Rect(200, 150, 240, 200);  // fixed size: buffers are reused
  RenderedView reused;
  for (const double x : {-30.0, 0.0, 25.0}) {
    const Eigen::Isometry3d cam_from_object = CamFromObject({x, 10.0, kDistance});
    caster_.Render(camera, cam_from_object, options, &reused);
    const uchar* mask_data = reused.mask.data;
    const RenderedView fresh = caster_.Render(camera, cam_from_object, options);
    EXPECT_EQ(cv::norm(reused.mask, fresh.mask, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(reused.depth, fresh.depth, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(reused.normal_in_cam, fresh.normal_in_cam, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(reused.point_in_object, fresh.point_in_object, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(reused.triangle_id, fresh.triangle_id, cv::NORM_INF), 0.0);
    caster_.Render(camera, cam_from_object, options, &reused);
    EXPECT_EQ(reused.mask.data, mask_data);  // no reallocation
  }
}

// Leaving images out changes nothing in the others; without any, the occlusion-ray mask is
// the closest-hit mask.
TEST_F(SphereTest, RenderingASubsetOfImagesMatchesTheFullRender) {
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({12.0, -8.0, kDistance});
  const RenderedView full = caster_.Render(camera, cam_from_object);
  RenderOptions points_only;
  points_only.depth = false;
  points_only.normal_in_cam = false;
  points_only.triangle_id = false;
  RenderedView view = caster_.Render(camera, cam_from_object, points_only);
  EXPECT_EQ(view.roi, full.roi);
  EXPECT_EQ(cv::norm(view.mask, full.mask, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(view.point_in_object, full.point_in_object, cv::NORM_INF), 0.0);
  EXPECT_TRUE(view.depth.empty() && view.normal_in_cam.empty() && view.triangle_id.empty());
  RenderOptions mask_only = points_only;
  mask_only.point_in_object = false;
  caster_.Render(camera, cam_from_object, mask_only, &view);  // releases the points
  EXPECT_EQ(cv::norm(view.mask, full.mask, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(view.mask), 1000);
  EXPECT_TRUE(view.point_in_object.empty());
}

// With a point stride the mask is the full render's everywhere and the geometry is the full
// render's on the stride grid (image coordinates multiples of the stride), misses elsewhere.
TEST_F(SphereTest, StridedGeometryMatchesTheFullRenderOnItsGrid) {
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({-21.0, 13.0, kDistance});
  const RenderedView full = caster_.Render(camera, cam_from_object);
  for (const int stride : {2, 3, 8}) {
    RenderOptions options;
    options.point_stride_px = stride;
    const RenderedView view = caster_.Render(camera, cam_from_object, options);
    ASSERT_EQ(view.roi, full.roi);
    EXPECT_EQ(view.point_stride_px, stride);
    EXPECT_EQ(cv::norm(view.mask, full.mask, cv::NORM_INF), 0.0) << stride;
    int on_grid_hits = 0;
    for (int r = 0; r < view.mask.rows; ++r) {
      for (int c = 0; c < view.mask.cols; ++c) {
        const bool on_grid = (view.roi.x + c) % stride == 0 && (view.roi.y + r) % stride == 0;
        if (on_grid) {
          EXPECT_NEAR(cv::norm(view.point_in_object(r, c) - full.point_in_object(r, c)), 0.0, 1e-3);
          EXPECT_EQ(view.triangle_id(r, c), full.triangle_id(r, c));
          on_grid_hits += view.mask(r, c) != 0;
        } else {
          EXPECT_EQ(view.triangle_id(r, c), -1);
          EXPECT_EQ(view.depth(r, c), 0.0f);
        }
      }
    }
    EXPECT_GT(on_grid_hits, 1000 / (stride * stride));
  }
  RenderOptions invalid;
  invalid.point_stride_px = 2;
  invalid.samples_per_axis = 2;
  EXPECT_FALSE(invalid.Validate().ok());
}

// mask_everywhere = false (for masks taken from the contour): the mask is traced only where the
// geometry is, on the stride grid, and equals the full render's there.
TEST_F(SphereTest, StridedMaskOnlyOnItsGrid) {
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({-21.0, 13.0, kDistance});
  const RenderedView full = caster_.Render(camera, cam_from_object);
  RenderOptions options;
  options.point_stride_px = 4;
  options.mask_everywhere = false;
  const RenderedView view = caster_.Render(camera, cam_from_object, options);
  ASSERT_EQ(view.roi, full.roi);
  int on_grid_hits = 0;
  for (int r = 0; r < view.mask.rows; ++r) {
    for (int c = 0; c < view.mask.cols; ++c) {
      const bool on_grid = (view.roi.x + c) % 4 == 0 && (view.roi.y + r) % 4 == 0;
      EXPECT_EQ(view.mask(r, c), on_grid ? full.mask(r, c) : 0) << r << ", " << c;
      on_grid_hits += on_grid && view.mask(r, c) != 0;
    }
  }
  EXPECT_GT(on_grid_hits, 1000 / 16);
  RenderOptions nothing_traced;
  nothing_traced.mask_everywhere = false;
  nothing_traced.depth = nothing_traced.normal_in_cam = nothing_traced.point_in_object =
      nothing_traced.triangle_id = false;
  const Status status = nothing_traced.Validate();
  EXPECT_EQ(status.code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(status.message(), HasSubstr("mask_everywhere = false"));
}

TEST(CubeTest, FrontFaceDepthAndNormal) {
  const Mesh cube = MakeBox(50.0);
  const RayCaster caster(cube);
  const Camera camera = TestCamera();
  const RenderedView view = caster.Render(camera, CamFromObject({0, 0, 500}));
  // Only the face z = −50 (camera depth 450) is visible from the axis; it spans
  // ±600·50/450 = ±66.67 px, i.e. pixels 254..386 by 190..322: 133² pixels.
  EXPECT_EQ(CountNonZero(view.mask), 133 * 133);
  for (int r = 0; r < view.mask.rows; ++r) {
    for (int c = 0; c < view.mask.cols; ++c) {
      if (!view.mask(r, c)) continue;
      ASSERT_NEAR(view.depth(r, c), 450.0f, 1e-3);
      const cv::Vec3f n = view.normal_in_cam(r, c);
      ASSERT_NEAR(n[0], 0.0f, 1e-6);
      ASSERT_NEAR(n[1], 0.0f, 1e-6);
      ASSERT_NEAR(n[2], -1.0f, 1e-6);
      ASSERT_NEAR(view.point_in_object(r, c)[2], -50.0f, 1e-3);
      ASSERT_GE(view.triangle_id(r, c), 0);
      ASSERT_LT(view.triangle_id(r, c), 12);
    }
  }
}

TEST(CubeTest, RotatedFacesDepthAndNormals) {
  const Mesh cube = MakeBox(50.0);
  const RayCaster caster(cube);
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object =
      CamFromObject({10, -5, 480}, Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized()));
  const RenderedView view = caster.Render(camera, cam_from_object);
  std::set<int> faces_seen;
  for (int r = 0; r < view.mask.rows; ++r) {
    for (int c = 0; c < view.mask.cols; ++c) {
      if (!view.mask(r, c)) continue;
      const cv::Vec3f p = view.point_in_object(r, c);
      const Eigen::Vector3d point_in_object(p[0], p[1], p[2]);
      // On a face: the largest coordinate is ±50; the face normal is that axis.
      int axis;
      const double extent = point_in_object.cwiseAbs().maxCoeff(&axis);
      ASSERT_NEAR(extent, 50.0, 1e-3);
      Eigen::Vector3d face_normal = Eigen::Vector3d::Zero();
      face_normal[axis] = point_in_object[axis] > 0 ? 1.0 : -1.0;
      faces_seen.insert(axis * 2 + (point_in_object[axis] > 0));
      const Eigen::Vector3d expected_normal = cam_from_object.linear() * face_normal;
      const cv::Vec3f n = view.normal_in_cam(r, c);
      // Skip pixels on a cube edge, where the face of the hit is ambiguous by 1e-3 mm.
      if ((point_in_object.cwiseAbs().array() > 50.0 - 1e-2).count() > 1) continue;
      ASSERT_LT((Eigen::Vector3d(n[0], n[1], n[2]) - expected_normal).norm(), 1e-5);
      ASSERT_NEAR(view.depth(r, c), (cam_from_object * point_in_object).z(), 1e-3);
    }
  }
  EXPECT_EQ(faces_seen.size(), 3u);  // a corner view shows three faces
}

// ---------------------------------------------------------------------------------------------
// Projected bounding box, degenerate poses
// ---------------------------------------------------------------------------------------------

TEST(ProjectedBoundingBoxTest, ContainsTheSilhouette) {
  const Mesh spool = SpoolMesh();
  const RayCaster caster(spool);
  for (const Camera& camera : {TestCamera(), DistortedCamera()}) {
    const Eigen::Isometry3d cam_from_object = CamFromObject(
        {60, -40, 450}, Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 0.5, 0.2).normalized()));
    RenderOptions full;
    full.roi = cv::Rect(0, 0, camera.width, camera.height);
    const RenderedView view = caster.Render(camera, cam_from_object, full);
    const cv::Rect box = caster.ProjectedBoundingBox(camera, cam_from_object, 0);
    ASSERT_GT(CountNonZero(view.mask), 1000);
    EXPECT_EQ(CountNonZero(view.mask), CountNonZero(view.mask(box).clone()));
    // Not absurdly loose either: the bbox of a box around the spool.
    EXPECT_LT(box.area(), 4 * CountNonZero(view.mask));
  }
}

TEST(ProjectedBoundingBoxTest, BehindStraddlingAndOutside) {
  const Mesh sphere = MakeIcosphere(50.0, 3);
  const RayCaster caster(sphere);
  const Camera camera = TestCamera();
  EXPECT_TRUE(caster.ProjectedBoundingBox(camera, CamFromObject({0, 0, -500}), 2).empty());
  EXPECT_EQ(caster.ProjectedBoundingBox(camera, CamFromObject({0, 0, 10}), 2),
            cv::Rect(0, 0, 640, 512));
  EXPECT_TRUE(caster.ProjectedBoundingBox(camera, CamFromObject({5000, 0, 500}), 2).empty());
}

TEST(RayCasterTest, ObjectBehindCamera) {
  const Mesh sphere = MakeIcosphere(50.0, 3);
  const RayCaster caster(sphere);
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({0, 0, -500});
  const RenderedView view = caster.Render(camera, cam_from_object);
  EXPECT_TRUE(view.roi.empty());
  EXPECT_TRUE(view.mask.empty());
  EXPECT_TRUE(view.depth.empty());
  EXPECT_TRUE(caster.ExtractContour(camera, cam_from_object).empty());
  EXPECT_FALSE(caster.Intersect(camera, cam_from_object, {320, 256}).has_value());
  // An explicit roi is still rendered, and sees nothing.
  RenderOptions options;
  options.roi = cv::Rect(100, 100, 50, 40);
  const RenderedView explicit_view = caster.Render(camera, cam_from_object, options);
  EXPECT_EQ(explicit_view.mask.size(), cv::Size(50, 40));
  EXPECT_EQ(CountNonZero(explicit_view.mask), 0);
}

TEST(RayCasterTest, CameraInsideTheObject) {
  // The box straddles the camera plane: the whole image is rendered (inside faces), and no
  // silhouette is visible.
  const Mesh sphere = MakeIcosphere(50.0, 3);
  const RayCaster caster(sphere);
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({0, 0, 0});
  const RenderedView view = caster.Render(camera, cam_from_object);
  EXPECT_EQ(view.roi, cv::Rect(0, 0, 640, 512));
  EXPECT_EQ(CountNonZero(view.mask), 640 * 512);
  EXPECT_TRUE(caster.ExtractContour(camera, cam_from_object).empty());
}

TEST(RayCasterTest, EmptyMesh) {
  const RayCaster caster(Mesh::FromArrays({}, {}));
  const Camera camera = TestCamera();
  EXPECT_TRUE(caster.Render(camera, CamFromObject({0, 0, 500})).mask.empty());
  EXPECT_TRUE(caster.ExtractContour(camera, CamFromObject({0, 0, 500})).empty());
}

TEST(RayCasterTest, Movable) {
  RayCaster a(MakeBox(50.0));
  RayCaster b(std::move(a));
  EXPECT_EQ(b.mesh().triangles().size(), 12u);
  RayCaster c(MakeIcosphere(10.0, 1));
  c = std::move(b);
  EXPECT_EQ(c.mesh().triangles().size(), 12u);
  EXPECT_TRUE(c.Intersect(TestCamera(), CamFromObject({0, 0, 500}), {320, 256}).has_value());
}

// ---------------------------------------------------------------------------------------------
// Contours
// ---------------------------------------------------------------------------------------------

// Every point's model point reprojects onto its pixel, and the normal separates a hit (half a
// pixel inside) from a miss (half a pixel outside). Returns the fraction of points passing the
// normal check.
double CheckContourBasics(const RayCaster& caster, const Camera& camera,
                          const Eigen::Isometry3d& cam_from_object,
                          const std::vector<ContourPoint>& contour) {
  int good_normals = 0;
  for (const ContourPoint& point : contour) {
    EXPECT_LT(ReprojectionErrorPx(camera, cam_from_object, point), 0.05) << point.pixel.transpose();
    EXPECT_NEAR(point.normal.norm(), 1.0, 1e-9);
    EXPECT_TRUE(camera.InImage(point.pixel));
    const bool outside_misses =
        !caster.Intersect(camera, cam_from_object, point.pixel + 0.5 * point.normal);
    const bool inside_hits =
        caster.Intersect(camera, cam_from_object, point.pixel - 0.5 * point.normal).has_value();
    good_normals += outside_misses && inside_hits;
  }
  return contour.empty() ? 0.0 : static_cast<double>(good_normals) / contour.size();
}

TEST_F(SphereTest, OnAxisContourOnAnalyticSilhouette) {
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({0, 0, kDistance});
  const ContourOptions options;
  const std::vector<ContourPoint> contour =
      caster_.ExtractContour(camera, cam_from_object, options);
  const double r_outer = SilhouetteRadiusPx(kRadius);
  const double r_inner = SilhouetteRadiusPx(inscribed_radius_);
  // One closed contour, sampled about every pixel along the traced polyline.
  EXPECT_GT(contour.size(), 2 * kPi * r_outer * 0.9);
  EXPECT_LT(contour.size(), 2 * kPi * r_outer * 1.5);
  double max_error = 0.0;
  double max_reprojection = 0.0;
  for (const ContourPoint& point : contour) {
    EXPECT_EQ(point.contour_id, 0);
    EXPECT_FALSE(point.is_hole);
    const Eigen::Vector2d offset = point.pixel - Eigen::Vector2d(320, 256);
    const double radius = offset.norm();
    // The polyhedral silhouette lies between those of the inscribed and circumscribed balls;
    // the bisection leaves at most precision_px / 2.
    const double slack = 0.5 * options.precision_px + 1e-3;
    EXPECT_GE(radius, r_inner - slack);
    EXPECT_LE(radius, r_outer + slack);
    max_error = std::max(max_error, std::abs(radius - r_outer));
    max_reprojection =
        std::max(max_reprojection, ReprojectionErrorPx(camera, cam_from_object, point));
    EXPECT_GT(point.normal.dot(offset / radius), 0.999) << point.pixel.transpose();
    EXPECT_GE(point.point_in_object.norm(), inscribed_radius_ - 1e-3);
    EXPECT_LE(point.point_in_object.norm(), kRadius + 1e-3);
  }
  EXPECT_LT(max_error, 0.05);
  EXPECT_LE(max_reprojection, 0.5 * options.precision_px + 1e-3);
  EXPECT_EQ(CheckContourBasics(caster_, camera, cam_from_object, contour), 1.0);
}

struct SphereCase {
  const char* name;
  bool distortion;
  Eigen::Vector3d centre_in_cam;
};

class SphereSilhouetteTest : public SphereTest, public ::testing::WithParamInterface<SphereCase> {};

// Off-axis the silhouette is an ellipse, and through distortion no conic at all; the exact
// test is that the ray through each contour pixel is tangent to the sphere.
TEST_P(SphereSilhouetteTest, ContourOnExactSilhouette) {
  const SphereCase& param = GetParam();
  const Camera camera = param.distortion ? DistortedCamera() : TestCamera();
  const Eigen::Isometry3d cam_from_object =
      CamFromObject(param.centre_in_cam, Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  const ContourOptions options;
  const std::vector<ContourPoint> contour =
      caster_.ExtractContour(camera, cam_from_object, options);
  ASSERT_GT(contour.size(), 100u);
  const double slack = 0.5 * options.precision_px + 1e-3;
  double max_error = 0.0;
  for (const ContourPoint& point : contour) {
    const double to_outer =
        OffsetToSphereSilhouette(camera, param.centre_in_cam, kRadius, point.pixel, point.normal);
    const double to_inner = OffsetToSphereSilhouette(camera, param.centre_in_cam, inscribed_radius_,
                                                     point.pixel, point.normal);
    // Outside the inscribed ball's silhouette, inside the circumscribed one's.
    EXPECT_GE(to_outer, -slack) << point.pixel.transpose();
    EXPECT_LE(to_inner, slack) << point.pixel.transpose();
    max_error = std::max(max_error, std::abs(to_outer));
    // Normal: the gradient direction of the silhouette function.
    const double h = 1e-3;
    const Eigen::Vector2d gradient(SilhouetteFunction(camera, param.centre_in_cam, kRadius,
                                                      point.pixel + Eigen::Vector2d(h, 0)) -
                                       SilhouetteFunction(camera, param.centre_in_cam, kRadius,
                                                          point.pixel - Eigen::Vector2d(h, 0)),
                                   SilhouetteFunction(camera, param.centre_in_cam, kRadius,
                                                      point.pixel + Eigen::Vector2d(0, h)) -
                                       SilhouetteFunction(camera, param.centre_in_cam, kRadius,
                                                          point.pixel - Eigen::Vector2d(0, h)));
    EXPECT_GT(point.normal.dot(gradient.normalized()), 0.998) << point.pixel.transpose();
  }
  EXPECT_LT(max_error, 0.05);
  EXPECT_EQ(CheckContourBasics(caster_, camera, cam_from_object, contour), 1.0);
}

INSTANTIATE_TEST_SUITE_P(
    Poses, SphereSilhouetteTest,
    ::testing::Values(SphereCase{"OffAxis", false, {150.0, -100.0, 600.0}},
                      SphereCase{"Near", false, {-40.0, 30.0, 260.0}},
                      SphereCase{"DistortedCentre", true, {0.0, 0.0, 500.0}},
                      SphereCase{"DistortedCorner", true, {230.0, 170.0, 650.0}}),
    [](const ::testing::TestParamInfo<SphereCase>& info) { return info.param.name; });

TEST_F(SphereTest, PartiallyOutsideTheImage) {
  const Camera camera = TestCamera();
  // Centre projects to (−4, 4): about a quarter of the disc is in the image.
  const Eigen::Vector3d centre_in_cam(-270.0, -210.0, 500.0);
  const Eigen::Isometry3d cam_from_object = CamFromObject(centre_in_cam);
  const RenderedView view = caster_.Render(camera, cam_from_object);
  EXPECT_EQ(view.roi.tl(), cv::Point(0, 0));
  EXPECT_TRUE((view.roi & cv::Rect(0, 0, 640, 512)) == view.roi);
  EXPECT_GT(CountNonZero(view.mask), 500);

  const ContourOptions options;
  const std::vector<ContourPoint> contour =
      caster_.ExtractContour(camera, cam_from_object, options);
  // Visible arc of a ~75 px radius circle: well over 60 px, under half the circumference.
  EXPECT_GT(contour.size(), 60u);
  EXPECT_LT(contour.size(), 250u);
  for (const ContourPoint& point : contour) {
    // No points along the image border: every point is on the true silhouette.
    EXPECT_LT(std::abs(OffsetToSphereSilhouette(camera, centre_in_cam, kRadius, point.pixel,
                                                point.normal)),
              0.05)
        << point.pixel.transpose();
  }
  EXPECT_EQ(CheckContourBasics(caster_, camera, cam_from_object, contour), 1.0);
}

TEST(ContourTest, SquareFrameHasOuterAndHoleContours) {
  // Frame face-on at 500 mm: the outer silhouette is the front face's outer square
  // (±50 mm at z = 495 → ±60.606 px), the see-through hole is bounded by the back face's inner
  // square (±25 mm at z = 505 → ±29.703 px). Exact polygons, so no tessellation excuse.
  const Mesh frame = MakeSquareFrame(50.0, 25.0, 5.0);
  const RayCaster caster(frame);
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({0, 0, 500});
  const std::vector<ContourPoint> contour = caster.ExtractContour(camera, cam_from_object);
  const double outer_px = 600.0 * 50.0 / 495.0;
  const double hole_px = 600.0 * 25.0 / 505.0;
  std::set<int> outer_ids, hole_ids;
  int checked = 0;
  for (const ContourPoint& point : contour) {
    (point.is_hole ? hole_ids : outer_ids).insert(point.contour_id);
    const Eigen::Vector2d offset = point.pixel - Eigen::Vector2d(320, 256);
    const double half_side = point.is_hole ? hole_px : outer_px;
    // Away from corners: on a side, with the axis normal (into the hole for the hole).
    int axis;
    const double chebyshev = offset.cwiseAbs().maxCoeff(&axis);
    if (offset.cwiseAbs().minCoeff() > half_side - 1.5) continue;
    ++checked;
    EXPECT_NEAR(chebyshev, half_side, 0.02) << point.pixel.transpose();
    Eigen::Vector2d expected_normal = Eigen::Vector2d::Zero();
    expected_normal[axis] = (offset[axis] > 0 ? 1.0 : -1.0) * (point.is_hole ? -1.0 : 1.0);
    EXPECT_GT(point.normal.dot(expected_normal), 0.999)
        << point.pixel.transpose() << " n " << point.normal.transpose();
  }
  EXPECT_EQ(outer_ids.size(), 1u);
  EXPECT_EQ(hole_ids.size(), 1u);
  EXPECT_NE(*outer_ids.begin(), *hole_ids.begin());
  EXPECT_GT(checked, static_cast<int>(0.8 * 8 * (outer_px + hole_px)));
  // Also at the corners, where the normal is the bisector.
  EXPECT_EQ(CheckContourBasics(caster, camera, cam_from_object, contour), 1.0);
}

TEST(ContourTest, TorusHoleNormalsPointIntoTheHole) {
  const Mesh torus = MakeTorus(40.0, 12.0, 160, 48);
  const RayCaster caster(torus);
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object =
      CamFromObject({15, -10, 500}, Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitX()));
  const std::vector<ContourPoint> contour = caster.ExtractContour(camera, cam_from_object);
  const Eigen::Vector2d centre = camera.Project(cam_from_object.translation());
  std::set<int> outer_ids, hole_ids;
  for (const ContourPoint& point : contour) {
    (point.is_hole ? hole_ids : outer_ids).insert(point.contour_id);
    const Eigen::Vector2d away = (point.pixel - centre).normalized();
    // A torus tilted by 14°: the silhouettes are close to ellipses around the centre.
    if (point.is_hole) {
      EXPECT_LT(point.normal.dot(away), -0.8) << point.pixel.transpose();
    } else {
      EXPECT_GT(point.normal.dot(away), 0.8) << point.pixel.transpose();
    }
  }
  EXPECT_EQ(outer_ids.size(), 1u);
  EXPECT_EQ(hole_ids.size(), 1u);
  EXPECT_EQ(CheckContourBasics(caster, camera, cam_from_object, contour), 1.0);
}

// ExtractContour reading its coarse grid from a render's mask (RenderSilhouette's way) finds
// the contour it traces itself, point for point: the grid's samples are that mask's pixel
// centres, cast with the same rays. Also through distortion, at a point stride (the mask then
// mixes occlusion and closest-hit rays) and for a hole.
TEST(ContourTest, CoarseGridFromARenderedMaskGivesTheSameContour) {
  const Mesh spool = SpoolMesh();
  const Mesh torus = MakeTorus(40.0, 12.0, 160, 48);
  int compared = 0;
  for (const Mesh* mesh : {&spool, &torus}) {
    const RayCaster caster(*mesh);
    for (const Camera& camera : {TestCamera(), DistortedCamera()}) {
      for (const int stride : {1, 2, 64}) {
        const Eigen::Isometry3d cam_from_object = CamFromObject(
            {25, -15, 430},
            Eigen::AngleAxisd(0.3 + 0.2 * stride, Eigen::Vector3d(1, 0.5, 0.2).normalized()));
        ContourOptions options;
        options.sample_spacing_px = 0.5;
        RenderOptions render_options;
        render_options.margin_px = options.margin_px;
        render_options.depth = render_options.normal_in_cam = render_options.triangle_id = false;
        render_options.point_in_object = stride > 1;
        render_options.point_stride_px = stride;
        const RenderedView view = caster.Render(camera, cam_from_object, render_options);
        const std::vector<ContourPoint> traced =
            caster.ExtractContour(camera, cam_from_object, options);
        const std::vector<ContourPoint> from_mask =
            caster.ExtractContour(camera, cam_from_object, options, &view);
        ASSERT_GT(traced.size(), 500u);
        ASSERT_EQ(from_mask.size(), traced.size()) << camera.name << " stride " << stride;
        for (size_t i = 0; i < traced.size(); ++i) {
          EXPECT_EQ(from_mask[i].pixel, traced[i].pixel);
          EXPECT_EQ(from_mask[i].normal, traced[i].normal);
          EXPECT_EQ(from_mask[i].point_in_object, traced[i].point_in_object);
          EXPECT_EQ(from_mask[i].contour_id, traced[i].contour_id);
          EXPECT_EQ(from_mask[i].is_hole, traced[i].is_hole);
        }
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 12);
}

// The spool is a CAD part with sharp creases: its silhouette has corners, so the test is
// against the mesh's own exact silhouette by ray casting, not an analytic shape.
TEST(ContourTest, SpoolPointsOnExactMeshSilhouette) {
  const Mesh spool = SpoolMesh();
  const RayCaster caster(spool);
  for (const Camera& camera : {TestCamera(), DistortedCamera()}) {
    const Eigen::Isometry3d cam_from_object = CamFromObject(
        {20, 10, 450}, Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 0.5, 0.2).normalized()));
    const ContourOptions options;
    const std::vector<ContourPoint> contour =
        caster.ExtractContour(camera, cam_from_object, options);
    ASSERT_GT(contour.size(), 300u);
    int bracketed = 0;
    for (const ContourPoint& point : contour) {
      // A hit just inside and a miss just outside along the normal: the boundary is within
      // 0.02 px of `pixel` (bisection leaves ≤ precision_px / 2 = 0.008 px).
      const bool inside =
          caster.Intersect(camera, cam_from_object, point.pixel - 0.02 * point.normal).has_value();
      const bool outside =
          !caster.Intersect(camera, cam_from_object, point.pixel + 0.02 * point.normal);
      bracketed += inside && outside;
      // The model point lies on the surface: its depth is the depth of its own ray.
      const auto hit = caster.Intersect(camera, cam_from_object,
                                        camera.Project(cam_from_object * point.point_in_object));
      ASSERT_TRUE(hit.has_value());
    }
    EXPECT_EQ(bracketed, static_cast<int>(contour.size()));
    EXPECT_EQ(CheckContourBasics(caster, camera, cam_from_object, contour), 1.0);
  }
}

TEST(ContourTest, SharedCatModel) {
  const std::string path = test::SharedDataPath("bcot_real_cat/models/Cat.obj");
  if (path.empty()) GTEST_SKIP() << "shared data absent";
  const StatusOr<Mesh> cat = Mesh::Load(path);
  ASSERT_TRUE(cat.ok()) << cat.status().message();
  const RayCaster caster(*cat);
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object =
      CamFromObject({0, 0, 3.0 * cat->diameter()},
                    Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.3, 1, 0.1).normalized()));
  const std::vector<ContourPoint> contour = caster.ExtractContour(camera, cam_from_object);
  ASSERT_GT(contour.size(), 200u);
  EXPECT_EQ(CheckContourBasics(caster, camera, cam_from_object, contour), 1.0);
}

TEST(ContourTest, SparserSamplingAndCoarserGrid) {
  const Mesh sphere = MakeIcosphere(50.0, 5);
  const RayCaster caster(sphere);
  const Camera camera = TestCamera();
  const Eigen::Isometry3d cam_from_object = CamFromObject({0, 0, 500});
  ContourOptions options;
  options.coarse_step_px = 4;
  options.sample_spacing_px = 3.0;
  options.precision_px = 1.0 / 128.0;
  const std::vector<ContourPoint> contour = caster.ExtractContour(camera, cam_from_object, options);
  const double r = 600.0 * 50.0 / std::sqrt(500.0 * 500.0 - 50.0 * 50.0);
  EXPECT_GT(contour.size(), 2 * kPi * r / 3.0 * 0.9);
  EXPECT_LT(contour.size(), 2 * kPi * r / 3.0 * 1.5);
  for (const ContourPoint& point : contour) {
    EXPECT_NEAR((point.pixel - Eigen::Vector2d(320, 256)).norm(), r, 0.05);
    EXPECT_LT(ReprojectionErrorPx(camera, cam_from_object, point),
              0.5 * options.precision_px + 1e-3);
  }
}

// ---------------------------------------------------------------------------------------------
// Concurrency
// ---------------------------------------------------------------------------------------------

TEST(RayCasterTest, ConcurrentCallsGiveSequentialResults) {
  const Mesh spool = SpoolMesh();
  const RayCaster caster(spool);
  const Camera camera = TestCamera();
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 6; ++i) {
    poses.push_back(
        CamFromObject({10.0 * i - 30, 5.0 * i, 420 + 10.0 * i},
                      Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(1, 2, 0.5).normalized())));
  }
  std::vector<RenderedView> expected_views;
  std::vector<std::vector<ContourPoint>> expected_contours;
  for (const auto& pose : poses) {
    expected_views.push_back(caster.Render(camera, pose));
    expected_contours.push_back(caster.ExtractContour(camera, pose));
  }
  std::vector<RenderedView> views[2];
  std::vector<std::vector<ContourPoint>> contours[2];
  auto work = [&](int thread) {
    for (int repeat = 0; repeat < 3; ++repeat) {
      for (size_t i = thread; i < poses.size(); i += 1) {
        const size_t k = (i + thread) % poses.size();
        views[thread].push_back(caster.Render(camera, poses[k]));
        contours[thread].push_back(caster.ExtractContour(camera, poses[k]));
      }
    }
  };
  std::thread first(work, 0);
  std::thread second(work, 1);
  first.join();
  second.join();
  for (int thread = 0; thread < 2; ++thread) {
    size_t n = 0;
    for (int repeat = 0; repeat < 3; ++repeat) {
      for (size_t i = thread; i < poses.size(); ++i, ++n) {
        const size_t k = (i + thread) % poses.size();
        const RenderedView& view = views[thread][n];
        ASSERT_EQ(view.roi, expected_views[k].roi);
        EXPECT_EQ(cv::norm(view.mask, expected_views[k].mask, cv::NORM_INF), 0.0);
        EXPECT_EQ(cv::norm(view.depth, expected_views[k].depth, cv::NORM_INF), 0.0);
        EXPECT_EQ(cv::norm(view.triangle_id, expected_views[k].triangle_id, cv::NORM_INF), 0.0);
        ASSERT_EQ(contours[thread][n].size(), expected_contours[k].size());
        for (size_t j = 0; j < expected_contours[k].size(); ++j) {
          EXPECT_EQ(contours[thread][n][j].pixel, expected_contours[k][j].pixel);
          EXPECT_EQ(contours[thread][n][j].point_in_object,
                    expected_contours[k][j].point_in_object);
        }
      }
    }
  }
}

}  // namespace
}  // namespace bcot

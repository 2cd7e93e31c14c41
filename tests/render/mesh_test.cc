#include "bcot/render/mesh.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "test_util.h"

namespace bcot {
namespace {

using test::SharedDataPath;
using test::SourcePath;
using test::TempDir;
using test::WriteText;
using ::testing::HasSubstr;

// A cube [-1, 1]³ with quad faces (triangulated on load), written in each text format from one
// vertex and face list.
constexpr int kCubeVertices[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                     {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
constexpr int kCubeQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                  {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

std::string CubeVertexLine(const char* prefix, int i) {
  const int* v = kCubeVertices[i];
  return prefix + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) +
         "\n";
}

// OBJ (1-based indices), PLY and OFF (0-based, "4 a b c d" faces).
std::string CubeText(const std::string& format) {
  std::string text;
  if (format == "obj") text = "# cube\n";
  if (format == "ply") {
    text =
        "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
        "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n";
  }
  if (format == "off") text = "OFF\n8 6 0\n";
  for (int i = 0; i < 8; ++i) text += CubeVertexLine(format == "obj" ? "v " : "", i);
  for (const auto& q : kCubeQuads) {
    const int base = format == "obj" ? 1 : 0;
    text += format == "obj" ? "f" : "4";
    for (int i : q) text += " " + std::to_string(i + base);
    text += "\n";
  }
  return text;
}

// ASCII STL: 12 triangles, every vertex repeated per facet (as STL always does).
std::string CubeStl() {
  std::string stl = "solid cube\n";
  for (const auto& q : kCubeQuads) {
    for (const auto& tri : {std::array<int, 3>{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}) {
      stl += "  facet normal 0 0 0\n    outer loop\n";
      for (int i : tri) stl += CubeVertexLine("      vertex ", i);
      stl += "    endloop\n  endfacet\n";
    }
  }
  return stl + "endsolid cube\n";
}

void ExpectUnitCubeScaled(const Mesh& mesh, double scale) {
  EXPECT_EQ(mesh.vertices().size(), 8u);
  EXPECT_EQ(mesh.triangles().size(), 12u);
  EXPECT_TRUE(mesh.bbox_min().isApprox(Eigen::Vector3d::Constant(-scale), 1e-6))
      << mesh.bbox_min().transpose();
  EXPECT_TRUE(mesh.bbox_max().isApprox(Eigen::Vector3d::Constant(scale), 1e-6))
      << mesh.bbox_max().transpose();
  EXPECT_NEAR(mesh.diameter(), 2.0 * scale, 1e-5 * scale);
  EXPECT_TRUE(mesh.bbox_center().isZero(1e-6));
  // A closed cube: every edge is shared by exactly two triangles, and the triangles are
  // non-degenerate.
  double area = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles()) {
    const Eigen::Vector3d a = mesh.vertices()[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices()[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices()[t[2]].cast<double>();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  EXPECT_NEAR(area, 6.0 * 4.0 * scale * scale, 1e-4 * scale * scale);
}

class MeshFormatTest : public ::testing::TestWithParam<std::string> {};

TEST_P(MeshFormatTest, LoadsCubeInEveryFormat) {
  TempDir dir;
  const std::string format = GetParam();
  const std::string path = dir.File("cube." + format);
  WriteText(path, format == "stl" ? CubeStl() : CubeText(format));

  const StatusOr<Mesh> mesh = Mesh::Load(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  ExpectUnitCubeScaled(*mesh, 1.0);

  const StatusOr<Mesh> in_mm = Mesh::Load(path, /*unit_to_mm=*/25.4);
  ASSERT_TRUE(in_mm.ok()) << in_mm.status().message();
  ExpectUnitCubeScaled(*in_mm, 25.4);
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshFormatTest, ::testing::Values("obj", "ply", "off", "stl"));

TEST(MeshTest, AppliesNodeTransforms) {
  // OBJ/PLY/OFF/STL loaders create identity nodes, so use a COLLADA file with a translated
  // node (Y_UP: assimp applies no axis conversion).
  TempDir dir;
  const std::string path = dir.File("tri.dae");
  WriteText(path, R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="tri" name="tri"><mesh>
      <source id="tri-pos"><float_array id="tri-pos-array" count="9">0 0 0 1 0 0 0 1 0</float_array>
        <technique_common><accessor source="#tri-pos-array" count="3" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
      <triangles count="1"><input semantic="VERTEX" source="#tri-vtx" offset="0"/><p>0 1 2</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene"><node id="n" name="n">
      <translate>10 20 30</translate>
      <instance_geometry url="#tri"/>
    </node></visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)");
  const StatusOr<Mesh> mesh = Mesh::Load(path);
  if (!mesh.ok() && mesh.status().message().find("cannot read") != std::string::npos) {
    GTEST_SKIP() << "assimp without COLLADA importer: " << mesh.status().message();
  }
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  ASSERT_EQ(mesh->triangles().size(), 1u);
  EXPECT_TRUE(mesh->bbox_min().isApprox(Eigen::Vector3d(10, 20, 30), 1e-6))
      << mesh->bbox_min().transpose();
  EXPECT_TRUE(mesh->bbox_max().isApprox(Eigen::Vector3d(11, 21, 30), 1e-6))
      << mesh->bbox_max().transpose();
}

TEST(MeshTest, MergesVerticesWithIdenticalPositions) {
  // STL repeats every vertex per facet; an OBJ with per-face normals makes assimp split
  // vertices by normal. Both must come back as the 8 cube corners.
  TempDir dir;
  const std::string path = dir.File("cube_normals.obj");
  WriteText(path, R"(v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 1 0 0
vn 0 1 0
vn -1 0 0
f 1//1 4//1 3//1 2//1
f 5//2 6//2 7//2 8//2
f 1//3 2//3 6//3 5//3
f 2//4 3//4 7//4 6//4
f 3//5 4//5 8//5 7//5
f 4//6 1//6 5//6 8//6
)");
  const StatusOr<Mesh> mesh = Mesh::Load(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  ExpectUnitCubeScaled(*mesh, 1.0);
}

TEST(MeshTest, LoadsBundledMeshes) {
  const StatusOr<Mesh> spool = Mesh::Load(SourcePath("data/meshes/spool.off"));
  ASSERT_TRUE(spool.ok()) << spool.status().message();
  EXPECT_EQ(spool->vertices().size(), 649u);
  EXPECT_EQ(spool->triangles().size(), 1294u);
  EXPECT_GT(spool->diameter(), 0.0);

  const StatusOr<Mesh> pinion = Mesh::Load(SourcePath("data/meshes/pinion.off"));
  ASSERT_TRUE(pinion.ok()) << pinion.status().message();
  EXPECT_EQ(pinion->triangles().size(), 1300u);

  const StatusOr<Mesh> bunny = Mesh::Load(SourcePath("data/meshes/bunny.obj"));
  ASSERT_TRUE(bunny.ok()) << bunny.status().message();
  EXPECT_EQ(bunny->triangles().size(), 3674u);
}

TEST(MeshTest, LoadsSharedCat) {
  const std::string path = SharedDataPath("bcot_real_cat/models/Cat.obj");
  if (path.empty()) GTEST_SKIP() << "shared data absent";
  const StatusOr<Mesh> cat = Mesh::Load(path);
  ASSERT_TRUE(cat.ok()) << cat.status().message();
  // The README: 2502 vertices, 5000 faces, in mm and centred.
  EXPECT_EQ(cat->vertices().size(), 2502u);
  EXPECT_EQ(cat->triangles().size(), 5000u);
  EXPECT_GT(cat->diameter(), 50.0);
  EXPECT_LT(cat->diameter(), 300.0);
  EXPECT_LT(cat->bbox_center().norm(), 0.1 * cat->diameter());
}

TEST(MeshTest, BoundsCentreAndTransforms) {
  const Mesh mesh = Mesh::FromArrays({{1, 2, 3}, {5, 2, 3}, {1, 4, 3}, {1, 2, 4}},
                                     {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}});
  EXPECT_TRUE(mesh.bbox_min().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(mesh.bbox_max().isApprox(Eigen::Vector3d(5, 4, 4)));
  EXPECT_TRUE(mesh.bbox_center().isApprox(Eigen::Vector3d(3, 3, 3.5)));
  EXPECT_DOUBLE_EQ(mesh.diameter(), 4.0);

  const Eigen::Isometry3d objcentre_from_template = mesh.objcentre_from_template();
  EXPECT_TRUE(objcentre_from_template.linear().isIdentity());
  EXPECT_TRUE(objcentre_from_template.translation().isApprox(Eigen::Vector3d(-3, -3, -3.5)));

  const Mesh centred = mesh.Transformed(objcentre_from_template, 25.0);
  EXPECT_TRUE(centred.bbox_center().isZero(1e-9));
  EXPECT_DOUBLE_EQ(centred.diameter(), 100.0);
  EXPECT_EQ(centred.triangles(), mesh.triangles());

  Eigen::Isometry3d rotated = Eigen::Isometry3d::Identity();
  rotated.linear() = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Mesh turned = mesh.Transformed(rotated);
  // x extent 4 becomes y extent 4.
  EXPECT_NEAR(turned.bbox_max().y() - turned.bbox_min().y(), 4.0, 1e-6);
  EXPECT_NEAR(turned.bbox_max().x() - turned.bbox_min().x(), 2.0, 1e-6);
}

TEST(MeshTest, MissingFile) {
  TempDir dir;
  const std::string path = dir.File("nope.obj");
  const StatusOr<Mesh> mesh = Mesh::Load(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(mesh.status().message(), HasSubstr(path));
  EXPECT_THAT(mesh.status().message(), HasSubstr("does not exist"));
}

TEST(MeshTest, EmptyFile) {
  TempDir dir;
  for (const char* name : {"empty.obj", "empty.ply", "empty.off", "empty.stl"}) {
    const std::string path = dir.File(name);
    WriteText(path, "");
    const StatusOr<Mesh> mesh = Mesh::Load(path);
    ASSERT_FALSE(mesh.ok()) << name;
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidInput) << name;
    EXPECT_THAT(mesh.status().message(), HasSubstr(path));
    // Either assimp's own reason or ours; never an empty explanation.
    EXPECT_GT(mesh.status().message().size(), path.size() + 10) << mesh.status().message();
  }
}

TEST(MeshTest, OnlyPointsAndLines) {
  TempDir dir;
  const std::string path = dir.File("wire.obj");
  WriteText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\np 1\n");
  const StatusOr<Mesh> mesh = Mesh::Load(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(mesh.status().message(), HasSubstr(path));
  EXPECT_THAT(mesh.status().message(), HasSubstr("no triangles"));
}

TEST(MeshTest, VerticesOnly) {
  TempDir dir;
  const std::string path = dir.File("cloud.ply");
  WriteText(path, R"(ply
format ascii 1.0
element vertex 3
property float x
property float y
property float z
end_header
0 0 0
1 0 0
0 1 0
)");
  const StatusOr<Mesh> mesh = Mesh::Load(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(mesh.status().message(), HasSubstr(path));
  EXPECT_THAT(mesh.status().message(),
              ::testing::AnyOf(HasSubstr("no triangles"), HasSubstr("no faces"),
                               HasSubstr("cannot read mesh")));
}

TEST(MeshTest, GarbageText) {
  TempDir dir;
  for (const char* name : {"garbage.ply", "garbage.off", "garbage.stl", "garbage.xyz"}) {
    const std::string path = dir.File(name);
    WriteText(path, "this is not a mesh\n\x01\x02\x03 at all }{\n");
    const StatusOr<Mesh> mesh = Mesh::Load(path);
    ASSERT_FALSE(mesh.ok()) << name;
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidInput) << name;
    EXPECT_THAT(mesh.status().message(), HasSubstr(path));
  }
  // OBJ is line based and skips unknown keywords, so garbage parses to an empty scene.
  const std::string path = dir.File("garbage.obj");
  WriteText(path, "this is not a mesh\nneither is this\n");
  const StatusOr<Mesh> mesh = Mesh::Load(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_THAT(mesh.status().message(), HasSubstr(path));
  EXPECT_THAT(mesh.status().message(),
              ::testing::AnyOf(HasSubstr("no faces"), HasSubstr("cannot read mesh")));
}

TEST(MeshTest, NonFiniteCoordinates) {
  TempDir dir;
  const std::string path = dir.File("nan.off");
  WriteText(path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n");
  const StatusOr<Mesh> mesh = Mesh::Load(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_THAT(mesh.status().message(), HasSubstr(path));
  EXPECT_THAT(mesh.status().message(), HasSubstr("non-finite"));
}

TEST(MeshTest, DegenerateBoundingBox) {
  TempDir dir;
  const std::string point = dir.File("point.obj");
  WriteText(point, "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n");
  StatusOr<Mesh> mesh = Mesh::Load(point);
  ASSERT_FALSE(mesh.ok());
  EXPECT_THAT(mesh.status().message(), HasSubstr(point));
  EXPECT_THAT(mesh.status().message(),
              ::testing::AnyOf(HasSubstr("zero-size bounding box"), HasSubstr("zero area")));

  const std::string line = dir.File("line.obj");
  WriteText(line, "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  mesh = Mesh::Load(line);
  ASSERT_FALSE(mesh.ok());
  EXPECT_THAT(mesh.status().message(), HasSubstr("zero area"));
}

TEST(MeshTest, RejectsBadUnit) {
  TempDir dir;
  const std::string path = dir.File("cube.obj");
  WriteText(path, CubeText("obj"));
  for (double unit : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                      std::numeric_limits<double>::infinity()}) {
    const StatusOr<Mesh> mesh = Mesh::Load(path, unit);
    ASSERT_FALSE(mesh.ok()) << unit;
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidConfig);
    EXPECT_THAT(mesh.status().message(), HasSubstr("unit_to_mm"));
    EXPECT_THAT(mesh.status().message(), HasSubstr(path));
  }
}

}  // namespace
}  // namespace bcot

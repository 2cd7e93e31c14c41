#include "bcot/render/mesh_writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::StartsWith;

// A tetrahedron whose coordinates need all of a float's digits.
Mesh PreciseTetrahedron() {
  std::vector<Eigen::Vector3f> vertices = {{0.1f, -2.5e-3f, 7.0f / 3.0f},
                                           {123.456789f, 0.0f, -1e-7f},
                                           {-33.3333f, 44.4f, 1e4f / 7.0f},
                                           {5.0f, 5.0f, 5.0f}};
  std::vector<Eigen::Vector3i> triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
  return Mesh::FromArrays(vertices, triangles);
}

// Writes `text` to `file_name`, loads it and expects `mesh` back exactly.
void ExpectLoadsBackTo(const std::string& text, const std::string& file_name, const Mesh& mesh) {
  test::TempDir dir;
  test::WriteText(dir.File(file_name), text);
  const StatusOr<Mesh> read = Mesh::Load(dir.File(file_name));
  ASSERT_TRUE(read.ok()) << read.status().message();
  ASSERT_EQ(read->vertices().size(), mesh.vertices().size());
  ASSERT_EQ(read->triangles().size(), mesh.triangles().size());
  // The loader may reorder vertices; every written vertex must come back exactly.
  for (const Eigen::Vector3f& v : mesh.vertices()) {
    bool found = false;
    for (const Eigen::Vector3f& w : read->vertices()) found = found || v == w;
    EXPECT_TRUE(found) << v.transpose();
  }
}

TEST(MeshWriterTest, ObjTextLoadsBackToTheSameMesh) {
  const Mesh mesh = PreciseTetrahedron();
  const std::string text = FormatObjMesh(mesh, "first line\nsecond line");
  EXPECT_THAT(text, StartsWith("# first line\n# second line\nv "));
  ExpectLoadsBackTo(text, "mesh.obj", mesh);
}

TEST(MeshWriterTest, PlyTextLoadsBackToTheSameMesh) {
  const Mesh mesh = PreciseTetrahedron();
  const std::string text = FormatPlyMesh(mesh, "first line\nsecond line");
  EXPECT_THAT(text, StartsWith("ply\nformat ascii 1.0\ncomment first line\ncomment second line\n"
                               "element vertex 4\n"));
  EXPECT_THAT(text, ::testing::HasSubstr("element face 4\n"));
  ExpectLoadsBackTo(text, "mesh.ply", mesh);
}

TEST(MeshWriterTest, PlyVertexNormalsAreUnitAndFollowTheWinding) {
  // Two counter-clockwise triangles in the plane z = 2 (seen from +z): every normal is +z.
  const Mesh mesh =
      Mesh::FromArrays({{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}}, {{0, 1, 2}, {0, 2, 3}});
  const std::string text = FormatPlyMesh(mesh, "");
  EXPECT_THAT(text,
              ::testing::HasSubstr("property float nx\nproperty float ny\nproperty float nz\n"));
  std::istringstream lines(text.substr(text.find("end_header\n") + 11));
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector3f v, n;
    lines >> v.x() >> v.y() >> v.z() >> n.x() >> n.y() >> n.z();
    EXPECT_TRUE(v.isApprox(mesh.vertices()[i])) << i;
    EXPECT_TRUE(n.isApprox(Eigen::Vector3f::UnitZ())) << i << ": " << n.transpose();
  }
}

}  // namespace
}  // namespace bcot

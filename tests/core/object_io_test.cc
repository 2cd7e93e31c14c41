#include "bcot/core/object_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

TEST(ObjectIoTest, ReadsAndResolvesMeshAgainstTheFilesDirectory) {
  test::TempDir dir;
  test::WriteText(dir.File("seq/object.yaml"),
                  "name: cat\nmesh: ../models/cat.obj\nunit_to_mm: 1000\n");
  const StatusOr<ObjectSpec> object = ReadObjectYaml(dir.File("seq/object.yaml"));
  ASSERT_TRUE(object.ok()) << object.status().message();
  EXPECT_EQ(object->name, "cat");
  EXPECT_EQ(object->mesh, "../models/cat.obj");
  EXPECT_EQ(object->mesh_path, dir.File("seq/../models/cat.obj"));
  EXPECT_EQ(object->unit_to_mm, 1000.0);
}

TEST(ObjectIoTest, UnitToMmDefaultsToOneAndAbsoluteMeshPassesThrough) {
  test::TempDir dir;
  test::WriteText(dir.File("object.yaml"), "name: spool\r\nmesh: /meshes/spool.off\r\n");
  const StatusOr<ObjectSpec> object = ReadObjectYaml(dir.File("object.yaml"));
  ASSERT_TRUE(object.ok()) << object.status().message();
  EXPECT_EQ(object->unit_to_mm, 1.0);
  EXPECT_EQ(object->mesh_path, "/meshes/spool.off");
}

TEST(ObjectIoTest, WriteThenReadIsExact) {
  test::TempDir dir;
  ObjectSpec object;
  object.name = "true";  // must be quoted to stay a string
  object.mesh = "meshes/my part: v2.obj";
  object.unit_to_mm = 25.4 / 3.0;
  ASSERT_TRUE(WriteObjectYaml(dir.File("a/object.yaml"), object).ok());
  const StatusOr<ObjectSpec> read = ReadObjectYaml(dir.File("a/object.yaml"));
  ASSERT_TRUE(read.ok()) << read.status().message() << "\n" << FormatObjectYaml(object);
  EXPECT_EQ(read->name, object.name);
  EXPECT_EQ(read->mesh, object.mesh);
  EXPECT_EQ(read->unit_to_mm, object.unit_to_mm);
  EXPECT_EQ(read->mesh_path, dir.File("a/meshes/my part: v2.obj"));
}

TEST(ObjectIoTest, FormatIsPlainForOrdinaryValues) {
  ObjectSpec object;
  object.name = "cat";
  object.mesh = "../models/Cat.obj";
  EXPECT_EQ(FormatObjectYaml(object), "name: cat\nmesh: ../models/Cat.obj\nunit_to_mm: 1\n");
}

struct BadObjectCase {
  std::string text;
  std::string prefix;  // after the file path
  std::string problem;
};

class BadObjectTest : public ::testing::TestWithParam<BadObjectCase> {};

TEST_P(BadObjectTest, MessageNamesFileLineKeyAndProblem) {
  const BadObjectCase& c = GetParam();
  test::TempDir dir;
  test::WriteText(dir.File("object.yaml"), c.text);
  const StatusOr<ObjectSpec> object = ReadObjectYaml(dir.File("object.yaml"));
  ASSERT_FALSE(object.ok()) << c.text;
  EXPECT_EQ(object.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(object.status().message(),
              AllOf(StartsWith(dir.File("object.yaml") + c.prefix), HasSubstr(c.problem)));
}

INSTANTIATE_TEST_SUITE_P(
    Errors, BadObjectTest,
    ::testing::Values(
        BadObjectCase{"mesh: cat.obj\n", ":1: name: ", "missing required key"},
        BadObjectCase{"name: cat\n", ":1: mesh: ", "missing required key"},
        BadObjectCase{"name: cat\nmesh: \"\"\n", ":2: mesh: ", "must not be empty"},
        BadObjectCase{"name: \"\"\nmesh: cat.obj\n", ":1: name: ", "must not be empty"},
        BadObjectCase{"name: cat\nmesh: cat.obj\nunit_to_mm: 0\n",
                      ":3: unit_to_mm: ", "0 must be > 0"},
        BadObjectCase{"name: cat\nmesh: cat.obj\nunit_to_mm: -2\n",
                      ":3: unit_to_mm: ", "-2 must be > 0"},
        BadObjectCase{"name: cat\nmesh: cat.obj\nunit_to_mm: mm\n",
                      ":3: unit_to_mm: ", "expected a number, got 'mm'"},
        BadObjectCase{"name: cat\nmesh: cat.obj\nscale: 2\n", ":3: scale: ", "unknown key"},
        BadObjectCase{"name: cat\nmesh: cat.obj\nname: dog\n",
                      ":3: name: ", "duplicate key (first at line 1)"},
        BadObjectCase{"name: cat\nmesh: [a.obj, b.obj]\n",
                      ":2: mesh: ", "expected a string, got a sequence of 2"},
        BadObjectCase{"- cat\n", ":1: the document: ", "expected a mapping"},
        BadObjectCase{"name: cat\n  mesh: cat.obj\n", ":2: ", "YAML syntax error"}));

TEST(ObjectIoTest, MissingFileIsNotFound) {
  test::TempDir dir;
  const StatusOr<ObjectSpec> object = ReadObjectYaml(dir.File("object.yaml"));
  ASSERT_FALSE(object.ok());
  EXPECT_EQ(object.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(object.status().message(), HasSubstr(dir.File("object.yaml")));
}

TEST(ObjectIoTest, CheckMeshFindsExistingMesh) {
  test::TempDir dir;
  test::WriteText(dir.File("models/cat.obj"), "v 0 0 0\n");
  test::WriteText(dir.File("seq/object.yaml"), "name: cat\nmesh: ../models/cat.obj\n");
  const StatusOr<ObjectSpec> object = ReadObjectYamlAndCheckMesh(dir.File("seq/object.yaml"));
  ASSERT_TRUE(object.ok()) << object.status().message();
  EXPECT_TRUE(std::filesystem::is_regular_file(object->mesh_path));
}

TEST(ObjectIoTest, CheckMeshReportsMissingMeshWithLine) {
  test::TempDir dir;
  test::WriteText(dir.File("object.yaml"), "# the cat\nname: cat\nmesh: cat.obj\n");
  // Without the check the file itself is fine.
  ASSERT_TRUE(ReadObjectYaml(dir.File("object.yaml")).ok());
  const StatusOr<ObjectSpec> object = ReadObjectYamlAndCheckMesh(dir.File("object.yaml"));
  ASSERT_FALSE(object.ok());
  EXPECT_EQ(object.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(object.status().message(),
              AllOf(StartsWith(dir.File("object.yaml") + ":3: mesh: "),
                    HasSubstr(dir.File("cat.obj")), HasSubstr("not found")));
}

TEST(ObjectIoTest, CheckMeshRejectsADirectory) {
  test::TempDir dir;
  std::filesystem::create_directory(dir.File("cat.obj"));
  test::WriteText(dir.File("object.yaml"), "name: cat\nmesh: cat.obj\n");
  const StatusOr<ObjectSpec> object = ReadObjectYamlAndCheckMesh(dir.File("object.yaml"));
  ASSERT_FALSE(object.ok());
  EXPECT_EQ(object.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(object.status().message(), AllOf(StartsWith(dir.File("object.yaml") + ":2: mesh: "),
                                               HasSubstr("not a regular file")));
}

}  // namespace
}  // namespace bcot

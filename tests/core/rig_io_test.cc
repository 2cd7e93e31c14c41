#include "bcot/core/rig_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "bcot/core/file_util.h"
#include "bcot/core/se3.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// A valid two-camera rig.yaml, one entry per line so tests can edit line n (1-based) by index.
std::vector<std::string> ValidRigLines() {
  return {
      "cameras:",                                                                    // 1
      "  - name: cam0",                                                              // 2
      "    image_size: [1280, 1024]",                                                // 3
      "    K: [1000, 1001, 640.5, 511.5]",                                           // 4
      "    distortion: [0.1, -0.2, 0.001, 0.002, 0.05]",                             // 5
      "    cam_from_rig: [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]",       // 6
      "  - name: cam1",                                                              // 7
      "    image_size: [1280, 1024]",                                                // 8
      "    K: [1000, 1000, 640, 512]",                                               // 9
      "    cam_from_rig: [0, 0, 1, -100,  0, 1, 0, 0,  -1, 0, 0, 50,  0, 0, 0, 1]",  // 10
  };
}

std::string Join(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// Parses ValidRigLines() with line `line` (1-based) replaced; returns the error message.
Status ParseWithLine(int line, const std::string& replacement) {
  std::vector<std::string> lines = ValidRigLines();
  lines[line - 1] = replacement;
  return ParseRigYaml(Join(lines), "rig.yaml").status();
}

Rig ExampleRig() {
  Camera cam0("left", 1280, 1024, 1234.5678901234567, 1235.25, 640.123456789, 511.987654321);
  cam0.distortion = {-0.123456789012345, 0.0456, 1e-4, -2.5e-5, 1.0 / 3.0};
  Camera cam1("yes", 640, 512, 500.0, 500.0, 319.5, 255.5);  // a name YAML would read as bool
  Vector6d twist;
  twist << 120.123456789, -3.3, 7.77, 0.1, -0.25, 0.05;
  RigCamera second{cam1, ExpSE3(twist)};
  return Rig({RigCamera{cam0, Eigen::Isometry3d::Identity()}, second});
}

void ExpectSameRig(const Rig& actual, const Rig& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (int i = 0; i < actual.size(); ++i) {
    const Camera& a = actual[i].camera;
    const Camera& e = expected[i].camera;
    EXPECT_EQ(a.name, e.name);
    EXPECT_EQ(a.width, e.width);
    EXPECT_EQ(a.height, e.height);
    EXPECT_EQ(a.fx, e.fx);
    EXPECT_EQ(a.fy, e.fy);
    EXPECT_EQ(a.cx, e.cx);
    EXPECT_EQ(a.cy, e.cy);
    EXPECT_EQ(a.distortion, e.distortion);
    EXPECT_TRUE(actual[i].cam_from_rig.matrix() == expected[i].cam_from_rig.matrix())
        << "camera " << i << "\n"
        << actual[i].cam_from_rig.matrix() << "\n"
        << expected[i].cam_from_rig.matrix();
  }
}

TEST(RigIoTest, ParsesValidRig) {
  const StatusOr<Rig> rig = ParseRigYaml(Join(ValidRigLines()), "rig.yaml");
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  ASSERT_EQ(rig->size(), 2);
  const Camera& cam0 = (*rig)[0].camera;
  EXPECT_EQ(cam0.name, "cam0");
  EXPECT_EQ(cam0.width, 1280);
  EXPECT_EQ(cam0.height, 1024);
  EXPECT_EQ(cam0.fx, 1000.0);
  EXPECT_EQ(cam0.fy, 1001.0);
  EXPECT_EQ(cam0.cx, 640.5);
  EXPECT_EQ(cam0.cy, 511.5);
  EXPECT_EQ(cam0.distortion, (std::array<double, 5>{0.1, -0.2, 0.001, 0.002, 0.05}));
  EXPECT_TRUE((*rig)[0].cam_from_rig.matrix().isIdentity(0.0));

  const RigCamera& cam1 = (*rig)[1];
  EXPECT_FALSE(cam1.camera.HasDistortion());  // optional, defaults to zeros
  const Eigen::Vector3d p_in_rig(1.0, 2.0, 3.0);
  // Rows [0 0 1 | -100], [0 1 0 | 0], [-1 0 0 | 50]: the matrix is row-major.
  EXPECT_TRUE((cam1.cam_from_rig * p_in_rig).isApprox(Eigen::Vector3d(-97.0, 2.0, 49.0)));
  EXPECT_EQ(rig->Find("cam1"), 1);
}

TEST(RigIoTest, FormatThenParseIsExact) {
  const Rig rig = ExampleRig();
  const std::string text = FormatRigYaml(rig);
  const StatusOr<Rig> parsed = ParseRigYaml(text, "rig.yaml");
  ASSERT_TRUE(parsed.ok()) << parsed.status().message() << "\n" << text;
  ExpectSameRig(*parsed, rig);
  // Formatting is stable: the parsed rig formats to the same text.
  EXPECT_EQ(FormatRigYaml(*parsed), text);
}

TEST(RigIoTest, FormatIsReadable) {
  const std::string text = FormatRigYaml(ExampleRig());
  EXPECT_THAT(text, StartsWith("cameras:\n  - name: left\n    image_size: [1280, 1024]\n"));
  EXPECT_THAT(text, HasSubstr("  - name: \"yes\"\n"));
  EXPECT_THAT(text, HasSubstr("    K: [500, 500, 319.5, 255.5]\n"));
  EXPECT_THAT(text, HasSubstr("    cam_from_rig: [1, 0, 0, 0,\n                   0, 1, 0, 0,\n"));
  // The second camera has no distortion: the key is omitted (defaults to zeros).
  EXPECT_EQ(text.find("distortion"), text.rfind("distortion"));
}

TEST(RigIoTest, WriteThenReadFileIsExact) {
  test::TempDir dir;
  const Rig rig = ExampleRig();
  ASSERT_TRUE(WriteRigYaml(dir.File("seq/rig.yaml"), rig).ok());
  const StatusOr<Rig> read = ReadRigYaml(dir.File("seq/rig.yaml"));
  ASSERT_TRUE(read.ok()) << read.status().message();
  ExpectSameRig(*read, rig);
}

TEST(RigIoTest, RoundedRotationIsAcceptedAndOrthonormalised) {
  const StatusOr<Rig> rig = ParseRigYaml(
      Join({"cameras:", "  - name: c", "    image_size: [640, 480]", "    K: [500, 500, 320, 240]",
            "    cam_from_rig: [0.707107, -0.707107, 0, 10,  0.707107, 0.707107, 0, 20,  0, 0, 1, "
            "30,  0, 0, 0, 1]"}),
      "rig.yaml");
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  const Eigen::Matrix3d r = (*rig)[0].cam_from_rig.linear();
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(r(0, 0), std::sqrt(0.5), 1e-6);
  EXPECT_EQ((*rig)[0].cam_from_rig.translation(), Eigen::Vector3d(10, 20, 30));
}

TEST(RigIoTest, ExampleMessageFromTheDesign) {
  // The message DESIGN.md and rig_io.h quote, verbatim.
  const std::vector<std::string> text = {
      "cameras:",
      "  - name: cam0",
      "    image_size: [1280, 1024]",
      "    K: [1000, 1001, 640.5, 511.5]",
      "    cam_from_rig: [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]",
      "  - name: cam1",
      "    K: [1000, 1000, 640]",
      "    image_size: [1280, 1024]",
      "    cam_from_rig: [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]",
  };
  const StatusOr<Rig> rig = ParseRigYaml(Join(text), "rig.yaml");
  ASSERT_FALSE(rig.ok());
  EXPECT_EQ(rig.status().code(), StatusCode::kInvalidInput);
  EXPECT_EQ(rig.status().message(), "rig.yaml:7: cameras[1].K: expected 4 numbers, got 3");
}

struct BadRigCase {
  int line;                 // line of ValidRigLines() to replace
  std::string replacement;  // its new text
  std::string prefix;       // expected start of the message: "rig.yaml:N: key.path: "
  std::string problem;      // expected substring after it
};

class BadRigTest : public ::testing::TestWithParam<BadRigCase> {};

TEST_P(BadRigTest, MessageNamesFileLineKeyAndProblem) {
  const BadRigCase& c = GetParam();
  const Status status = ParseWithLine(c.line, c.replacement);
  ASSERT_FALSE(status.ok()) << c.replacement;
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_THAT(status.message(), AllOf(StartsWith(c.prefix), HasSubstr(c.problem)));
  EXPECT_EQ(status.message().find('\n'), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    Errors, BadRigTest,
    ::testing::Values(
        BadRigCase{9, "    K: [1000, 1000, 640]",
                   "rig.yaml:9: cameras[1].K: ", "expected 4 numbers, got 3"},
        BadRigCase{9, "    K: 1000",
                   "rig.yaml:9: cameras[1].K: ", "expected a sequence [...], got '1000'"},
        BadRigCase{9, "    K: [1000, 1000, 640, cx]",
                   "rig.yaml:9: cameras[1].K[3]: ", "expected a number, got 'cx'"},
        BadRigCase{9, "    K: [-1000, 1000, 640, 512]",
                   "rig.yaml:9: cameras[1].K: ", "fx and fy must be > 0"},
        BadRigCase{5, "    fx: 1000", "rig.yaml:5: cameras[0].fx: ", "unknown key"},
        BadRigCase{5, "    K: [1, 1, 1, 1]",
                   "rig.yaml:5: cameras[0].K: ", "duplicate key (first at line 4)"},
        BadRigCase{10, "    cam_from_rig_typo: []",
                   "rig.yaml:7: cameras[1].cam_from_rig: ", "missing required key"},
        BadRigCase{3, "    image_size: big",
                   "rig.yaml:3: cameras[0].image_size: ", "expected a sequence [...], got 'big'"},
        BadRigCase{3, "    image_size: [1280.5, 1024]",
                   "rig.yaml:3: cameras[0].image_size[0]: ", "expected an integer, got '1280.5'"},
        BadRigCase{3, "    image_size: [1280, 1024, 3]", "rig.yaml:3: cameras[0].image_size: ",
                   "expected 2 numbers [width, height], got 3"},
        BadRigCase{3, "    image_size: [0, 1024]",
                   "rig.yaml:3: cameras[0].image_size: ", "must be > 0"},
        BadRigCase{5, "    distortion: [0.1, -0.2, 0.001, 0.002]",
                   "rig.yaml:5: cameras[0].distortion: ", "expected 5 numbers, got 4"},
        BadRigCase{6, "    cam_from_rig: [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0]",
                   "rig.yaml:6: cameras[0].cam_from_rig: ", "expected 16 numbers, got 12"},
        BadRigCase{6, "    cam_from_rig: [1, 0.1, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]",
                   "rig.yaml:6: cameras[0].cam_from_rig: ", "not orthonormal"},
        BadRigCase{6, "    cam_from_rig: [-1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]",
                   "rig.yaml:6: cameras[0].cam_from_rig: ", "determinant"},
        BadRigCase{6, "    cam_from_rig: [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 1, 1]",
                   "rig.yaml:6: cameras[0].cam_from_rig: ",
                   "last row is [0, 0, 1, 1], expected [0, 0, 0, 1]"},
        BadRigCase{6, "    cam_from_rig: [1, 0, 0, .nan,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]",
                   "rig.yaml:6: cameras[0].cam_from_rig[3]: ", "expected a finite number"},
        BadRigCase{7, "  - name: cam0",
                   "rig.yaml:7: cameras[1].name: ", "'cam0' is already the name of cameras[0]"},
        BadRigCase{2, "  - name: a/b", "rig.yaml:2: cameras[0].name: ", "folder name"},
        BadRigCase{2, "  - name: \"\"", "rig.yaml:2: cameras[0].name: ", "must not be empty"},
        BadRigCase{2, "  - name: [a]",
                   "rig.yaml:2: cameras[0].name: ", "expected a string, got a sequence of 1"},
        BadRigCase{2, "  - nam: cam0", "rig.yaml:2: cameras[0].name: ", "missing required key"},
        BadRigCase{1, "cameraz:", "rig.yaml:1: cameras: ", "missing required key"},
        BadRigCase{10,
                   "    cam_from_rig: [0, 0, 1, -100,  0, 1, 0, 0,  -1, 0, 0, 50,  0, 0, 0, 1]\n"
                   "extra: 1",
                   "rig.yaml:11: extra: ", "unknown key"},
        BadRigCase{4, "    K: [1000, 1001, 640.5, 511.5", "rig.yaml:", "YAML syntax error"},
        // Finite but absurd values (they used to reach the ray caster and abort in Embree).
        BadRigCase{4, "    K: [1000, 1e-300, 640.5, 511.5]",
                   "rig.yaml:4: cameras[0].K: ", "plausible focal lengths of a 1280x1024 image"},
        BadRigCase{4, "    K: [1e300, 1000, 640.5, 511.5]",
                   "rig.yaml:4: cameras[0].K: ", "outside [12.8, 1.28e+06] px"},
        BadRigCase{4, "    K: [1000, 1000, 1e5, 511.5]",
                   "rig.yaml:4: cameras[0].K: ", "more than one image size outside"},
        BadRigCase{5, "    distortion: [1e6, 0, 0, 0, 0]",
                   "rig.yaml:5: cameras[0].distortion: ", "is out of range"},
        BadRigCase{5, "    distortion: [-1.5, 0, 0, 0, 0]",
                   "rig.yaml:5: cameras[0].distortion: ", "folds over"},
        BadRigCase{
            6, "    cam_from_rig: [1, 0, 0, 1e39,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]",
            "rig.yaml:6: cameras[0].cam_from_rig: ", "more than 10 km from the rig origin"}));

TEST(RigIoTest, CamerasMustBeANonEmptySequence) {
  for (const std::string& text :
       {std::string("cameras: []\n"), std::string("cameras: cam0\n"), std::string("cameras:\n")}) {
    const StatusOr<Rig> rig = ParseRigYaml(text, "rig.yaml");
    ASSERT_FALSE(rig.ok()) << text;
    EXPECT_THAT(rig.status().message(),
                AllOf(StartsWith("rig.yaml:1: cameras: "), HasSubstr("non-empty sequence")));
  }
}

TEST(RigIoTest, CameraEntryMustBeAMapping) {
  const StatusOr<Rig> rig = ParseRigYaml("cameras:\n  - cam0\n", "rig.yaml");
  ASSERT_FALSE(rig.ok());
  EXPECT_THAT(rig.status().message(),
              AllOf(StartsWith("rig.yaml:2: cameras[0]: "), HasSubstr("expected a mapping")));
}

TEST(RigIoTest, EmptyFileIsMissingCameras) {
  const StatusOr<Rig> rig = ParseRigYaml("", "rig.yaml");
  ASSERT_FALSE(rig.ok());
  EXPECT_EQ(rig.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(rig.status().message(), HasSubstr("cameras: missing required key"));
}

TEST(RigIoTest, ReadNamesThePathAndMissingFileIsNotFound) {
  test::TempDir dir;
  const StatusOr<Rig> missing = ReadRigYaml(dir.File("rig.yaml"));
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(missing.status().message(), HasSubstr(dir.File("rig.yaml")));

  std::vector<std::string> lines = ValidRigLines();
  lines[8] = "    K: [1000, 1000, 640]";
  test::WriteText(dir.File("rig.yaml"), Join(lines));
  const StatusOr<Rig> bad = ReadRigYaml(dir.File("rig.yaml"));
  ASSERT_FALSE(bad.ok());
  EXPECT_THAT(bad.status().message(),
              StartsWith(dir.File("rig.yaml") + ":9: cameras[1].K: expected 4 numbers, got 3"));
}

TEST(RigIoTest, CrlfFileWithByteOrderMarkIsRead) {
  std::string text = "\xEF\xBB\xBF";
  for (const std::string& line : ValidRigLines()) text += line + "\r\n";
  const StatusOr<Rig> rig = ParseRigYaml(text, "rig.yaml");
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  EXPECT_EQ((*rig)[1].camera.name, "cam1");
}

}  // namespace
}  // namespace bcot

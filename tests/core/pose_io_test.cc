#include "bcot/core/pose_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <fmt/format.h>

#include "bcot/core/file_util.h"
#include "bcot/core/se3.h"
#include "test_util.h"

namespace bcot {
namespace {

using test::PoseNear;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

// Random poses with fixed seed: rotations of any angle, translations up to 1 m.
std::vector<Eigen::Isometry3d> RandomPoses(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < count; ++i) {
    Vector6d twist;
    for (int k = 0; k < 6; ++k) twist[k] = unit(rng) * (k < 3 ? 1000.0 : 3.0);
    poses.push_back(ExpSE3(twist));
  }
  return poses;
}

double OrthonormalityError(const Eigen::Matrix3d& r) {
  return (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
}

// A pose line with BCOT's 6-digit rotation and 3-decimal translation, like the release files.
constexpr char kBcotLine[] =
    "0.78603\t-0.587438\t0.19255\t0.604647\t0.795404\t-0.0416517\t-0.128687\t0.149164\t"
    "0.980401\t281.848\t-166.599\t731.918\t";

TEST(FormatPoseLineTest, TabSeparatedTwelveNumbersShortestForm) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.5, -12.25, 1e-7);
  EXPECT_EQ(FormatPoseLine(pose), "1\t0\t0\t0\t1\t0\t0\t0\t1\t0.5\t-12.25\t1e-07");
}

TEST(PoseIoTest, WriteThenReadIsBitExact) {
  test::TempDir dir;
  const std::vector<Eigen::Isometry3d> poses = RandomPoses(50, 7);
  ASSERT_TRUE(WritePoseFile(dir.File("out/poses.txt"), poses).ok());
  const StatusOr<std::vector<Eigen::Isometry3d>> read = ReadPoseFile(dir.File("out/poses.txt"));
  ASSERT_TRUE(read.ok()) << read.status().message();
  ASSERT_EQ(read->size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_TRUE((*read)[i].matrix() == poses[i].matrix()) << "pose " << i << "\n"
                                                          << (*read)[i].matrix() << "\n"
                                                          << poses[i].matrix();
  }
}

TEST(PoseIoTest, WritesOneLfLinePerPose) {
  test::TempDir dir;
  ASSERT_TRUE(WritePoseFile(dir.File("p.txt"), RandomPoses(3, 1)).ok());
  const std::string text = *ReadTextFile(dir.File("p.txt"));
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);
  EXPECT_EQ(text.find('\r'), std::string::npos);
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(std::count(text.begin(), text.end(), '\t'), 3 * 11);
}

TEST(PoseIoTest, EmptyPoseListWritesEmptyFileAndReadsBackEmpty) {
  test::TempDir dir;
  ASSERT_TRUE(WritePoseFile(dir.File("p.txt"), {}).ok());
  const auto read = ReadPoseFile(dir.File("p.txt"));
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_TRUE(read->empty());
}

TEST(ParsePoseLineTest, ReadsBcotLineWithTrailingTabAndCarriageReturn) {
  const StatusOr<Eigen::Isometry3d> pose = ParsePoseLine(std::string(kBcotLine) + "\r", "ctx");
  ASSERT_TRUE(pose.ok()) << pose.status().message();
  EXPECT_NEAR(pose->linear()(0, 0), 0.78603, 1e-5);
  EXPECT_NEAR(pose->linear()(2, 1), 0.149164, 1e-5);
  EXPECT_EQ(pose->translation(), Eigen::Vector3d(281.848, -166.599, 731.918));
  // Six stored digits are not orthonormal to double precision; the reader repairs that.
  EXPECT_LT(OrthonormalityError(pose->linear()), 1e-14);
  EXPECT_NEAR(pose->linear().determinant(), 1.0, 1e-14);
}

TEST(ParsePoseLineTest, AcceptsSpacesMixedSeparatorsAndSigns) {
  const StatusOr<Eigen::Isometry3d> pose =
      ParsePoseLine("  +1 0 0\t0  1 0 \t 0 0 1e0   1.5e2 -2 +3  ", "ctx");
  ASSERT_TRUE(pose.ok()) << pose.status().message();
  EXPECT_TRUE(pose->linear().isIdentity(0.0));
  EXPECT_EQ(pose->translation(), Eigen::Vector3d(150.0, -2.0, 3.0));
}

TEST(ParsePoseLineTest, WrongCountNamesContextAndCount) {
  for (const auto& [line, count] : std::vector<std::pair<std::string, int>>{
           {"1 0 0 0 1 0 0 0 1 0 0", 11}, {"1 0 0 0 1 0 0 0 1 0 0 0 9", 13}, {"", 0}}) {
    const auto pose = ParsePoseLine(line, "poses.txt:4");
    ASSERT_FALSE(pose.ok()) << line;
    EXPECT_EQ(pose.status().code(), StatusCode::kInvalidInput);
    EXPECT_THAT(pose.status().message(),
                AllOf(HasSubstr("poses.txt:4: "), HasSubstr("expected 12 numbers"),
                      HasSubstr("got " + std::to_string(count))));
  }
}

TEST(ParsePoseLineTest, NonNumberNamesPositionAndToken) {
  const auto pose = ParsePoseLine("1 0 0 0 1x 0 0 0 1 0 0 0", "poses.txt:2");
  ASSERT_FALSE(pose.ok());
  EXPECT_EQ(pose.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(pose.status().message(),
              AllOf(HasSubstr("poses.txt:2: "), HasSubstr("number 5 of 12"), HasSubstr("'1x'")));
}

TEST(ParsePoseLineTest, CommaDecimalIsRejected) {
  const auto pose = ParsePoseLine("1 0 0 0 1 0 0 0 1 0,5 0 0", "p.txt:1");
  ASSERT_FALSE(pose.ok());
  EXPECT_THAT(pose.status().message(), AllOf(HasSubstr("number 10"), HasSubstr("'0,5'")));
}

TEST(ParsePoseLineTest, NonFiniteIsRejected) {
  for (const char* bad : {"nan", "inf", "-inf"}) {
    const auto pose = ParsePoseLine(fmt::format("1 0 0 0 1 0 0 0 1 0 {} 0", bad), "p.txt:9");
    ASSERT_FALSE(pose.ok()) << bad;
    EXPECT_THAT(pose.status().message(),
                AllOf(HasSubstr("p.txt:9: "), HasSubstr("number 11"), HasSubstr("finite")));
  }
}

TEST(ParsePoseLineTest, NonOrthonormalRotationIsRejected) {
  // Scaled rotation (a common mistake: a similarity transform or a unit error in R).
  const auto pose = ParsePoseLine("1.01 0 0 0 1 0 0 0 1 0 0 0", "p.txt:3");
  ASSERT_FALSE(pose.ok());
  EXPECT_EQ(pose.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(pose.status().message(), AllOf(HasSubstr("p.txt:3: "), HasSubstr("orthonormal"),
                                             HasSubstr("0.0201"), HasSubstr("tolerance 0.0001")));
}

TEST(ParsePoseLineTest, ReflectionIsRejected) {
  const auto pose = ParsePoseLine("-1 0 0 0 1 0 0 0 1 0 0 0", "p.txt:1");
  ASSERT_FALSE(pose.ok());
  EXPECT_THAT(pose.status().message(), AllOf(HasSubstr("p.txt:1: "), HasSubstr("determinant")));
}

TEST(ParsePoseLineTest, ToleranceBoundary) {
  // Deviation of RᵀR from I is about 2·ε for R = diag(1+ε, 1, 1).
  EXPECT_TRUE(ParsePoseLine("1.00004 0 0 0 1 0 0 0 1 0 0 0", "c").ok());
  EXPECT_FALSE(ParsePoseLine("1.00006 0 0 0 1 0 0 0 1 0 0 0", "c").ok());
}

TEST(ReadPoseFileTest, BcotFormatWithCrlfTrailingTabsAndBlankTrailingLines) {
  test::TempDir dir;
  const std::string line2 = "1\t0\t0\t0\t1\t0\t0\t0\t1\t10\t20\t30\t";
  test::WriteText(dir.File("pose.txt"),
                  std::string(kBcotLine) + "\r\n" + line2 + "\r\n\r\n \t\r\n\n");
  const auto poses = ReadPoseFile(dir.File("pose.txt"));
  ASSERT_TRUE(poses.ok()) << poses.status().message();
  ASSERT_EQ(poses->size(), 2u);
  EXPECT_EQ((*poses)[0].translation(), Eigen::Vector3d(281.848, -166.599, 731.918));
  EXPECT_EQ((*poses)[1].translation(), Eigen::Vector3d(10, 20, 30));
  EXPECT_TRUE((*poses)[1].linear().isIdentity(0.0));
}

TEST(ReadPoseFileTest, Utf8ByteOrderMarkIsIgnored) {
  test::TempDir dir;
  test::WriteText(dir.File("pose.txt"),
                  "\xEF\xBB\xBF"
                  "1 0 0 0 1 0 0 0 1 4 5 6\r\n");
  const auto poses = ReadPoseFile(dir.File("pose.txt"));
  ASSERT_TRUE(poses.ok()) << poses.status().message();
  ASSERT_EQ(poses->size(), 1u);
  EXPECT_EQ((*poses)[0].translation(), Eigen::Vector3d(4, 5, 6));
}

TEST(ReadPoseFileTest, RealBcotGroundTruthFile) {
  const std::string path = test::SharedDataPath("bcot_real_cat/handheld_demo/Cat/pose.txt");
  if (path.empty()) GTEST_SKIP() << "shared BCOT data not available";
  const auto poses = ReadPoseFile(path);
  ASSERT_TRUE(poses.ok()) << poses.status().message();
  ASSERT_EQ(poses->size(), 31u);
  // First line of the file: 0.78603 -0.587438 0.19255 ... 281.848 -166.599 731.918.
  EXPECT_NEAR((*poses)[0](0, 0), 0.78603, 1e-5);
  EXPECT_NEAR((*poses)[0](0, 1), -0.587438, 1e-5);
  EXPECT_EQ((*poses)[0].translation(), Eigen::Vector3d(281.848, -166.599, 731.918));
  EXPECT_EQ((*poses)[30].translation(), Eigen::Vector3d(-81.9978, -31.0102, 386.45));
  for (const Eigen::Isometry3d& pose : *poses) {
    EXPECT_LT(OrthonormalityError(pose.linear()), 1e-14);
    EXPECT_GT(pose.translation().z(), 0.0);  // the object is in front of the camera
  }
  // Handheld motion at 30 fps: consecutive frames are close (at most ~27° and ~25 mm here), so
  // lines were neither skipped nor merged.
  for (size_t i = 1; i < poses->size(); ++i) {
    EXPECT_THAT((*poses)[i], PoseNear((*poses)[i - 1], 40.0, 50.0)) << "frame " << i;
  }
}

TEST(ReadPoseFileTest, ErrorNamesFileAndLineOfBadRotation) {
  test::TempDir dir;
  test::WriteText(dir.File("poses.txt"),
                  "1 0 0 0 1 0 0 0 1 0 0 0\r\n"
                  "1 0 0 0 1 0 0 0 1 0 0 0\r\n"
                  "1 0.1 0 0 1 0 0 0 1 0 0 0\r\n"
                  "1 0 0 0 1 0 0 0 1 0 0 0\r\n");
  const auto poses = ReadPoseFile(dir.File("poses.txt"));
  ASSERT_FALSE(poses.ok());
  EXPECT_EQ(poses.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(poses.status().message(),
              AllOf(HasSubstr(dir.File("poses.txt") + ":3: "), HasSubstr("orthonormal")));
}

TEST(ReadPoseFileTest, ErrorNamesLineOfWrongCount) {
  test::TempDir dir;
  test::WriteText(dir.File("poses.txt"), "1 0 0 0 1 0 0 0 1 0 0 0\n1 0 0 0 1 0 0 0 1 0 0\n");
  const auto poses = ReadPoseFile(dir.File("poses.txt"));
  ASSERT_FALSE(poses.ok());
  EXPECT_THAT(poses.status().message(), AllOf(HasSubstr("poses.txt:2: "), HasSubstr("got 11")));
}

TEST(ReadPoseFileTest, BlankLineInTheMiddleIsAnError) {
  test::TempDir dir;
  test::WriteText(dir.File("poses.txt"), "1 0 0 0 1 0 0 0 1 0 0 0\n\n1 0 0 0 1 0 0 0 1 0 0 0\n");
  const auto poses = ReadPoseFile(dir.File("poses.txt"));
  ASSERT_FALSE(poses.ok());
  EXPECT_EQ(poses.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(poses.status().message(), AllOf(HasSubstr("poses.txt:2: "), HasSubstr("blank")));
}

TEST(ReadPoseFileTest, MissingFileIsNotFound) {
  test::TempDir dir;
  const auto poses = ReadPoseFile(dir.File("nope.txt"));
  ASSERT_FALSE(poses.ok());
  EXPECT_EQ(poses.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(poses.status().message(), HasSubstr("nope.txt"));
}

TEST(WritePoseFileTest, UnwritablePathIsIoError) {
  test::TempDir dir;
  test::WriteText(dir.File("file"), "");
  const Status status = WritePoseFile(dir.File("file/poses.txt"), RandomPoses(1, 3));
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kIoError);
}

TEST(OrthonormalizeReadRotationTest, KeepsExactRotationsAndRepairsNearlyOrthonormal) {
  const Eigen::Matrix3d exact = ExpSO3(Eigen::Vector3d(0.3, -1.2, 2.0));
  Eigen::Matrix3d kept = exact;
  std::string why;
  ASSERT_TRUE(OrthonormalizeReadRotation(&kept, &why));
  EXPECT_TRUE(kept == exact);

  Eigen::Matrix3d rounded = (exact * 1e5).array().round() / 1e5;
  ASSERT_GT(OrthonormalityError(rounded), 1e-12);
  ASSERT_TRUE(OrthonormalizeReadRotation(&rounded, &why));
  EXPECT_LT(OrthonormalityError(rounded), 1e-14);
  EXPECT_LT(RotationDistanceDeg(rounded, exact), 1e-3);

  Eigen::Matrix3d bad = exact * 1.1;
  EXPECT_FALSE(OrthonormalizeReadRotation(&bad, &why));
  EXPECT_THAT(why, HasSubstr("orthonormal"));
  EXPECT_THAT(why, Not(HasSubstr("determinant")));
}

}  // namespace
}  // namespace bcot

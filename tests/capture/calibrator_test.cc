// Calibration on synthetic boards with known cameras (always runs) and on OpenCV's real stereo
// sample (skipped when ../shared/data is absent).
#include "bcot/capture/calibrator.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/rig_io.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

constexpr double kSquareMm = 25.0;

Eigen::Isometry3d Pose(double rx_deg, double ry_deg, double rz_deg, const Eigen::Vector3d& t) {
  const double d = M_PI / 180.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(rz_deg * d, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(ry_deg * d, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(rx_deg * d, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = t;
  return pose;
}

// Renders a 9×6-inner-corner board (25 mm squares, board frame: x, y along the corner grid,
// origin at the first inner corner) seen by `camera` at `cam_from_board`; 2× supersampled.
cv::Mat RenderBoard(const Camera& camera, const Eigen::Isometry3d& cam_from_board) {
  constexpr int kPxPerSquare = 40, kMarginPx = 40;
  cv::Mat texture(7 * kPxPerSquare + 2 * kMarginPx, 10 * kPxPerSquare + 2 * kMarginPx, CV_8UC1,
                  cv::Scalar(255));
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 10; ++x) {
      if ((x + y) % 2 == 0) {
        texture(cv::Rect(kMarginPx + x * kPxPerSquare, kMarginPx + y * kPxPerSquare, kPxPerSquare,
                         kPxPerSquare)) = 0;
      }
    }
  }
  // texture px → board mm (corner (0,0) sits at the edge between texture pixels, −0.5).
  const double s = kSquareMm / kPxPerSquare, offset = kMarginPx + kPxPerSquare - 0.5;
  Eigen::Matrix3d board_from_texture;
  board_from_texture << s, 0, -offset * s, 0, s, -offset * s, 0, 0, 1;
  const Camera big = camera.Scaled(2.0);
  Eigen::Matrix3d plane;
  plane << cam_from_board.linear().col(0), cam_from_board.linear().col(1),
      cam_from_board.translation();
  const Eigen::Matrix3d image_from_texture = big.K() * plane * board_from_texture;
  cv::Mat h;
  cv::eigen2cv(image_from_texture, h);
  cv::Mat rendered, image;
  cv::warpPerspective(texture, rendered, h, cv::Size(big.width, big.height), cv::INTER_LINEAR,
                      cv::BORDER_CONSTANT, cv::Scalar(150));
  cv::resize(rendered, image, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
  return image;
}

// A two-camera rig and 8 board views written as <dir>/cam0/NN.png and <dir>/cam1/NN.png.
class SyntheticCalibrationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    camera0_ = new Camera("cam0", 640, 480, 600.0, 600.0, 319.5, 239.5);
    camera1_ = new Camera("cam1", 640, 480, 620.0, 615.0, 325.0, 235.0);
    cam1_from_cam0_ = new Eigen::Isometry3d(Pose(0.0, 2.0, 0.5, Eigen::Vector3d::Zero()));
    cam1_from_cam0_->translation() = -(cam1_from_cam0_->linear() * Eigen::Vector3d(100, 0, 0));
    const double angles[8][3] = {{0, 0, 0},     {20, 0, 5},     {-20, 10, 0}, {0, 25, -10},
                                 {15, -20, 10}, {-15, -15, -5}, {25, 15, 0},  {-10, 30, 15}};
    for (int k = 0; k < 8; ++k) {
      // Board centre (112.5, 62.5) mm in the board frame lands near the optical axis.
      Eigen::Isometry3d cam0_from_board = Pose(angles[k][0], angles[k][1], angles[k][2],
                                               Eigen::Vector3d(-40.0 + 5 * k, 0.0, 600.0 + 10 * k));
      cam0_from_board.translation() -= cam0_from_board.linear() * Eigen::Vector3d(112.5, 62.5, 0);
      const std::string name = fmt::format("{:02d}.png", k);
      std::filesystem::create_directories(dir_->File("cam0"));
      std::filesystem::create_directories(dir_->File("cam1"));
      cv::imwrite(dir_->File("cam0/" + name), RenderBoard(*camera0_, cam0_from_board));
      cv::imwrite(dir_->File("cam1/" + name),
                  RenderBoard(*camera1_, *cam1_from_cam0_ * cam0_from_board));
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    delete camera0_;
    delete camera1_;
    delete cam1_from_cam0_;
  }

  static CalibrationOptions Options(const std::string& images_dir) {
    CalibrationOptions options;
    options.input.images_dir = images_dir;
    options.input.cameras = {"cam0", "cam1"};
    options.board.square_size_mm = kSquareMm;
    return options;
  }

  // A copy of the synthetic images to damage.
  static void CopyImages(const std::string& to) {
    std::filesystem::copy(dir_->path(), to, std::filesystem::copy_options::recursive);
  }

  static test::TempDir* dir_;
  static Camera* camera0_;
  static Camera* camera1_;
  static Eigen::Isometry3d* cam1_from_cam0_;
};
test::TempDir* SyntheticCalibrationTest::dir_ = nullptr;
Camera* SyntheticCalibrationTest::camera0_ = nullptr;
Camera* SyntheticCalibrationTest::camera1_ = nullptr;
Eigen::Isometry3d* SyntheticCalibrationTest::cam1_from_cam0_ = nullptr;

TEST_F(SyntheticCalibrationTest, RecoversIntrinsicsAndExtrinsics) {
  const StatusOr<CalibrationResult> result = Calibrate(Options(dir_->path()));
  ASSERT_TRUE(result.ok()) << result.status().message();
  ASSERT_EQ(result->rig.size(), 2);
  const Camera* truth[2] = {camera0_, camera1_};
  for (int c = 0; c < 2; ++c) {
    const Camera& estimate = result->rig[c].camera;
    EXPECT_EQ(result->cameras[c].num_used, 8);
    EXPECT_LT(result->cameras[c].rms_px, 0.3);
    EXPECT_NEAR(estimate.fx, truth[c]->fx, 0.01 * truth[c]->fx);
    EXPECT_NEAR(estimate.fy, truth[c]->fy, 0.01 * truth[c]->fy);
    EXPECT_NEAR(estimate.cx, truth[c]->cx, 3.0);
    EXPECT_NEAR(estimate.cy, truth[c]->cy, 3.0);
    EXPECT_EQ(estimate.width, 640);
  }
  EXPECT_THAT(result->rig[0].cam_from_rig, test::PoseNear(Eigen::Isometry3d::Identity(), 0, 0));
  EXPECT_THAT(result->rig[1].cam_from_rig, test::PoseNear(*cam1_from_cam0_, 0.2, 2.0));
  ASSERT_EQ(result->pairs.size(), 1u);
  EXPECT_EQ(result->pairs[0].views.size(), 8u);
  EXPECT_LT(result->pairs[0].rms_px, 0.3);
  EXPECT_TRUE(result->outliers.empty());
}

TEST_F(SyntheticCalibrationTest, WritesARigThatReadsBack) {
  const CalibrationOptions options = Options(dir_->path());
  const StatusOr<CalibrationResult> result = Calibrate(options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  test::TempDir out;
  ASSERT_TRUE(WriteCalibration(*result, options, out.path()).ok());
  const StatusOr<Rig> rig = ReadRigYaml(out.File("rig.yaml"));
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  EXPECT_THAT((*rig)[1].cam_from_rig, test::PoseNear(result->rig[1].cam_from_rig, 1e-9, 1e-9));
  const StatusOr<std::string> report = ReadTextFile(out.File("calibration_report.csv"));
  ASSERT_TRUE(report.ok());
  EXPECT_THAT(*report, HasSubstr("cam1,07,"));
  EXPECT_THAT(*report, HasSubstr("cam0+cam1,07,"));
}

TEST_F(SyntheticCalibrationTest, AnUnreadableImageIsAnErrorNamingTheFile) {
  test::TempDir copy;
  CopyImages(copy.File("imgs"));
  test::WriteText(copy.File("imgs/cam1/03.png"), "not a png");
  const StatusOr<CalibrationResult> result = Calibrate(Options(copy.File("imgs")));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(result.status().message(), HasSubstr("cam1/03.png"));
}

TEST_F(SyntheticCalibrationTest, AnImageOfAnotherSizeIsAnErrorNamingTheFile) {
  test::TempDir copy;
  CopyImages(copy.File("imgs"));
  const cv::Mat image = cv::imread(copy.File("imgs/cam0/05.png"));
  cv::Mat smaller;
  cv::resize(image, smaller, cv::Size(320, 240));
  cv::imwrite(copy.File("imgs/cam0/05.png"), smaller);
  const StatusOr<CalibrationResult> result = Calibrate(Options(copy.File("imgs")));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(result.status().message(), HasSubstr("cam0/05.png: image is 320x240"));
}

TEST_F(SyntheticCalibrationTest, ABoardNotFoundInAnyImageIsAClearError) {
  CalibrationOptions options = Options(dir_->path());
  options.board.inner_corners_x = 10;  // the board has 9×6 inner corners
  options.board.inner_corners_y = 7;
  const StatusOr<CalibrationResult> result = Calibrate(options);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(result.status().message(), HasSubstr("no 10x7 chessboard found in any of the 8"));
  EXPECT_THAT(result.status().message(), HasSubstr("camera 'cam0'"));
}

TEST_F(SyntheticCalibrationTest, MissingFolderOrCameraImagesAreNotFound) {
  CalibrationOptions options = Options(dir_->File("nope"));
  EXPECT_EQ(Calibrate(options).status().code(), StatusCode::kNotFound);
  options = Options(dir_->path());
  options.input.cameras = {"cam0", "cam7"};
  const StatusOr<CalibrationResult> result = Calibrate(options);
  EXPECT_EQ(result.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(result.status().message(), HasSubstr("camera 'cam7'"));
}

// OpenCV's real stereo sample: 13 pairs of 640×480, 9×6 inner corners.
TEST(StereoSampleCalibrationTest, CalibratesTheRealStereoPairs) {
  const std::string images = test::SourcePath("data/stereo_chessboard");
  CalibrationOptions options;
  options.input.images_dir = images;
  options.input.cameras = {"left", "right"};
  options.board.square_size_mm = kSquareMm;  // unknown for the sample; sets the unit only
  const StatusOr<CalibrationResult> result = Calibrate(options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  for (const CameraCalibration& camera : result->cameras) {
    EXPECT_EQ(camera.images.size(), 13u) << camera.name;
    EXPECT_EQ(camera.num_used, 13) << camera.name;
    EXPECT_LT(camera.rms_px, 0.8) << camera.name;
    EXPECT_GT(camera.rms_px, 0.0) << camera.name;
  }
  ASSERT_EQ(result->pairs.size(), 1u);
  EXPECT_EQ(result->pairs[0].views.size(), 13u);
  EXPECT_LT(result->pairs[0].rms_px, 0.8);
  // The right camera sits to the right of the left one (+x of the rig frame), roughly level.
  const Eigen::Isometry3d& right_from_rig = result->rig[1].cam_from_rig;
  const Eigen::Vector3d right_centre_in_rig = right_from_rig.inverse().translation();
  EXPECT_GT(right_centre_in_rig.x(), 0.95 * right_centre_in_rig.norm());
  EXPECT_LT(test::RotationErrorDeg(right_from_rig, Eigen::Isometry3d::Identity()), 5.0);
  std::printf(
      "stereo sample: RMS left %.3f px, right %.3f px, stereo %.3f px, baseline %.1f "
      "squares\n",
      result->cameras[0].rms_px, result->cameras[1].rms_px, result->pairs[0].rms_px,
      result->pairs[0].baseline_mm / kSquareMm);
}

}  // namespace
}  // namespace bcot

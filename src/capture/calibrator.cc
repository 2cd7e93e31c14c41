#include "bcot/capture/calibrator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/rig_io.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

constexpr int kMinViews = 3;

bool IsImageFile(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" ||
         ext == ".tiff";
}

// Images of camera `name`, sorted by view key (see the layout in calibration_options.h).
StatusOr<std::vector<CalibrationImage>> FindImages(const std::string& images_dir,
                                                   const std::string& name) {
  std::error_code error;
  const fs::path folder = fs::path(images_dir) / name;
  const bool use_folder = fs::is_directory(folder, error);
  const fs::path scan_dir = use_folder ? folder : fs::path(images_dir);
  std::vector<CalibrationImage> images;
  for (const fs::directory_entry& entry : fs::directory_iterator(scan_dir, error)) {
    const fs::path& path = entry.path();
    const std::string file = path.filename().string();
    if (file.empty() || file[0] == '.' || !IsImageFile(path) || !entry.is_regular_file(error)) {
      continue;
    }
    std::string key = path.stem().string();
    if (!use_folder) {
      if (key.compare(0, name.size(), name) != 0) continue;
      key = key.substr(name.size());
    }
    CalibrationImage image;
    image.view = key;
    image.path = path.string();
    images.push_back(std::move(image));
  }
  if (error) {
    return Status::IoError(fmt::format("{}: cannot list: {}", scan_dir.string(), error.message()));
  }
  std::sort(images.begin(), images.end(),
            [](const CalibrationImage& a, const CalibrationImage& b) { return a.view < b.view; });
  for (size_t i = 1; i < images.size(); ++i) {
    if (images[i].view == images[i - 1].view) {
      return Status::InvalidInput(fmt::format("{} and {}: two images of camera '{}' for view '{}'",
                                              images[i - 1].path, images[i].path, name,
                                              images[i].view));
    }
  }
  if (images.empty()) {
    return Status::NotFound(
        fmt::format("{}: no images for camera '{}' (expected {}/*.png|jpg or {}*.png|jpg)",
                    images_dir, name, folder.string(), (fs::path(images_dir) / name).string()));
  }
  return images;
}

// Board corners of every image of one camera (empty vector where not found).
struct Detections {
  cv::Size image_size;
  std::vector<std::vector<cv::Point2f>> corners;  // per image
};

StatusOr<Detections> DetectBoards(const CalibrationOptions& options,
                                  std::vector<CalibrationImage>* images,
                                  const std::function<void()>& on_image) {
  const cv::Size pattern(options.board.inner_corners_x, options.board.inner_corners_y);
  int flags = 0;
  if (options.detection.adaptive_threshold) {
    flags |= cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE;
  }
  if (options.detection.fast_check) flags |= cv::CALIB_CB_FAST_CHECK;
  const int half = options.detection.subpixel_half_window_px;
  Detections detections;
  std::string first_path;
  for (CalibrationImage& image : *images) {
    const cv::Mat gray = cv::imread(image.path, cv::IMREAD_GRAYSCALE);
    if (gray.empty()) {
      return Status::InvalidInput(
          fmt::format("{}: cannot read the image (unreadable or not an image file)", image.path));
    }
    if (detections.corners.empty()) {
      detections.image_size = gray.size();
      first_path = image.path;
    } else if (gray.size() != detections.image_size) {
      return Status::InvalidInput(
          fmt::format("{}: image is {}x{}, but {} is {}x{} (all images of "
                      "a camera must have the same size)",
                      image.path, gray.cols, gray.rows, first_path, detections.image_size.width,
                      detections.image_size.height));
    }
    std::vector<cv::Point2f> corners;
    image.board_found = cv::findChessboardCorners(gray, pattern, corners, flags);
    if (image.board_found) {
      cv::cornerSubPix(gray, corners, cv::Size(half, half), cv::Size(-1, -1),
                       cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
    } else {
      corners.clear();
    }
    detections.corners.push_back(std::move(corners));
    if (on_image) on_image();
  }
  return detections;
}

std::vector<cv::Point3f> BoardPoints(const CalibrationOptions::Board& board) {
  std::vector<cv::Point3f> points;
  for (int y = 0; y < board.inner_corners_y; ++y) {
    for (int x = 0; x < board.inner_corners_x; ++x) {
      points.emplace_back(static_cast<float>(x * board.square_size_mm),
                          static_cast<float>(y * board.square_size_mm), 0.0f);
    }
  }
  return points;
}

struct Intrinsics {
  cv::Mat K;
  cv::Mat distortion;
};

// Calibrates one camera from its used images, filling rms_px of each used image.
Intrinsics CalibrateIntrinsics(const CalibrationOptions& options, const Detections& detections,
                               CameraCalibration* camera) {
  const std::vector<cv::Point3f> board = BoardPoints(options.board);
  std::vector<std::vector<cv::Point3f>> object_points;
  std::vector<std::vector<cv::Point2f>> image_points;
  std::vector<int> image_index;
  for (size_t i = 0; i < camera->images.size(); ++i) {
    camera->images[i].rms_px = -1.0;
    if (!camera->images[i].used) continue;
    object_points.push_back(board);
    image_points.push_back(detections.corners[i]);
    image_index.push_back(static_cast<int>(i));
  }
  int flags = 0;
  if (options.model.fix_k3) flags |= cv::CALIB_FIX_K3;
  if (options.model.zero_tangential) flags |= cv::CALIB_ZERO_TANGENT_DIST;
  if (options.model.fix_aspect_ratio) flags |= cv::CALIB_FIX_ASPECT_RATIO;
  Intrinsics intrinsics;
  intrinsics.K = cv::Mat::eye(3, 3, CV_64F);  // fx/fy = 1 when the aspect ratio is fixed
  intrinsics.distortion = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat std_intrinsics, std_extrinsics, per_view_errors;
  camera->rms_px = cv::calibrateCamera(object_points, image_points, detections.image_size,
                                       intrinsics.K, intrinsics.distortion, rvecs, tvecs,
                                       std_intrinsics, std_extrinsics, per_view_errors, flags);
  for (size_t k = 0; k < image_index.size(); ++k) {
    camera->images[image_index[k]].rms_px = per_view_errors.at<double>(static_cast<int>(k));
  }
  camera->num_used = static_cast<int>(image_index.size());
  return intrinsics;
}

Camera ToCamera(const std::string& name, const cv::Size& size, const Intrinsics& intrinsics) {
  const cv::Mat& K = intrinsics.K;
  Camera camera(name, size.width, size.height, K.at<double>(0, 0), K.at<double>(1, 1),
                K.at<double>(0, 2), K.at<double>(1, 2));
  const cv::Mat d = intrinsics.distortion.reshape(1, 1);
  for (int i = 0; i < 5 && i < d.cols; ++i) camera.distortion[i] = d.at<double>(0, i);
  return camera;
}

std::string NoBoardMessage(const CalibrationOptions& options, const CameraCalibration& camera,
                           int found, const std::string& images_dir) {
  if (found == 0) {
    return fmt::format(
        "{}: no {}x{} chessboard found in any of the {} images of camera '{}' (check "
        "board.inner_corners_x/y: inner corners, not squares)",
        images_dir, options.board.inner_corners_x, options.board.inner_corners_y,
        camera.images.size(), camera.name);
  }
  return fmt::format("{}: camera '{}': the board was found in {} of {} images, need at least {}",
                     images_dir, camera.name, found, camera.images.size(), kMinViews);
}

}  // namespace

StatusOr<CalibrationResult> Calibrate(const CalibrationOptions& options,
                                      const CalibrationProgress& progress) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  const std::string& images_dir = options.input.images_dir;
  std::error_code error;
  if (!fs::is_directory(images_dir, error)) {
    return Status::NotFound(fmt::format("{}: images folder not found", images_dir));
  }

  CalibrationResult result;
  const int num_cameras = static_cast<int>(options.input.cameras.size());
  int total = 0;
  for (const std::string& name : options.input.cameras) {
    CameraCalibration camera;
    camera.name = name;
    BCOT_ASSIGN_OR_RETURN(camera.images, FindImages(images_dir, name));
    total += static_cast<int>(camera.images.size());
    result.cameras.push_back(std::move(camera));
  }

  // Detection and intrinsics, camera by camera.
  int done = 0;
  std::vector<Detections> detections(num_cameras);
  std::vector<Intrinsics> intrinsics(num_cameras);
  for (int c = 0; c < num_cameras; ++c) {
    CameraCalibration& camera = result.cameras[c];
    BCOT_ASSIGN_OR_RETURN(detections[c], DetectBoards(options, &camera.images, [&] {
                            if (progress) progress(++done, total);
                          }));
    int found = 0;
    for (CalibrationImage& image : camera.images) {
      image.used = image.board_found;
      found += image.board_found ? 1 : 0;
    }
    if (found < kMinViews) {
      return Status::InvalidInput(NoBoardMessage(options, camera, found, images_dir));
    }
    intrinsics[c] = CalibrateIntrinsics(options, detections[c], &camera);
    bool any_outlier = false;
    for (CalibrationImage& image : camera.images) {
      image.outlier = image.used && image.rms_px > options.outliers.max_rms_px;
      any_outlier = any_outlier || image.outlier;
    }
    if (any_outlier && options.outliers.drop) {
      int kept = 0;
      for (CalibrationImage& image : camera.images) {
        image.used = image.used && !image.outlier;
        kept += image.used ? 1 : 0;
      }
      if (kept < kMinViews) {
        return Status::InvalidInput(fmt::format(
            "{}: camera '{}': only {} images left after dropping outliers above {} px, need {}",
            images_dir, camera.name, kept, options.outliers.max_rms_px, kMinViews));
      }
      intrinsics[c] = CalibrateIntrinsics(options, detections[c], &camera);
    }
    for (const CalibrationImage& image : camera.images) {
      if (image.outlier) result.outliers.push_back(image.path);
    }
    RigCamera rig_camera;
    rig_camera.camera = ToCamera(camera.name, detections[c].image_size, intrinsics[c]);
    result.rig.Add(std::move(rig_camera));
  }

  // Extrinsics: each camera against the first over their shared views.
  const std::vector<cv::Point3f> board = BoardPoints(options.board);
  const CameraCalibration& first = result.cameras[0];
  std::vector<RigCamera> rig_cameras = result.rig.cameras();
  for (int c = 1; c < num_cameras; ++c) {
    const CameraCalibration& camera = result.cameras[c];
    std::map<std::string, int> index_in_c;
    for (size_t i = 0; i < camera.images.size(); ++i) {
      if (camera.images[i].used) index_in_c[camera.images[i].view] = static_cast<int>(i);
    }
    PairCalibration pair;
    pair.camera_index = c;
    std::vector<std::vector<cv::Point3f>> object_points;
    std::vector<std::vector<cv::Point2f>> points_first, points_c;
    for (size_t i = 0; i < first.images.size(); ++i) {
      if (!first.images[i].used) continue;
      const auto it = index_in_c.find(first.images[i].view);
      if (it == index_in_c.end()) continue;
      pair.views.push_back(first.images[i].view);
      object_points.push_back(board);
      points_first.push_back(detections[0].corners[i]);
      points_c.push_back(detections[c].corners[it->second]);
    }
    if (static_cast<int>(pair.views.size()) < kMinViews) {
      return Status::InvalidInput(fmt::format(
          "{}: cameras '{}' and '{}' see the board together in {} views, need at least {} "
          "(views are paired by file name)",
          images_dir, first.name, camera.name, pair.views.size(), kMinViews));
    }
    cv::Mat R, T, E, F, per_view_errors;
    pair.rms_px = cv::stereoCalibrate(
        object_points, points_first, points_c, intrinsics[0].K, intrinsics[0].distortion,
        intrinsics[c].K, intrinsics[c].distortion, detections[0].image_size, R, T, E, F,
        per_view_errors, cv::CALIB_FIX_INTRINSIC,
        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-6));
    for (size_t v = 0; v < pair.views.size(); ++v) {
      const double e0 = per_view_errors.at<double>(static_cast<int>(v), 0);
      const double e1 = per_view_errors.at<double>(static_cast<int>(v), 1);
      const double rms = std::sqrt(0.5 * (e0 * e0 + e1 * e1));
      pair.view_rms_px.push_back(rms);
      pair.view_outlier.push_back(rms > options.outliers.max_rms_px);
      if (pair.view_outlier.back()) {
        result.outliers.push_back(
            fmt::format("view {} ({}+{})", pair.views[v], first.name, camera.name));
      }
    }
    Eigen::Matrix3d rotation;
    Eigen::Vector3d translation;
    cv::cv2eigen(R, rotation);
    cv::cv2eigen(T, translation);
    rig_cameras[c].cam_from_rig.linear() = rotation;
    rig_cameras[c].cam_from_rig.translation() = translation;
    pair.baseline_mm = translation.norm();
    result.pairs.push_back(std::move(pair));
  }
  result.rig = Rig(std::move(rig_cameras));
  const Status valid = result.rig.Validate();
  if (!valid.ok()) {
    return Status::Internal("calibration produced an invalid rig: " + valid.message());
  }
  return result;
}

std::string FormatCalibrationReport(const CalibrationResult& result) {
  std::string csv = "camera,view,image,board_found,rms_px,outlier\n";
  for (const CameraCalibration& camera : result.cameras) {
    for (const CalibrationImage& image : camera.images) {
      csv += fmt::format(
          "{},{},{},{},{},{}\n", camera.name, image.view, image.path, image.board_found ? 1 : 0,
          image.rms_px >= 0.0 ? fmt::format("{:.4f}", image.rms_px) : "", image.outlier ? 1 : 0);
    }
  }
  for (const PairCalibration& pair : result.pairs) {
    const std::string name = result.cameras[0].name + "+" + result.cameras[pair.camera_index].name;
    for (size_t v = 0; v < pair.views.size(); ++v) {
      csv += fmt::format("{},{},,,{:.4f},{}\n", name, pair.views[v], pair.view_rms_px[v],
                         pair.view_outlier[v] ? 1 : 0);
    }
  }
  return csv;
}

std::string FormatCalibrationSummary(const CalibrationResult& result) {
  std::string text;
  for (size_t c = 0; c < result.cameras.size(); ++c) {
    const CameraCalibration& camera = result.cameras[c];
    const Camera& intrinsics = result.rig[static_cast<int>(c)].camera;
    int found = 0;
    for (const CalibrationImage& image : camera.images) found += image.board_found ? 1 : 0;
    text += fmt::format(
        "camera {}: board in {}/{} images, {} used, RMS {:.3f} px, fx {:.2f} fy {:.2f} cx {:.2f} "
        "cy {:.2f}\n",
        camera.name, found, camera.images.size(), camera.num_used, camera.rms_px, intrinsics.fx,
        intrinsics.fy, intrinsics.cx, intrinsics.cy);
  }
  for (const PairCalibration& pair : result.pairs) {
    text += fmt::format("pair {}+{}: {} shared views, stereo RMS {:.3f} px, baseline {:.2f} mm\n",
                        result.cameras[0].name, result.cameras[pair.camera_index].name,
                        pair.views.size(), pair.rms_px, pair.baseline_mm);
  }
  if (result.outliers.empty()) {
    text += "outliers: none\n";
  } else {
    text += fmt::format("outliers ({}): {}\n", result.outliers.size(),
                        fmt::join(result.outliers, ", "));
  }
  return text;
}

Status WriteCalibration(const CalibrationResult& result, const CalibrationOptions& options,
                        const std::string& out_dir) {
  BCOT_RETURN_IF_ERROR(CreateDirectories(out_dir));
  const fs::path dir(out_dir);
  BCOT_RETURN_IF_ERROR(WriteFileAtomic((dir / "calibrate.resolved.yaml").string(),
                                       FormatCalibrationOptions(options)));
  BCOT_RETURN_IF_ERROR(
      WriteFileAtomic((dir / "calibration_report.csv").string(), FormatCalibrationReport(result)));
  // Written last: a folder with rig.yaml holds a complete calibration.
  return WriteRigYaml((dir / "rig.yaml").string(), result.rig);
}

}  // namespace bcot

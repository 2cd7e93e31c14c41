#include "bcot/annotate/moving_object_finder.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "bcot/annotate/initializer.h"
#include "bcot/core/image_io.h"

namespace bcot {
namespace {

// Frames spread evenly over [0, num_frames), `frame` among them (replacing the nearest).
std::vector<int> SampleFrames(int num_frames, int frame, int count) {
  count = std::min(count, num_frames);
  std::vector<int> frames(count);
  for (int k = 0; k < count; ++k) {
    frames[k] = static_cast<int>(std::lround(k * (num_frames - 1.0) / std::max(1, count - 1)));
  }
  const auto nearest = std::min_element(frames.begin(), frames.end(), [frame](int a, int b) {
    return std::abs(a - frame) < std::abs(b - frame);
  });
  *nearest = frame;
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

// Per-pixel, per-channel median of the images (all of one size).
cv::Mat3b MedianImage(const std::vector<cv::Mat3b>& images) {
  cv::Mat3b median(images[0].size());
  std::vector<uchar> values(images.size());
  const size_t middle = values.size() / 2;
  for (int y = 0; y < median.rows; ++y) {
    for (int x = 0; x < median.cols; ++x) {
      for (int c = 0; c < 3; ++c) {
        for (size_t k = 0; k < images.size(); ++k) values[k] = images[k](y, x)[c];
        std::nth_element(values.begin(), values.begin() + middle, values.end());
        median(y, x)[c] = values[middle];
      }
    }
  }
  return median;
}

// Steps 2 and 3 of the header comment on the resized images; `scale` = capture px per work px.
MovingObjectView LocateChange(const cv::Mat3b& image, const cv::Mat3b& background,
                              const Eigen::Vector2d& scale, const MovingObjectOptions& options) {
  MovingObjectView view;
  cv::Mat1f change(image.size());
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      float largest = 0.0f;
      for (int c = 0; c < 3; ++c) {
        largest = std::max(largest, std::abs(static_cast<float>(image(y, x)[c]) -
                                             static_cast<float>(background(y, x)[c])));
      }
      change(y, x) = largest;
    }
  }
  std::vector<float> values(change.begin(), change.end());
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const double sigma = std::max(1.0, 1.4826 * values[values.size() / 2]);
  const double threshold = std::max(options.threshold_sigmas * sigma, options.min_change);
  cv::Mat1b changed = change > threshold;
  cv::morphologyEx(changed, changed, cv::MORPH_OPEN, cv::Mat::ones(3, 3, CV_8U));
  cv::morphologyEx(changed, changed, cv::MORPH_CLOSE, cv::Mat::ones(7, 7, CV_8U));
  const double area = static_cast<double>(image.total());
  view.changed_fraction = cv::countNonZero(changed) / area;
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(changed, labels, stats, centroids, 8);
  int best = 0;
  for (int label = 1; label < count; ++label) {
    if (best == 0 ||
        stats.at<int>(label, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) {
      best = label;
    }
  }
  if (best == 0) return view;
  view.area_fraction = stats.at<int>(best, cv::CC_STAT_AREA) / area;
  if (view.area_fraction < options.min_area_fraction) return view;
  view.found = true;
  // Pixel centres: work pixel u covers capture pixels [u·s − 0.5, (u + 1)·s − 0.5].
  view.centroid_px = Eigen::Vector2d((centroids.at<double>(best, 0) + 0.5) * scale.x() - 0.5,
                                     (centroids.at<double>(best, 1) + 0.5) * scale.y() - 0.5);
  return view;
}

}  // namespace

Status MovingObjectOptions::Validate() const {
  InitOptions options;
  options.search.motion = *this;
  return InitOptionSchema().Validate(options, nullptr);
}

StatusOr<std::vector<MovingObjectView>> FindMovingObject(const Sequence& sequence, int frame,
                                                         const MovingObjectOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_CHECK(frame >= 0 && frame < sequence.num_frames);
  if (sequence.num_frames < 3) {
    return Status::InvalidInput(fmt::format(
        "finding the object by its motion needs at least 3 frames, the sequence has {}; give "
        "--click CAM:X,Y",
        sequence.num_frames));
  }
  const std::vector<int> frames = SampleFrames(sequence.num_frames, frame, options.frames);
  const int target =
      static_cast<int>(std::find(frames.begin(), frames.end(), frame) - frames.begin());
  const int num_views = sequence.rig.size();
  std::vector<MovingObjectView> views(num_views);
  std::vector<Status> errors(num_views);
  tbb::parallel_for(0, num_views, [&](int v) {
    const Camera& camera = sequence.rig[v].camera;
    const double shrink = std::max(1.0, static_cast<double>(camera.width) / options.work_width_px);
    const cv::Size work_size(std::max(1, static_cast<int>(std::lround(camera.width / shrink))),
                             std::max(1, static_cast<int>(std::lround(camera.height / shrink))));
    const Eigen::Vector2d scale(static_cast<double>(camera.width) / work_size.width,
                                static_cast<double>(camera.height) / work_size.height);
    std::vector<cv::Mat3b> images;
    for (int f : frames) {
      StatusOr<cv::Mat3b> image = ReadCameraImage(sequence.image_paths[v][f], camera);
      if (!image.ok()) {
        errors[v] = image.status();
        return;
      }
      cv::Mat3b resized;
      cv::resize(*image, resized, work_size, 0, 0, cv::INTER_AREA);
      images.push_back(resized);
    }
    views[v] = LocateChange(images[target], MedianImage(images), scale, options);
    views[v].camera = camera.name;
  });
  for (const Status& error : errors) BCOT_RETURN_IF_ERROR(error);
  return views;
}

}  // namespace bcot

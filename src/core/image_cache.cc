#include "bcot/core/image_cache.h"

#include "bcot/core/image_io.h"

namespace bcot {

DecodedImageCache::DecodedImageCache(size_t budget_bytes) : budget_bytes_(budget_bytes) {}

StatusOr<cv::Mat3b> DecodedImageCache::Read(const std::string& path, const Camera& camera) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto kept = images_.find(path);
    if (kept != images_.end()) {
      // The size was checked against a camera when the image was kept; a different camera
      // reading the same file is checked again.
      if (kept->second.cols == camera.width && kept->second.rows == camera.height) {
        ++hits_;
        return kept->second;  // shares the kept pixels (header: read-only)
      }
    }
  }
  StatusOr<cv::Mat3b> image = ReadCameraImage(path, camera);
  if (!image.ok()) return image;
  const size_t size = image->total() * image->elemSize();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (bytes_ + size <= budget_bytes_ && images_.count(path) == 0) {
    images_.emplace(path, *image);  // the decoded pixels themselves, shared with the caller
    bytes_ += size;
  }
  return image;
}

size_t DecodedImageCache::bytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}

size_t DecodedImageCache::hits() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}

StatusOr<cv::Mat3b> ReadCameraImage(const std::string& path, const Camera& camera,
                                    DecodedImageCache* cache) {
  return cache != nullptr ? cache->Read(path, camera) : ReadCameraImage(path, camera);
}

}  // namespace bcot

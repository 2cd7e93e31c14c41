// Decoded frames kept in memory for a second pass over a sequence. `bcot annotate` decodes
// every image to solve it and again to measure the quality of the final poses, which are only
// known after the temporal window; decoding a 960×768 frame costs 10–15 ms (PNG, JPEG), about a
// tenth of a binocular frame's annotation (docs/notes/issue19_speed.md, "Decoding each image
// once"). The cache keeps decoded images in the order they are first read until a byte budget
// is spent, so a sequential second pass finds the first frames of a long sequence in memory
// and decodes the rest again.
//
// Thread safety: Read may be called concurrently; decoding happens outside the lock.
#pragma once

#include <cstddef>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <unordered_map>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"

namespace bcot {

class DecodedImageCache {
 public:
  // `budget_bytes`: the most pixel bytes kept; 0 keeps nothing (every Read decodes).
  explicit DecodedImageCache(size_t budget_bytes);

  // ReadCameraImage(path, camera) (image_io.h), answered from memory when `path` was kept. A
  // decoded image is kept while it fits in what is left of the budget. A kept image's pixels are
  // shared (cv::Mat's reference counting) by the cache and every image returned for `path`, so
  // a reader must not write into them: every reader in the library takes frames as const (the
  // tracker, the quality check). Copying a 960×768 frame in and out of the cache, with the page
  // faults of its fresh buffers, cost about 3 % of a JPEG annotation's CPU
  // (docs/notes/issue19_speed.md, "The decoded-image cache without copies").
  StatusOr<cv::Mat3b> Read(const std::string& path, const Camera& camera);

  size_t bytes() const;  // pixel bytes kept
  size_t hits() const;   // reads answered from memory

 private:
  const size_t budget_bytes_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, cv::Mat3b> images_;
  size_t bytes_ = 0;
  size_t hits_ = 0;
};

// `cache->Read(path, camera)`, or ReadCameraImage(path, camera) without a cache.
StatusOr<cv::Mat3b> ReadCameraImage(const std::string& path, const Camera& camera,
                                    DecodedImageCache* cache);

}  // namespace bcot

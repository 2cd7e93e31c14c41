// The interface a monocular 6DoF tracker implements to be evaluated online by `bcot eval`
// (evaluator.h runs the BCOT/RBOT protocol against it).
//
// Frames: poses are cam_from_object, object = the mesh template frame O_t, translations in mm,
// OpenCV camera frame. Images are 8-bit BGR, undistorted, of the camera's size.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"

namespace bcot {

// One tracker instance follows one object through one sequence. Not thread-safe.
class MonocularTracker {
 public:
  virtual ~MonocularTracker() = default;

  // (Re)initialises the tracker on `image` at the known pose: called on frame 0 with its GT,
  // and again on any frame whose estimate failed the protocol's reset test, with that frame's
  // GT (the tracker should rebuild its appearance model there, as after initialisation).
  virtual Status Reset(const cv::Mat3b& image, const Eigen::Isometry3d& cam_from_object) = 0;

  // Estimates cam_from_object on the next frame, starting from its own last estimate (or the
  // pose of the last Reset). An error status counts the frame as lost (and triggers a reset);
  // it does not abort the evaluation.
  virtual StatusOr<Eigen::Isometry3d> Track(const cv::Mat3b& image) = 0;
};

// Builds a tracker for one sequence. `camera`: pinhole intrinsics with the image size set, no
// distortion. `mesh`: the object in mm, O_t; it outlives the returned tracker. Errors abort the
// evaluation (bad tracker configuration, unusable mesh).
using MonocularTrackerFactory = std::function<StatusOr<std::unique_ptr<MonocularTracker>>(
    const Camera& camera, const Mesh& mesh)>;

}  // namespace bcot

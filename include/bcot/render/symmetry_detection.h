// Finds whether a mesh is a body of revolution, as far as silhouettes can tell
// (core/rotational_symmetry.h says what the annotation does with one).
//
// 1. Candidates from the surface's second moments: a body of revolution has two equal
//    principal moments, and its axis is the third principal direction through the surface's
//    centroid. Moments within `moment_tolerance` (relative to the largest) make a candidate; a
//    mesh whose three moments agree (a cube, a sphere) gives three.
// 2. Each candidate is checked where it matters to the energies: silhouettes. From four view
//    directions (90°, 80°, 60° and 30° from the axis, different azimuths) the mesh is rendered
//    as is and turned about the axis by four angles that are no multiple of 30°, 45° or 72°
//    (so an n-fold part such as a gear or a nut fails); the mean displacement between the two
//    silhouettes is the differing area over the boundary's length. The worst of the 16, as a
//    fraction of the object's diameter in that image, must stay within `tolerance`.
// A candidate that passes is the symmetry. When two or more pass (a sphere), none is returned:
// a sphere's pose has three unobservable directions, which this does not handle.
//
// Frames: the mesh's template frame O_t (mm), like RayCaster. Thread safety: const on the
// caster; renders run in parallel (TBB) inside.
#pragma once

#include <optional>
#include <vector>

#include "bcot/core/rotational_symmetry.h"
#include "bcot/core/status.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct SymmetryDetectionOptions {
  // Largest relative difference (to the largest moment) of two principal moments of the
  // surface that makes their common axis a candidate; in (0, 0.5).
  double moment_tolerance = 0.01;
  // Largest mean silhouette displacement, as a fraction of the object's diameter in the image,
  // for which a turn about the axis counts as invisible; in (0, 0.1). 0.001: 0.25 px on an
  // object 250 px across (the edge stage measures a contour to ~0.05 px, but a displacement this
  // small, spread along the whole contour, moves the pose by less than its own noise).
  // Measured (tests/render/symmetry_detection_test.cc): a 64-sided cylinder 0.0001, an 8-sided
  // prism 0.009, the pinion of data/meshes (a gear) 0.02, a cube 0.06.
  double tolerance = 0.001;
  // Width and height (px) of the check's renders, rendered with 2×2 rays per pixel; in
  // [64, 2048].
  int image_px = 192;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// One candidate axis and what the silhouettes said of it.
struct SymmetryCandidate {
  RotationalSymmetry symmetry;
  double moment_gap = 0.0;    // relative difference of its two equal moments
  double displacement = 0.0;  // worst mean silhouette displacement / diameter (step 2)
  bool symmetric = false;     // displacement <= tolerance
};

// The mesh's symmetry in O_t, if it has exactly one. `candidates`, when not null, receives every
// candidate checked (empty for a mesh with three distinct moments).
StatusOr<std::optional<RotationalSymmetry>> DetectRotationalSymmetry(
    const RayCaster& caster, const SymmetryDetectionOptions& options,
    std::vector<SymmetryCandidate>* candidates = nullptr);

}  // namespace bcot

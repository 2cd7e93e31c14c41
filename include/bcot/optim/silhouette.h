// The projected silhouette of the object in one view at one pose: the full-image mask and the
// sub-pixel contour. It is the sample set of the colour models (which pixels are foreground,
// which background, where the contour regions sit) and the geometry of the region template.
//
// Frames: `cam_from_template` maps the mesh's template frame O_t to the camera (mm); contour
// model points are in O_t as RayCaster returns them. Pixel centres at integer coordinates.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/status.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct Silhouette {
  // camera.height × camera.width; 255 where the pixel centre's ray hits the mesh. Filled from
  // the contour (FillContour) when the object's box lies inside the image and no model point
  // is needed at every pixel: then a pixel centre within the contour's precision_px of the
  // boundary, or on a part thinner than its coarse grid, may differ from its ray (about 5 of
  // 21,000 pixels of the bunny in scripts/bench_throughput.sh's 960×768 sequence).
  cv::Mat1b mask;
  // The render over the projected bounding box (one sample per pixel): point_in_object (O_t)
  // of the inside pixels of its point grid; depth, normals and triangle ids are not rendered
  // (empty), nor point_in_object by RenderSilhouetteContour and RenderSilhouetteMask. Its mask
  // holds the grid's rays (with a point stride > 1 only the stride pixels; elsewhere 0) or,
  // without points, the box's part of `mask`.
  RenderedView view;
  // Sub-pixel contour (outer boundaries and holes), outward normals, exact model points.
  std::vector<ContourPoint> contour;
};

// Renders the silhouette. `contour_options` must be valid (CHECKed by the ray caster). An
// object outside the image or behind the camera gives an all-zero mask and no contour.
// `point_stride_px` >= 1: view.point_in_object only at pixels whose column and row are
// multiples of it (RenderOptions::point_stride_px), enough for a region template of that
// stride (or a multiple) at a fraction of the closest-hit rays.
Silhouette RenderSilhouette(const RayCaster& caster, const Camera& camera,
                            const Eigen::Isometry3d& cam_from_template,
                            const ContourOptions& contour_options = {}, int point_stride_px = 1);

// The mask and contour of RenderSilhouette without per-pixel model points (view.point_in_object
// empty): for consumers that read the mask and the contour only (colour models, the quality
// check), saving a closest-hit ray per pixel.
Silhouette RenderSilhouetteContour(const RayCaster& caster, const Camera& camera,
                                   const Eigen::Isometry3d& cam_from_template,
                                   const ContourOptions& contour_options = {});

// The mask of RenderSilhouette without the contour (left empty; one of 1/16 px precision is
// traced for the mask): for consumers that only read the mask (ColorModel::UsesContour()
// false).
Silhouette RenderSilhouetteMask(const RayCaster& caster, const Camera& camera,
                                const Eigen::Isometry3d& cam_from_template);

// Checks a view's image: a valid camera and an image of its size (kInvalidConfig /
// kInvalidInput naming the camera).
Status CheckViewImage(const Camera& camera, const cv::Mat3b& image);
// Checks what the templates built on a silhouette need: a valid camera, an image of the
// camera's size and a mask of the image's size (kInvalidConfig / kInvalidInput naming the
// camera).
Status CheckSilhouetteInputs(const Camera& camera, const cv::Mat3b& image,
                             const Silhouette& silhouette);

}  // namespace bcot

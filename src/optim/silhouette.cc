#include "bcot/optim/silhouette.h"

#include <fmt/format.h>

#include "bcot/render/contour_drawing.h"

namespace bcot {

Status CheckViewImage(const Camera& camera, const cv::Mat3b& image) {
  BCOT_RETURN_IF_ERROR(camera.Validate());
  if (image.cols != camera.width || image.rows != camera.height) {
    return Status::InvalidInput(fmt::format("camera '{}': image is {}x{}, camera expects {}x{}",
                                            camera.name, image.cols, image.rows, camera.width,
                                            camera.height));
  }
  return Status::Ok();
}

Status CheckSilhouetteInputs(const Camera& camera, const cv::Mat3b& image,
                             const Silhouette& silhouette) {
  BCOT_RETURN_IF_ERROR(CheckViewImage(camera, image));
  if (silhouette.mask.size() != image.size()) {
    return Status::InvalidInput(fmt::format("camera '{}': silhouette mask is {}x{}, image {}x{}",
                                            camera.name, silhouette.mask.cols, silhouette.mask.rows,
                                            image.cols, image.rows));
  }
  return Status::Ok();
}

namespace {

// A render of the mask and, when `points`, the model points on the `point_stride_px` grid: no
// depth, normals or triangle ids.
RenderOptions MaskAndPointsOptions(bool points, int point_stride_px) {
  RenderOptions render_options;
  render_options.depth = render_options.normal_in_cam = render_options.triangle_id = false;
  render_options.point_in_object = points;
  render_options.point_stride_px = point_stride_px;
  return render_options;
}

// The silhouette's mask and render over the projected bounding box grown by `margin_px`;
// `points`: with point_in_object on the `point_stride_px` grid (else occlusion rays only).
Silhouette RenderMask(const RayCaster& caster, const Camera& camera,
                      const Eigen::Isometry3d& cam_from_template, int margin_px, bool points,
                      int point_stride_px) {
  Silhouette silhouette;
  silhouette.mask = cv::Mat1b::zeros(camera.height, camera.width);
  RenderOptions render_options = MaskAndPointsOptions(points, point_stride_px);
  render_options.margin_px = margin_px;
  silhouette.view = caster.Render(camera, cam_from_template, render_options);
  const cv::Rect image_rect(0, 0, camera.width, camera.height);
  const cv::Rect inside = silhouette.view.roi & image_rect;
  if (!inside.empty() && !silhouette.view.mask.empty()) {
    const cv::Rect in_view(inside.tl() - silhouette.view.roi.tl(), inside.size());
    silhouette.view.mask(in_view).copyTo(silhouette.mask(inside));
  }
  return silhouette;
}

// True when `box` (the contour's) lies inside the image with a pixel to spare. Where the
// object leaves the image its contour has gaps along the border (no bracket there), which a
// filled polygon would close with chords.
bool InsideImage(const cv::Rect& box, const Camera& camera) {
  return !box.empty() && box.x > 0 && box.y > 0 && box.x + box.width < camera.width &&
         box.y + box.height < camera.height;
}

// The silhouette from its contour: ExtractContour traces its coarse grid itself (the same rays
// as it would read from a full render's mask), the mask is filled from the contour
// (FillContour), and when `points`, the model points come from closest-hit rays on the
// `point_stride_px` grid only (RenderOptions::mask_everywhere false). Saves the occlusion ray
// of every other pixel of the box (docs/notes/issue19_speed.md, "The mask from the contour").
// `box` is the contour's: the projected bounding box grown by contour_options.margin_px.
Silhouette RenderFromContour(const RayCaster& caster, const Camera& camera,
                             const Eigen::Isometry3d& cam_from_template,
                             const ContourOptions& contour_options, const cv::Rect& box,
                             bool points, int point_stride_px) {
  Silhouette silhouette;
  silhouette.contour =
      caster.ExtractContour(camera, cam_from_template, contour_options, /*rendered=*/nullptr);
  silhouette.mask = cv::Mat1b::zeros(camera.height, camera.width);
  FillContour(silhouette.contour, &silhouette.mask);
  if (points) {
    RenderOptions render_options = MaskAndPointsOptions(/*points=*/true, point_stride_px);
    render_options.roi = box;
    render_options.mask_everywhere = false;
    silhouette.view = caster.Render(camera, cam_from_template, render_options);
  } else {
    silhouette.view.roi = box;
    silhouette.mask(box).copyTo(silhouette.view.mask);
  }
  return silhouette;
}

// The silhouette from its contour where that is exact enough (see RenderFromContour), else
// from a render of the whole box (RenderMask) with the contour read from its mask. Without
// `keep_contour` the contour is only the means of the mask and is left empty.
Silhouette RenderSilhouetteOf(const RayCaster& caster, const Camera& camera,
                              const Eigen::Isometry3d& cam_from_template,
                              const ContourOptions& contour_options, bool points,
                              int point_stride_px, bool keep_contour) {
  const cv::Rect box =
      caster.ProjectedBoundingBox(camera, cam_from_template, contour_options.margin_px);
  if ((!points || point_stride_px > 1) && InsideImage(box, camera)) {
    Silhouette silhouette = RenderFromContour(caster, camera, cam_from_template, contour_options,
                                              box, points, point_stride_px);
    if (!keep_contour) silhouette.contour.clear();
    return silhouette;
  }
  Silhouette silhouette = RenderMask(caster, camera, cam_from_template, contour_options.margin_px,
                                     points, point_stride_px);
  // Rendered over the contour's box, so that the contour reads its coarse grid from the mask.
  if (keep_contour) {
    silhouette.contour =
        caster.ExtractContour(camera, cam_from_template, contour_options, &silhouette.view);
  }
  return silhouette;
}

}  // namespace

Silhouette RenderSilhouetteMask(const RayCaster& caster, const Camera& camera,
                                const Eigen::Isometry3d& cam_from_template) {
  // The contour is only the means of the mask here: a coarser precision than the templates'
  // is enough (a pixel centre is misjudged only within it of the boundary).
  ContourOptions contour_options;
  contour_options.margin_px = 2;
  contour_options.precision_px = 1.0 / 16.0;
  return RenderSilhouetteOf(caster, camera, cam_from_template, contour_options, false, 1,
                            /*keep_contour=*/false);
}

Silhouette RenderSilhouetteContour(const RayCaster& caster, const Camera& camera,
                                   const Eigen::Isometry3d& cam_from_template,
                                   const ContourOptions& contour_options) {
  return RenderSilhouetteOf(caster, camera, cam_from_template, contour_options, false, 1,
                            /*keep_contour=*/true);
}

Silhouette RenderSilhouette(const RayCaster& caster, const Camera& camera,
                            const Eigen::Isometry3d& cam_from_template,
                            const ContourOptions& contour_options, int point_stride_px) {
  return RenderSilhouetteOf(caster, camera, cam_from_template, contour_options, true,
                            point_stride_px, /*keep_contour=*/true);
}

}  // namespace bcot

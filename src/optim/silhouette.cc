#include "bcot/optim/silhouette.h"

#include <fmt/format.h>

namespace bcot {

Status CheckSilhouetteInputs(const Camera& camera, const cv::Mat3b& image,
                             const Silhouette& silhouette) {
  BCOT_RETURN_IF_ERROR(camera.Validate());
  if (image.cols != camera.width || image.rows != camera.height) {
    return Status::InvalidInput(fmt::format("camera '{}': image is {}x{}, camera expects {}x{}",
                                            camera.name, image.cols, image.rows, camera.width,
                                            camera.height));
  }
  if (silhouette.mask.size() != image.size()) {
    return Status::InvalidInput(fmt::format("camera '{}': silhouette mask is {}x{}, image {}x{}",
                                            camera.name, silhouette.mask.cols, silhouette.mask.rows,
                                            image.cols, image.rows));
  }
  return Status::Ok();
}

namespace {

// The silhouette's mask and render over the projected bounding box grown by `margin_px`;
// `points`: with point_in_object on the `point_stride_px` grid (else occlusion rays only).
Silhouette RenderMask(const RayCaster& caster, const Camera& camera,
                      const Eigen::Isometry3d& cam_from_template, int margin_px, bool points,
                      int point_stride_px) {
  Silhouette silhouette;
  silhouette.mask = cv::Mat1b::zeros(camera.height, camera.width);
  RenderOptions render_options;
  render_options.margin_px = margin_px;
  // The mask, and the model points when asked for: no depth, normals or triangle ids.
  render_options.depth = render_options.normal_in_cam = render_options.triangle_id = false;
  render_options.point_in_object = points;
  render_options.point_stride_px = point_stride_px;
  silhouette.view = caster.Render(camera, cam_from_template, render_options);
  const cv::Rect image_rect(0, 0, camera.width, camera.height);
  const cv::Rect inside = silhouette.view.roi & image_rect;
  if (!inside.empty() && !silhouette.view.mask.empty()) {
    const cv::Rect in_view(inside.tl() - silhouette.view.roi.tl(), inside.size());
    silhouette.view.mask(in_view).copyTo(silhouette.mask(inside));
  }
  return silhouette;
}

}  // namespace

Silhouette RenderSilhouetteMask(const RayCaster& caster, const Camera& camera,
                                const Eigen::Isometry3d& cam_from_template) {
  return RenderMask(caster, camera, cam_from_template, /*margin_px=*/2, /*points=*/false, 1);
}

Silhouette RenderSilhouetteContour(const RayCaster& caster, const Camera& camera,
                                   const Eigen::Isometry3d& cam_from_template,
                                   const ContourOptions& contour_options) {
  // Rendered over the contour's box, so that the contour reads its coarse grid from the mask.
  Silhouette silhouette = RenderMask(caster, camera, cam_from_template, contour_options.margin_px,
                                     /*points=*/false, 1);
  silhouette.contour =
      caster.ExtractContour(camera, cam_from_template, contour_options, &silhouette.view);
  return silhouette;
}

Silhouette RenderSilhouette(const RayCaster& caster, const Camera& camera,
                            const Eigen::Isometry3d& cam_from_template,
                            const ContourOptions& contour_options, int point_stride_px) {
  Silhouette silhouette = RenderMask(caster, camera, cam_from_template, contour_options.margin_px,
                                     /*points=*/true, point_stride_px);
  silhouette.contour =
      caster.ExtractContour(camera, cam_from_template, contour_options, &silhouette.view);
  return silhouette;
}

}  // namespace bcot

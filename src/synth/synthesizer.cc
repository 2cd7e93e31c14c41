#include "bcot/synth/synthesizer.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <utility>

#include "bcot/core/file_util.h"
#include "bcot/core/object_io.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/rig_io.h"
#include "bcot/core/se3.h"
#include "bcot/render/mesh_writer.h"
#include "bcot/synth/synth_appearance.h"

namespace bcot {
namespace {

constexpr double kDegToRad = kPi / 180.0;
constexpr int kStripRows = 8;  // rows per parallel work item

// Per-triangle data for smooth shading: barycentrics of a hit point and crease-aware corner
// normals (object frame).
struct TriangleShading {
  Eigen::Vector3f v0, e1, e2;
  float d00 = 0, d01 = 0, d11 = 0, inv_denom = 0;
  Eigen::Vector3f face;  // unit normal of the stored winding
  Eigen::Vector3f corner[3];
};

// A mesh with its ray caster, shading data and material.
struct ShadedBody {
  std::unique_ptr<RayCaster> caster;
  std::vector<TriangleShading> triangles;
  SurfaceMaterial material;
};

std::vector<TriangleShading> ComputeShading(const Mesh& mesh, double crease_angle_deg) {
  const auto& vertices = mesh.vertices();
  const auto& tris = mesh.triangles();
  std::vector<Eigen::Vector3f> area_normals(tris.size());
  std::vector<std::vector<int>> incident(vertices.size());
  for (size_t t = 0; t < tris.size(); ++t) {
    const Eigen::Vector3f& a = vertices[tris[t][0]];
    area_normals[t] = (vertices[tris[t][1]] - a).cross(vertices[tris[t][2]] - a);
    for (int k = 0; k < 3; ++k) incident[tris[t][k]].push_back(static_cast<int>(t));
  }
  const float cos_crease = static_cast<float>(std::cos(crease_angle_deg * kDegToRad));
  std::vector<TriangleShading> shading(tris.size());
  for (size_t t = 0; t < tris.size(); ++t) {
    TriangleShading& s = shading[t];
    s.v0 = vertices[tris[t][0]];
    s.e1 = vertices[tris[t][1]] - s.v0;
    s.e2 = vertices[tris[t][2]] - s.v0;
    s.d00 = s.e1.dot(s.e1);
    s.d01 = s.e1.dot(s.e2);
    s.d11 = s.e2.dot(s.e2);
    const float denom = s.d00 * s.d11 - s.d01 * s.d01;
    s.inv_denom = denom > 0.0f ? 1.0f / denom : 0.0f;
    const float area = area_normals[t].norm();
    s.face = area > 0.0f ? Eigen::Vector3f(area_normals[t] / area) : Eigen::Vector3f::UnitZ();
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      for (int other : incident[tris[t][k]]) {
        const float other_area = area_normals[other].norm();
        if (other_area <= 0.0f) continue;
        if (crease_angle_deg > 0.0 && s.face.dot(area_normals[other] / other_area) >= cos_crease) {
          sum += area_normals[other];
        }
      }
      s.corner[k] = sum.norm() > 0.0f ? Eigen::Vector3f(sum.normalized()) : s.face;
    }
  }
  return shading;
}

// Smooth shading normal (object frame) at `point` on triangle `t`, oriented like `facing`.
Eigen::Vector3f ShadingNormal(const TriangleShading& s, const Eigen::Vector3f& point) {
  const Eigen::Vector3f d = point - s.v0;
  const float d20 = d.dot(s.e1), d21 = d.dot(s.e2);
  float b1 = (s.d11 * d20 - s.d01 * d21) * s.inv_denom;
  float b2 = (s.d00 * d21 - s.d01 * d20) * s.inv_denom;
  b1 = std::clamp(b1, 0.0f, 1.0f);
  b2 = std::clamp(b2, 0.0f, 1.0f - b1);
  const float b0 = 1.0f - b1 - b2;
  const Eigen::Vector3f n = b0 * s.corner[0] + b1 * s.corner[1] + b2 * s.corner[2];
  const float norm = n.norm();
  return norm > 0.0f ? Eigen::Vector3f(n / norm) : s.face;
}

ShadedBody MakeBody(const Mesh& mesh, double crease_angle_deg, const SurfaceMaterial& material) {
  ShadedBody body;
  body.caster = std::make_unique<RayCaster>(mesh);
  body.triangles = ComputeShading(mesh, crease_angle_deg);
  body.material = material;
  return body;
}

// Colour of a ray-cast sample of `body` (sample (row, col) of `view`), camera frame; the
// shading normal (camera frame) in `shading_normal` when not null.
Eigen::Vector3f ShadeSample(const ShadedBody& body, const RenderedView& view, int row, int col,
                            const Eigen::Matrix3f& cam_from_object_rotation,
                            const SceneLight& light_in_cam, const Eigen::Vector3f& point_in_cam,
                            Eigen::Vector3f* shading_normal = nullptr) {
  const int triangle = view.triangle_id(row, col);
  const cv::Vec3f& p = view.point_in_object(row, col);
  const cv::Vec3f& g = view.normal_in_cam(row, col);
  const Eigen::Vector3f geometric(g[0], g[1], g[2]);
  Eigen::Vector3f normal = geometric;
  if (triangle >= 0 && triangle < static_cast<int>(body.triangles.size())) {
    const TriangleShading& s = body.triangles[triangle];
    Eigen::Vector3f smooth =
        cam_from_object_rotation * ShadingNormal(s, Eigen::Vector3f(p[0], p[1], p[2]));
    if ((cam_from_object_rotation * s.face).dot(geometric) < 0.0f) smooth = -smooth;
    normal = smooth;
  }
  const Eigen::Vector3f to_viewer = -point_in_cam.normalized();
  if (shading_normal != nullptr) *shading_normal = normal;
  return Shade(body.material, light_in_cam, normal, to_viewer);
}

Eigen::Isometry3d Translation(const Eigen::Vector3d& t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = t;
  return pose;
}

Eigen::Vector3d RandomColor255(SynthRng* rng) {
  // Muted to saturated everyday colours.
  const double h = rng->Uniform(), s = rng->Uniform(0.1, 0.8), v = rng->Uniform(0.25, 0.9);
  const double h6 = 6.0 * h;
  const int sector = static_cast<int>(h6) % 6;
  const double f = h6 - std::floor(h6);
  const double p = v * (1 - s), q = v * (1 - s * f), u = v * (1 - s * (1 - f));
  const Eigen::Vector3d rgb[6] = {{v, u, p}, {q, v, p}, {p, v, u}, {p, q, v}, {u, p, v}, {v, p, q}};
  return 255.0 * rgb[sector];
}

// Per view-time geometry shared by all strips of one render.
struct ViewState {
  const Camera* camera = nullptr;
  Eigen::Isometry3d cam_from_world;
  Eigen::Isometry3d world_from_cam;
  Eigen::Isometry3d cam_from_object;
  cv::Rect object_roi;
  std::vector<Eigen::Isometry3d> cam_from_distractor;
  std::vector<cv::Rect> distractor_roi;
  SceneLight light_in_cam;
  SceneLight light_in_world;
};

}  // namespace

struct SynthWorld::Impl {
  SynthOptions options;
  std::vector<SynthCamera> cameras;
  Rig rig;
  std::optional<SynthMotion> motion;
  std::optional<Mesh> object_mesh;
  ShadedBody object;
  std::string object_name;
  double unit_to_mm = 1.0;
  std::string mesh_source;  // file copied into the sequence; empty = built-in
  std::string model_extension = ".obj";
  std::vector<ShadedBody> distractors;
  std::vector<Eigen::Isometry3d> world_from_distractor;
  std::vector<TexturedPlane> backdrops;  // one per view
  std::optional<TexturedPlane> ground;
  Eigen::Vector3f fallback = Eigen::Vector3f::Constant(0.15f);
  // Per view with distortion: (x, y) of the ray (x, y, 1) at every pixel centre, with a one
  // pixel border ((w+2)×(h+2), entry (r, c) is pixel (c−1, r−1)). PixelToRay is iterative
  // with distortion; the map is smooth, so bilinear interpolation is exact to ~1e-9.
  std::vector<cv::Mat2f> ray_maps;

  Eigen::Vector3d CameraRay(int view, double px, double py) const {
    const Camera& camera = cameras[view].camera;
    const cv::Mat2f& map = ray_maps[view];
    if (map.empty()) return {(px - camera.cx) / camera.fx, (py - camera.cy) / camera.fy, 1.0};
    const double gx = std::clamp(px + 1.0, 0.0, map.cols - 1.001);
    const double gy = std::clamp(py + 1.0, 0.0, map.rows - 1.001);
    const int x0 = static_cast<int>(gx), y0 = static_cast<int>(gy);
    const float wx = static_cast<float>(gx - x0), wy = static_cast<float>(gy - y0);
    const cv::Vec2f v = (1 - wy) * ((1 - wx) * map(y0, x0) + wx * map(y0, x0 + 1)) +
                        wy * ((1 - wx) * map(y0 + 1, x0) + wx * map(y0 + 1, x0 + 1));
    return {v[0], v[1], 1.0};
  }

  ViewState MakeViewState(int view, double t) const;
  void RenderRegion(const ViewState& state, int view, const cv::Rect& region, int n,
                    bool include_object, cv::Mat3f* radiance, cv::Mat1f* coverage) const;
};

namespace {

cv::Rect ClipToImage(const cv::Rect& rect, const Camera& camera) {
  return rect & cv::Rect(0, 0, camera.width, camera.height);
}

}  // namespace

ViewState SynthWorld::Impl::MakeViewState(int view, double t) const {
  ViewState s;
  s.camera = &cameras[view].camera;
  s.cam_from_world = motion->CamFromWorld(view, t);
  s.world_from_cam = s.cam_from_world.inverse();
  s.cam_from_object = s.cam_from_world * motion->WorldFromObject(t);
  s.object_roi =
      ClipToImage(object.caster->ProjectedBoundingBox(*s.camera, s.cam_from_object, 2), *s.camera);
  for (size_t i = 0; i < distractors.size(); ++i) {
    s.cam_from_distractor.push_back(s.cam_from_world * world_from_distractor[i]);
    s.distractor_roi.push_back(ClipToImage(
        distractors[i].caster->ProjectedBoundingBox(*s.camera, s.cam_from_distractor.back(), 2),
        *s.camera));
  }
  const SynthOptions::Light& l = options.light;
  const double azimuth = (l.azimuth_deg + (l.moves ? l.deg_per_frame * t : 0.0)) * kDegToRad;
  const double elevation = l.elevation_deg * kDegToRad;
  const Eigen::Vector3d to_light_world(std::cos(elevation) * std::cos(azimuth),
                                       std::cos(elevation) * std::sin(azimuth),
                                       std::sin(elevation));
  s.light_in_world.to_light = to_light_world.cast<float>();
  s.light_in_world.intensity = static_cast<float>(l.intensity);
  s.light_in_world.ambient = static_cast<float>(l.ambient);
  s.light_in_world.softness = static_cast<float>(std::sin(l.softness_deg * kDegToRad));
  s.light_in_cam = s.light_in_world;
  s.light_in_cam.to_light = (s.cam_from_world.linear() * to_light_world).cast<float>();
  return s;
}

void SynthWorld::Impl::RenderRegion(const ViewState& state, int view, const cv::Rect& region, int n,
                                    bool include_object, cv::Mat3f* radiance,
                                    cv::Mat1f* coverage) const {
  const Camera& camera = *state.camera;
  RenderOptions render_options;
  render_options.samples_per_axis = n;

  RenderedView object_view;
  cv::Rect object_rect;
  if (include_object) {
    object_rect = region & state.object_roi;
    if (!object_rect.empty()) {
      render_options.roi = object_rect;
      object_view = object.caster->Render(camera, state.cam_from_object, render_options);
    }
  }
  std::vector<RenderedView> distractor_views(distractors.size());
  std::vector<cv::Rect> distractor_rects(distractors.size());
  for (size_t i = 0; i < distractors.size(); ++i) {
    distractor_rects[i] = region & state.distractor_roi[i];
    if (distractor_rects[i].empty()) continue;
    render_options.roi = distractor_rects[i];
    distractor_views[i] =
        distractors[i].caster->Render(camera, state.cam_from_distractor[i], render_options);
  }

  const Eigen::Matrix3f object_rotation = state.cam_from_object.linear().cast<float>();
  std::vector<Eigen::Matrix3f> distractor_rotation;
  for (const auto& pose : state.cam_from_distractor) {
    distractor_rotation.push_back(pose.linear().cast<float>());
  }
  const Eigen::Matrix3d world_from_cam_rotation = state.world_from_cam.linear();
  const Eigen::Vector3d camera_centre = state.world_from_cam.translation();
  const TexturedPlane& backdrop = backdrops[view];
  const float inv_samples = 1.0f / static_cast<float>(n * n);
  // The nearest of the view's backdrop and the table along a world ray (null when neither).
  const auto nearest_plane = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& direction,
                                 double* depth) -> const TexturedPlane* {
    const TexturedPlane* plane = nullptr;
    *depth = backdrop.Intersect(from, direction);
    if (*depth > 0.0) plane = &backdrop;
    if (ground) {
      const double ground_depth = ground->Intersect(from, direction);
      if (ground_depth > 0.0 && (plane == nullptr || ground_depth < *depth)) {
        plane = &*ground;
        *depth = ground_depth;
      }
    }
    return plane;
  };
  const auto plane_radiance = [&](const TexturedPlane& plane, const Eigen::Vector3d& point) {
    const float lambert = SoftLambert(plane.normal.cast<float>().dot(state.light_in_world.to_light),
                                      state.light_in_world.softness);
    return Eigen::Vector3f(plane.Albedo(point) * (state.light_in_world.ambient +
                                                  state.light_in_world.intensity * lambert));
  };

  for (int y = region.y; y < region.y + region.height; ++y) {
    for (int x = region.x; x < region.x + region.width; ++x) {
      if (!include_object && state.object_roi.contains(cv::Point(x, y))) continue;
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      int object_hits = 0;
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          // Nearest surface along this sample's ray: object, distractors, planes.
          float best_depth = std::numeric_limits<float>::infinity();
          int best = -3;  // -3 none, -2 plane, -1 object, k distractor
          int sample_row = 0, sample_col = 0;
          if (!object_rect.empty() && object_rect.contains(cv::Point(x, y))) {
            const int r = (y - object_rect.y) * n + j, c = (x - object_rect.x) * n + i;
            if (object_view.mask(r, c) && object_view.depth(r, c) > 0.0f) {
              best_depth = object_view.depth(r, c);
              best = -1;
              sample_row = r;
              sample_col = c;
            }
          }
          for (size_t k = 0; k < distractors.size(); ++k) {
            const cv::Rect& rect = distractor_rects[k];
            if (rect.empty() || !rect.contains(cv::Point(x, y))) continue;
            const int r = (y - rect.y) * n + j, c = (x - rect.x) * n + i;
            const RenderedView& dv = distractor_views[k];
            if (dv.mask(r, c) && dv.depth(r, c) > 0.0f && dv.depth(r, c) < best_depth) {
              best_depth = dv.depth(r, c);
              best = static_cast<int>(k);
              sample_row = r;
              sample_col = c;
            }
          }
          // Ray (x, y, 1) in the camera frame: its parameter is the camera z-depth.
          const Eigen::Vector3d ray_in_cam =
              CameraRay(view, x - 0.5 + (i + 0.5) / n, y - 0.5 + (j + 0.5) / n);
          const Eigen::Vector3d ray_in_world = world_from_cam_rotation * ray_in_cam;
          // Meshes are always in front of the planes (the object's workspace and the
          // distractors lie between the cameras and their backdrops, above the table), so the
          // planes only matter for samples that miss every mesh.
          double plane_depth = -1.0;
          const TexturedPlane* plane =
              best == -3 ? nearest_plane(camera_centre, ray_in_world, &plane_depth) : nullptr;
          if (plane != nullptr && plane_depth < best_depth) {
            best = -2;
          }

          Eigen::Vector3f color;
          if (best == -1) {
            const Eigen::Vector3f point_in_cam = (ray_in_cam * best_depth).cast<float>();
            Eigen::Vector3f normal;
            color = ShadeSample(object, object_view, sample_row, sample_col, object_rotation,
                                state.light_in_cam, point_in_cam, &normal);
            const float f0 = object.material.reflectance;
            if (f0 > 0.0f) {
              // Clear coat: the mirror direction's backdrop or table, Fresnel-weighted (the
              // object's reflection of itself is left out).
              const Eigen::Vector3f to_viewer = -point_in_cam.normalized();
              const float cos_theta = normal.dot(to_viewer);
              const float fresnel = SchlickFresnel(f0, cos_theta);
              const Eigen::Vector3f mirror = 2.0f * cos_theta * normal - to_viewer;
              const Eigen::Vector3d mirror_in_world =
                  world_from_cam_rotation * mirror.cast<double>().normalized();
              const Eigen::Vector3d point_in_world = camera_centre + best_depth * ray_in_world;
              double depth = -1.0;
              const TexturedPlane* mirrored =
                  nearest_plane(point_in_world, mirror_in_world, &depth);
              const Eigen::Vector3f environment =
                  mirrored != nullptr
                      ? plane_radiance(*mirrored, point_in_world + depth * mirror_in_world)
                      : fallback;
              color = (1.0f - fresnel) * color + fresnel * environment;
            }
            ++object_hits;
          } else if (best >= 0) {
            const Eigen::Vector3f point_in_cam = (ray_in_cam * best_depth).cast<float>();
            color = ShadeSample(distractors[best], distractor_views[best], sample_row, sample_col,
                                distractor_rotation[best], state.light_in_cam, point_in_cam);
          } else if (best == -2) {
            color = plane_radiance(*plane, camera_centre + plane_depth * ray_in_world);
          } else {
            color = fallback;
          }
          sum += color;
        }
      }
      sum *= inv_samples;
      (*radiance)(y, x) = cv::Vec3f(sum.x(), sum.y(), sum.z());
      if (coverage != nullptr) (*coverage)(y, x) = object_hits * inv_samples;
    }
  }
}

SynthWorld::SynthWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SynthWorld::~SynthWorld() = default;

const SynthOptions& SynthWorld::options() const { return impl_->options; }
const Rig& SynthWorld::rig() const { return impl_->rig; }
const std::vector<SynthCamera>& SynthWorld::cameras() const { return impl_->cameras; }
const SynthMotion& SynthWorld::motion() const { return *impl_->motion; }
int SynthWorld::num_frames() const { return impl_->options.motion.num_frames; }
int SynthWorld::num_distractors() const { return static_cast<int>(impl_->distractors.size()); }
const Mesh& SynthWorld::object_mesh() const { return *impl_->object_mesh; }
const RayCaster& SynthWorld::object_caster() const { return *impl_->object.caster; }
const std::string& SynthWorld::object_name() const { return impl_->object_name; }
double SynthWorld::object_unit_to_mm() const { return impl_->unit_to_mm; }

Eigen::Isometry3d SynthWorld::RigFromObject(double t) const {
  return impl_->motion->RigFromObject(t);
}

Eigen::Isometry3d SynthWorld::CamFromObject(int view, double t) const {
  return impl_->rig[view].cam_from_rig * RigFromObject(t);
}

SynthViewRender SynthWorld::RenderView(int view, double t) const {
  const Impl& w = *impl_;
  const ViewState state = w.MakeViewState(view, t);
  const Camera& camera = *state.camera;
  SynthViewRender out;
  out.radiance = cv::Mat3f(camera.height, camera.width, cv::Vec3f(0, 0, 0));
  out.coverage = cv::Mat1f(camera.height, camera.width, 0.0f);
  // Pass 1: everything outside the object's box at the background sampling rate.
  const int n_bg = w.options.render.background_samples_per_axis;
  const int strips = (camera.height + kStripRows - 1) / kStripRows;
  tbb::parallel_for(0, strips, [&](int strip) {
    const int y0 = strip * kStripRows;
    const cv::Rect region(0, y0, camera.width, std::min(kStripRows, camera.height - y0));
    w.RenderRegion(state, view, region, n_bg, false, &out.radiance, &out.coverage);
  });
  // Pass 2: the object's box at the object sampling rate.
  const cv::Rect roi = state.object_roi;
  if (!roi.empty()) {
    const int n_obj = w.options.render.object_samples_per_axis;
    const int roi_strips = (roi.height + kStripRows - 1) / kStripRows;
    tbb::parallel_for(0, roi_strips, [&](int strip) {
      const int y0 = roi.y + strip * kStripRows;
      const cv::Rect region(roi.x, y0, roi.width, std::min(kStripRows, roi.y + roi.height - y0));
      w.RenderRegion(state, view, region, n_obj, true, &out.radiance, &out.coverage);
    });
  }
  return out;
}

cv::Mat3b SynthWorld::RenderFrame(int view, int frame, cv::Mat1f* coverage) const {
  const SynthOptions& o = impl_->options;
  const int k = o.sensor.motion_blur_subframes;
  cv::Mat3f radiance;
  cv::Mat1f cover;
  for (int j = 0; j < k; ++j) {
    const double t = k == 1 ? frame : frame + o.sensor.exposure_fraction * ((j + 0.5) / k - 0.5);
    SynthViewRender render = RenderView(view, t);
    if (j == 0) {
      radiance = render.radiance;
      cover = render.coverage;
    } else {
      radiance += render.radiance;
      cover += render.coverage;
    }
  }
  if (k > 1) {
    radiance *= 1.0 / k;
    cover *= 1.0 / k;
  }
  if (coverage != nullptr) *coverage = cover;
  const uint64_t noise_key =
      MixSeed(MixSeed(static_cast<uint64_t>(o.seed), 4000 + static_cast<uint64_t>(view)),
              static_cast<uint64_t>(frame));
  return ApplySensor(radiance, o.sensor, noise_key);
}

std::string SynthWorld::ModelRelativePath() const {
  return "model/" + impl_->object_name + impl_->model_extension;
}

Status SynthWorld::WriteModel(const std::string& path) const {
  if (impl_->mesh_source.empty())
    return WriteFileAtomic(path,
                           FormatObjMesh(*impl_->object_mesh, "bcot synth built-in mesh (mm)"));
  BCOT_ASSIGN_OR_RETURN(const std::string bytes, ReadTextFile(impl_->mesh_source));
  return WriteFileAtomic(path, bytes);
}

namespace {

// Places distractors on the table around the workspace (see DistractorsOptions), visible in
// at least one view, never intersecting the workspace or each other and, unless
// allow_occlusion, never between a camera and the workspace at any frame.
struct Placement {
  Mesh mesh;
  Eigen::Isometry3d world_from_object;
  double radius_mm;
};

std::vector<Placement> PlaceDistractors(const SynthOptions& options,
                                        const std::vector<Mesh>& sources,
                                        const std::vector<SynthCamera>& cameras,
                                        const SynthMotion& motion, double workspace_reach_mm,
                                        double ground_z_mm, SynthRng* rng) {
  const SynthOptions::Distractors& d = options.distractors;
  std::vector<Placement> placed;
  const int num_frames = options.motion.num_frames;
  const int frame_step = std::max(1, num_frames / 30);
  std::vector<std::vector<Eigen::Vector3d>> camera_centres(cameras.size());
  for (size_t c = 0; c < cameras.size(); ++c) {
    for (int f = 0; f < num_frames; f += frame_step) {
      camera_centres[c].push_back(
          motion.CamFromWorld(static_cast<int>(c), f).inverse().translation());
    }
  }
  const double distance = options.cameras.distance_mm;
  for (int index = 0; index < d.count; ++index) {
    // Shape: a file mesh (cycled) or a random built-in primitive.
    std::optional<Mesh> shape;
    if (!sources.empty()) {
      shape = sources[index % sources.size()];
    } else {
      const int kind = rng->UniformInt(0, 2);
      if (kind == 0) {
        shape =
            MakeBoxMesh({rng->Uniform(0.3, 1.0), rng->Uniform(0.3, 1.0), rng->Uniform(0.3, 1.0)});
      } else if (kind == 1) {
        shape = MakeCylinderMesh(rng->Uniform(0.15, 0.5), rng->Uniform(0.4, 1.0), 48);
      } else {
        shape = MakeEllipsoidMesh(
            {rng->Uniform(0.3, 0.5), rng->Uniform(0.3, 0.5), rng->Uniform(0.2, 0.5)}, 16, 32);
      }
    }
    const double size = rng->Uniform(d.size_min_mm, d.size_max_mm);
    Mesh scaled = shape->Transformed(shape->objcentre_from_template(), size / shape->diameter());
    const double yaw = rng->Uniform(0.0, 2.0 * kPi);
    Eigen::Isometry3d rotation = Eigen::Isometry3d::Identity();
    rotation.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    double min_z = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3f& v : scaled.vertices()) {
      min_z = std::min(min_z, (rotation.linear() * v.cast<double>()).z());
    }
    const double radius = BoundingRadiusMm(scaled);
    bool accepted = false;
    for (int attempt = 0; attempt < 3000 && !accepted; ++attempt) {
      const double rho = 1.3 * distance * std::sqrt(rng->Uniform());
      const double phi = rng->Uniform(0.0, 2.0 * kPi);
      const Eigen::Vector3d centre(rho * std::cos(phi), rho * std::sin(phi), ground_z_mm - min_z);
      if (centre.norm() < workspace_reach_mm + radius + 5.0) continue;
      bool ok = true;
      for (const Placement& other : placed) {
        if ((other.world_from_object.translation() - centre).norm() < other.radius_mm + radius) {
          ok = false;
          break;
        }
      }
      if (!ok) continue;
      // Visible (centre in the image, in front of the view's backdrop) in some view at frame 0.
      bool visible = false;
      for (size_t c = 0; c < cameras.size() && !visible; ++c) {
        const Eigen::Vector3d p = motion.CamFromWorld(static_cast<int>(c), 0) * centre;
        if (p.z() <= radius + 50.0) continue;
        if (p.z() + radius > distance + options.background.backdrop_distance_mm) continue;
        visible = cameras[c].camera.InImage(cameras[c].camera.Project(p), 20.0);
      }
      if (!visible) continue;
      for (size_t c = 0; c < cameras.size() && ok; ++c) {
        for (const Eigen::Vector3d& eye : camera_centres[c]) {
          const Eigen::Vector3d to_object = centre - eye;
          const double dist = to_object.norm();
          if (dist < radius + 50.0) {
            ok = false;
            break;
          }
          if (d.allow_occlusion) continue;
          // The look-at point of this camera is within 0.7 r of the origin in rig mode; use
          // the origin and the full reach as a conservative workspace ball.
          const Eigen::Vector3d to_target = -eye;
          const double target_dist = to_target.norm();
          if (dist - radius > target_dist + workspace_reach_mm) continue;  // behind it
          const double angle =
              std::acos(std::clamp(to_object.dot(to_target) / (dist * target_dist), -1.0, 1.0));
          const double clearance = std::asin(std::min(1.0, workspace_reach_mm / target_dist)) +
                                   std::asin(std::min(1.0, radius / dist));
          if (angle < clearance) {
            ok = false;
            break;
          }
        }
      }
      if (!ok) continue;
      Placement placement{std::move(scaled), Translation(centre) * rotation, radius};
      placed.push_back(std::move(placement));
      accepted = true;
    }
    if (!accepted) {
      std::fprintf(stderr, "bcot synth: warning: could not place distractor %d without conflicts\n",
                   index);
    }
  }
  return placed;
}

// A view's backdrop: perpendicular to its frame-0 optical axis, `backdrop_distance_mm` behind
// the target, texture upright in the image and spanning 1.5× the frame-0 field of view.
StatusOr<TexturedPlane> MakeBackdrop(const SynthOptions& options, int view,
                                     const SynthCamera& camera,
                                     const Eigen::Isometry3d& world_from_cam,
                                     int image_view_index) {
  const SynthOptions::Background& b = options.background;
  const std::string& kind = b.kinds[view % b.kinds.size()];
  const double along = options.cameras.distance_mm + b.backdrop_distance_mm;
  TexturedPlane plane;
  const Eigen::Vector3d forward = world_from_cam.linear().col(2);
  plane.origin = world_from_cam.translation() + along * forward;
  plane.u_axis = world_from_cam.linear().col(0);
  plane.v_axis = world_from_cam.linear().col(1);
  plane.normal = -forward;
  constexpr double kExtent = 1.5;
  constexpr int kMaxTexture = 4096;
  const double width = std::min<double>(kMaxTexture, kExtent * camera.camera.width);
  const cv::Size size(static_cast<int>(width),
                      static_cast<int>(width * camera.camera.height / camera.camera.width));
  plane.texel_mm = kExtent * camera.camera.width * along / camera.camera.fx / size.width;
  SynthRng rng(MixSeed(static_cast<uint64_t>(options.seed), 1000 + static_cast<uint64_t>(view)));
  cv::Mat3b texture;
  if (kind == "plain") {
    texture = MakePlainTexture(size, &rng);
  } else if (kind == "cluttered") {
    texture = MakeClutteredTexture(size, options.object.color_rgb, b.clutter_shapes,
                                   b.similar_color_fraction, &rng);
  } else {
    const std::string& path = b.images[image_view_index % b.images.size()];
    BCOT_ASSIGN_OR_RETURN(texture, LoadPhotoTexture(path, size));
  }
  TintTexture(options.object.color_rgb, b.object_tint, &texture);
  plane.texture = Texture(SrgbImageToLinear(texture));
  return plane;
}

}  // namespace

StatusOr<std::unique_ptr<SynthWorld>> SynthWorld::Create(const SynthOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  auto w = std::make_unique<Impl>();
  w->options = options;
  const SynthOptions::Object& o = options.object;

  // Object mesh in mm, exactly as the annotator will load it from the sequence.
  if (o.mesh.empty()) {
    const Mesh knot = MakeTrefoilKnotMesh(o.size_mm > 0.0 ? o.size_mm : 150.0 * o.unit_to_mm);
    // Round-trip through the OBJ text precision (9 significant digits read back exactly).
    std::vector<Eigen::Vector3f> vertices;
    for (const Eigen::Vector3f& v : knot.vertices()) {
      vertices.emplace_back(std::stof(fmt::format("{:.9g}", v.x())),
                            std::stof(fmt::format("{:.9g}", v.y())),
                            std::stof(fmt::format("{:.9g}", v.z())));
    }
    w->object_mesh = Mesh::FromArrays(std::move(vertices), knot.triangles());
    w->unit_to_mm = 1.0;
    w->object_name = o.name.empty() ? "knot" : o.name;
  } else {
    w->mesh_source = o.mesh;
    double unit_to_mm = o.unit_to_mm;
    if (o.size_mm > 0.0) {
      BCOT_ASSIGN_OR_RETURN(const Mesh raw, Mesh::Load(o.mesh, 1.0));
      unit_to_mm = o.size_mm / raw.diameter();
    }
    BCOT_ASSIGN_OR_RETURN(w->object_mesh, Mesh::Load(o.mesh, unit_to_mm));
    w->unit_to_mm = unit_to_mm;
    const std::filesystem::path path(o.mesh);
    w->object_name = o.name.empty() ? path.stem().string() : o.name;
    w->model_extension = path.extension().string();
  }
  SurfaceMaterial material;
  material.albedo = SrgbToLinear(o.color_rgb) * static_cast<float>(o.diffuse);
  material.specular = static_cast<float>(o.specular);
  material.shininess = static_cast<float>(o.shininess);
  material.reflectance = static_cast<float>(o.reflectance);
  w->object = MakeBody(*w->object_mesh, o.crease_angle_deg, material);

  // Cameras and motion.
  w->cameras = MakeSynthCameras(options.cameras);
  w->rig = MakeSynthRig(w->cameras);
  BCOT_ASSIGN_OR_RETURN(SynthMotion motion,
                        SynthMotion::Create(options, w->cameras, *w->object_mesh));
  w->motion = std::move(motion);
  BCOT_RETURN_IF_ERROR(CheckObjectInViews(*w->motion, w->cameras, *w->object_mesh,
                                          options.motion.num_frames,
                                          options.motion.frustum_margin_px));
  const double r = w->motion->workspace_radius_mm();
  const double object_radius = w->motion->object_radius_mm();
  const double centre_reach = options.motion.mode == "rotate" ? 0.0
                              : options.motion.mode == "rig"  ? 0.3 * r
                                                              : r;
  const double reach = centre_reach + object_radius;
  const double look_reach = (options.motion.mode == "rig" ? r : centre_reach) + object_radius;
  if (options.background.backdrop_distance_mm <= look_reach) {
    return Status::InvalidConfig(fmt::format(
        "background.backdrop_distance_mm = {} cuts through the object's workspace (reach {:.1f} "
        "mm from the target): increase it",
        options.background.backdrop_distance_mm, look_reach));
  }

  // Backgrounds.
  int image_views = 0;
  for (size_t view = 0; view < w->cameras.size(); ++view) {
    const Eigen::Isometry3d world_from_cam =
        w->motion->CamFromWorld(static_cast<int>(view), 0).inverse();
    BCOT_ASSIGN_OR_RETURN(TexturedPlane backdrop,
                          MakeBackdrop(options, static_cast<int>(view), w->cameras[view],
                                       world_from_cam, image_views));
    const std::string& kind = options.background.kinds[view % options.background.kinds.size()];
    if (kind == "image") ++image_views;
    w->backdrops.push_back(std::move(backdrop));
  }
  const double ground_z = -(reach + options.background.ground_clearance_mm);
  if (options.background.ground) {
    TexturedPlane ground;
    ground.origin = Eigen::Vector3d(0.0, 0.0, ground_z);
    ground.u_axis = Eigen::Vector3d::UnitX();
    ground.v_axis = Eigen::Vector3d::UnitY();
    ground.normal = Eigen::Vector3d::UnitZ();
    ground.texel_mm = std::max(0.25, options.cameras.distance_mm / w->cameras[0].camera.fx);
    SynthRng rng(MixSeed(static_cast<uint64_t>(options.seed), 999));
    cv::Mat3b table = MakeTableTexture(cv::Size(2048, 2048), &rng);
    TintTexture(options.object.color_rgb, options.background.object_tint, &table);
    ground.texture = Texture(SrgbImageToLinear(table));
    w->ground = std::move(ground);
  }

  // Distractors.
  std::vector<Mesh> sources;
  for (const std::string& path : options.distractors.meshes) {
    BCOT_ASSIGN_OR_RETURN(Mesh mesh, Mesh::Load(path, 1.0));
    sources.push_back(std::move(mesh));
  }
  SynthRng distractor_rng(MixSeed(static_cast<uint64_t>(options.seed), 2000));
  std::vector<Placement> placements =
      PlaceDistractors(options, sources, w->cameras, *w->motion, reach, ground_z, &distractor_rng);
  for (Placement& placement : placements) {
    SurfaceMaterial m;
    const Eigen::Vector3d rgb =
        distractor_rng.Uniform() < options.distractors.similar_color_fraction
            ? Eigen::Vector3d(o.color_rgb[0], o.color_rgb[1], o.color_rgb[2]) *
                  distractor_rng.Uniform(0.8, 1.1)
            : RandomColor255(&distractor_rng);
    m.albedo = SrgbToLinear({std::clamp(rgb[0], 0.0, 255.0), std::clamp(rgb[1], 0.0, 255.0),
                             std::clamp(rgb[2], 0.0, 255.0)}) *
               0.85f;
    m.specular = static_cast<float>(distractor_rng.Uniform(0.0, 0.3));
    m.shininess = static_cast<float>(distractor_rng.Uniform(10.0, 60.0));
    w->distractors.push_back(MakeBody(placement.mesh, 35.0, m));
    w->world_from_distractor.push_back(placement.world_from_object);
  }

  // Ray maps for distorted cameras.
  for (const SynthCamera& synth_camera : w->cameras) {
    const Camera& camera = synth_camera.camera;
    cv::Mat2f map;
    if (camera.HasDistortion()) {
      map.create(camera.height + 2, camera.width + 2);
      tbb::parallel_for(0, map.rows, [&](int row) {
        for (int col = 0; col < map.cols; ++col) {
          const Eigen::Vector3d ray = camera.PixelToRay(Eigen::Vector2d(col - 1.0, row - 1.0));
          map(row, col) = cv::Vec2f(static_cast<float>(ray.x()), static_cast<float>(ray.y()));
        }
      });
    }
    w->ray_maps.push_back(map);
  }
  return std::unique_ptr<SynthWorld>(new SynthWorld(std::move(w)));
}

// ---------------------------------------------------------------------------------------------

namespace {

// PNG, or JPEG with 4:2:0 chroma subsampling when jpeg_quality > 0 (the path's extension
// must match).
Status WriteImage(const std::string& path, const cv::Mat& image, int jpeg_quality = 0) {
  std::vector<uchar> bytes;
  if (jpeg_quality > 0) {
    // libjpeg's defaults (which OpenCV keeps) subsample both chroma channels 2×2 (4:2:0).
    const std::vector<int> params = {cv::IMWRITE_JPEG_QUALITY, jpeg_quality};
    if (!cv::imencode(".jpg", image, bytes, params)) {
      return Status::Internal(path + ": JPEG encoding failed");
    }
  } else if (!cv::imencode(".png", image, bytes)) {
    return Status::Internal(path + ": PNG encoding failed");
  }
  return WriteFileAtomic(path, std::string(bytes.begin(), bytes.end()));
}

std::string FrameName(int frame) { return fmt::format("{:06d}", frame); }

}  // namespace

Status Synthesize(const SynthOptions& options, const std::string& out_dir,
                  const SynthProgress& progress) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(out_dir, error) && !fs::is_empty(out_dir, error)) {
    return Status::InvalidConfig(
        fmt::format("{}: output directory exists and is not empty", out_dir));
  }
  const int threads =
      options.render.threads > 0 ? options.render.threads : tbb::task_arena::automatic;
  tbb::task_arena arena(threads);
  Status status;
  arena.execute([&] {
    StatusOr<std::unique_ptr<SynthWorld>> created = SynthWorld::Create(options);
    if (!created.ok()) {
      status = created.status();
      return;
    }
    const SynthWorld& world = **created;
    const Rig& rig = world.rig();
    const int num_frames = world.num_frames();
    const std::string root = out_dir + "/";

    // Frames: rendered in parallel, each written as soon as it is done.
    std::mutex mutex;
    Status frame_status;
    int done = 0;
    tbb::parallel_for(
        0, num_frames,
        [&](int frame) {
          {
            std::lock_guard<std::mutex> lock(mutex);
            if (!frame_status.ok()) return;
          }
          Status local;
          for (int view = 0; view < rig.size() && local.ok(); ++view) {
            const std::string& name = rig[view].camera.name;
            cv::Mat1f coverage;
            const cv::Mat3b image = world.RenderFrame(view, frame, &coverage);
            local = options.sensor.jpeg_quality > 0
                        ? WriteImage(root + name + "/" + FrameName(frame) + ".jpg", image,
                                     options.sensor.jpeg_quality)
                        : WriteImage(root + name + "/" + FrameName(frame) + ".png", image);
            if (local.ok() && options.output.write_coverage) {
              cv::Mat1b coverage8;
              coverage.convertTo(coverage8, CV_8U, 255.0);
              local = WriteImage(root + "gt/" + name + "/coverage_" + FrameName(frame) + ".png",
                                 coverage8);
            }
          }
          std::lock_guard<std::mutex> lock(mutex);
          if (!local.ok() && frame_status.ok()) frame_status = local;
          ++done;
          if (progress) progress(done, num_frames);
        },
        tbb::simple_partitioner());
    if (!frame_status.ok()) {
      status = frame_status;
      return;
    }

    // Ground truth and metadata.
    std::vector<Eigen::Isometry3d> rig_from_object, world_from_rig, world_from_object;
    for (int frame = 0; frame < num_frames; ++frame) {
      rig_from_object.push_back(world.RigFromObject(frame));
      world_from_rig.push_back(world.motion().WorldFromRig(frame));
      world_from_object.push_back(world.motion().WorldFromObject(frame));
    }
    auto run = [&](const Status& s) {
      if (status.ok() && !s.ok()) status = s;
    };
    run(WritePoseFile(root + "gt/rig_from_object.txt", rig_from_object));
    run(WritePoseFile(root + "gt/world_from_rig.txt", world_from_rig));
    run(WritePoseFile(root + "gt/world_from_object.txt", world_from_object));
    for (int view = 0; view < rig.size(); ++view) {
      std::vector<Eigen::Isometry3d> cam_from_object;
      for (const Eigen::Isometry3d& pose : rig_from_object) {
        cam_from_object.push_back(rig[view].cam_from_rig * pose);
      }
      run(WritePoseFile(root + "gt/" + rig[view].camera.name + "/pose.txt", cam_from_object));
    }

    // init_pose.txt: frame-0 GT perturbed by exactly the configured magnitudes, the rotation
    // about the object's bounding-box centre (not the mesh origin, which may lie far outside
    // the object and would turn a small rotation into a large displacement).
    SynthRng rng(MixSeed(static_cast<uint64_t>(options.seed), 3000));
    const Eigen::Vector3d axis = rng.UnitVector();
    const Eigen::Vector3d direction = rng.UnitVector();
    const Eigen::Isometry3d objcentre_from_template = world.object_mesh().objcentre_from_template();
    Eigen::Isometry3d rig_from_objcentre =
        rig_from_object.at(0) * objcentre_from_template.inverse();
    rig_from_objcentre.linear() = NearestRotation(
        ExpSO3(options.init.rotation_deg * kDegToRad * axis) * rig_from_objcentre.linear());
    rig_from_objcentre.translation() += options.init.translation_mm * direction;
    run(WritePoseFile(root + "init_pose.txt", {rig_from_objcentre * objcentre_from_template}));

    // timestamps.csv: synchronized cameras at the configured frame rate.
    std::string csv = "frame";
    for (int view = 0; view < rig.size(); ++view) csv += "," + rig[view].camera.name;
    csv += "\n";
    for (int frame = 0; frame < num_frames; ++frame) {
      const int64_t stamp = std::llround(frame * 1e9 / options.motion.fps);
      csv += std::to_string(frame);
      for (int view = 0; view < rig.size(); ++view) csv += "," + std::to_string(stamp);
      csv += "\n";
    }
    run(WriteFileAtomic(root + "timestamps.csv", csv));

    run(world.WriteModel(root + world.ModelRelativePath()));
    ObjectSpec object;
    object.name = world.object_name();
    object.mesh = world.ModelRelativePath();
    object.unit_to_mm = world.object_unit_to_mm();
    run(WriteObjectYaml(root + "object.yaml", object));
    run(WriteRigYaml(root + "rig.yaml", rig));
    run(WriteFileAtomic(root + "synth.resolved.yaml", FormatSynthOptions(options)));
  });
  return status;
}

}  // namespace bcot

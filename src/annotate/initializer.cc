#include "bcot/annotate/initializer.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bcot/annotate/pose_scorer.h"
#include "bcot/core/file_util.h"
#include "bcot/core/image_io.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/rotation_grid.h"
#include "bcot/core/se3.h"
#include "bcot/core/triangulation.h"
#include "bcot/optim/color_model.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/optim/region_cost.h"
#include "bcot/optim/region_template.h"
#include "bcot/optim/se3_manifold.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/contour_drawing.h"
#include "bcot/render/mesh.h"

namespace bcot {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

PoseScorerOptions ScorerOptions(const InitializerOptions& search, int width_px) {
  PoseScorerOptions options;
  options.width_px = width_px;
  options.band_px = search.band_px;
  options.bins_per_channel = search.bins_per_channel;
  options.background_band_px = search.background_band_px;
  return options;
}

struct ScoredPose {
  Eigen::Isometry3d rig_from_objcentre = Eigen::Isometry3d::Identity();
  double energy = std::numeric_limits<double>::infinity();
};

Eigen::Isometry3d PoseAt(const Eigen::Quaterniond& rotation, const Eigen::Vector3d& centre) {
  Eigen::Isometry3d rig_from_objcentre = Eigen::Isometry3d::Identity();
  rig_from_objcentre.linear() = rotation.toRotationMatrix();
  rig_from_objcentre.translation() = centre;
  return rig_from_objcentre;
}

// Every rotation at every centre, scored in parallel; sorted, best first.
std::vector<ScoredPose> ScoreGrid(const PoseScorer& scorer,
                                  const std::vector<Eigen::Quaterniond>& rotations,
                                  const std::vector<Eigen::Vector3d>& centres) {
  std::vector<ScoredPose> scored(rotations.size() * centres.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, scored.size(), 8),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t i = range.begin(); i != range.end(); ++i) {
                        scored[i].rig_from_objcentre =
                            PoseAt(rotations[i % rotations.size()], centres[i / rotations.size()]);
                        scored[i].energy = scorer.Score(scored[i].rig_from_objcentre);
                      }
                    });
  std::sort(scored.begin(), scored.end(),
            [](const ScoredPose& a, const ScoredPose& b) { return a.energy < b.energy; });
  return scored;
}

// The best `count` poses (sorted input) whose rotations are at least `min_deg` apart.
std::vector<ScoredPose> DistinctBest(const std::vector<ScoredPose>& sorted, int count,
                                     double min_deg) {
  std::vector<ScoredPose> chosen;
  for (const ScoredPose& pose : sorted) {
    if (static_cast<int>(chosen.size()) >= count || !std::isfinite(pose.energy)) break;
    const bool near = std::any_of(chosen.begin(), chosen.end(), [&](const ScoredPose& other) {
      return RotationDistanceDeg(pose.rig_from_objcentre.linear(),
                                 other.rig_from_objcentre.linear()) < min_deg;
    });
    if (!near) chosen.push_back(pose);
  }
  return chosen;
}

// Centres along the clicked ray at geometric steps of distance covering the projected sizes
// of InitializerOptions (min/max_extent_fraction).
std::vector<Eigen::Vector3d> DepthCentres(const RigRay& ray, const Camera& camera,
                                          double diameter_mm, const InitializerOptions& options) {
  const double focal = 0.5 * (camera.fx + camera.fy);
  const double side = std::min(camera.width, camera.height);
  const double near_mm = focal * diameter_mm / (options.max_extent_fraction * side);
  const double far_mm = focal * diameter_mm / (options.min_extent_fraction * side);
  std::vector<Eigen::Vector3d> centres;
  for (int i = 0; i < options.depth_steps; ++i) {
    const double distance =
        near_mm * std::pow(far_mm / near_mm, double(i) / (options.depth_steps - 1));
    centres.push_back(ray.origin_in_rig + distance * ray.direction_in_rig);
  }
  return centres;
}

// The rays of the clicks, in click order.
std::vector<RigRay> ClickRays(const Sequence& sequence, const InitRequest& request) {
  std::vector<RigRay> rays;
  for (const ImageClick& click : request.clicks) {
    rays.push_back(PixelRayInRig(sequence.rig[sequence.rig.Find(click.camera)], click.pixel));
  }
  return rays;
}

// The object centre the grid is searched at (result->centre_in_rig and centre_source): the
// clicks triangulated, the point at the given distance on one click's ray, or the best of a
// depth sweep along it.
Status LocateCentre(const Sequence& sequence, const PoseScorer& scorer, double diameter_mm,
                    const InitRequest& request, const InitializerOptions& options,
                    InitResult* result) {
  const std::vector<RigRay> rays = ClickRays(sequence, request);
  if (rays.size() >= 2) {
    BCOT_ASSIGN_OR_RETURN(result->centre_in_rig, TriangulateRays(rays));
    result->centre_source = fmt::format("{} clicks", rays.size());
    return Status::Ok();
  }
  if (request.distance_mm.has_value()) {
    result->centre_in_rig = rays[0].origin_in_rig + *request.distance_mm * rays[0].direction_in_rig;
    result->centre_source = fmt::format("1 click at {:g} mm", *request.distance_mm);
    return Status::Ok();
  }
  const Camera& camera = sequence.rig[sequence.rig.Find(request.clicks[0].camera)].camera;
  const std::vector<ScoredPose> depths =
      ScoreGrid(scorer, SuperFibonacciRotations(options.depth_grid_rotations),
                DepthCentres(rays[0], camera, diameter_mm, options));
  result->poses_scored += static_cast<int>(depths.size());
  if (!std::isfinite(depths.front().energy)) {
    return Status::InvalidInput("no depth along the clicked ray shows the object in any view");
  }
  result->centre_in_rig = depths.front().rig_from_objcentre.translation();
  result->centre_source = fmt::format("1 click, depth searched ({:.0f} mm)",
                                      (result->centre_in_rig - rays[0].origin_in_rig).norm());
  return Status::Ok();
}

// The grid search: the best distinct poses at the object centre.
StatusOr<std::vector<ScoredPose>> SearchGrid(const Sequence& sequence, const PoseScorer& scorer,
                                             double diameter_mm, const InitRequest& request,
                                             const InitializerOptions& options,
                                             InitResult* result) {
  BCOT_RETURN_IF_ERROR(LocateCentre(sequence, scorer, diameter_mm, request, options, result));
  const std::vector<ScoredPose> scored =
      ScoreGrid(scorer, SuperFibonacciRotations(options.grid_rotations), {result->centre_in_rig});
  result->poses_scored += static_cast<int>(scored.size());
  if (!std::isfinite(scored.front().energy)) {
    return Status::InvalidInput(fmt::format(
        "the object centre ({:.1f}, {:.1f}, {:.1f}) mm in the rig shows the object in no view",
        result->centre_in_rig.x(), result->centre_in_rig.y(), result->centre_in_rig.z()));
  }
  return DistinctBest(scored, options.refine_candidates, options.distinct_deg);
}

// Each grid pose refined by annotate's frame-0 bootstrap (in parallel, one tracker each).
StatusOr<std::vector<InitCandidate>> Refine(const Sequence& sequence, const RayCaster& caster,
                                            const std::vector<cv::Mat3b>& images,
                                            const std::vector<ScoredPose>& starts,
                                            const InitOptions& options) {
  std::vector<TrackedView> views;
  for (const RigCamera& camera : sequence.rig.cameras()) {
    views.push_back({camera.camera, camera.cam_from_rig, 1.0});
  }
  std::vector<std::unique_ptr<MultiViewTracker>> trackers;
  for (size_t i = 0; i < starts.size(); ++i) {
    BCOT_ASSIGN_OR_RETURN(std::unique_ptr<MultiViewTracker> tracker,
                          MultiViewTracker::Create(caster, views, options.annotate.tracker));
    trackers.push_back(std::move(tracker));
  }
  const Eigen::Isometry3d objcentre_from_template = caster.mesh().objcentre_from_template();
  std::vector<InitCandidate> candidates(starts.size());
  std::vector<Status> statuses(starts.size());
  tbb::parallel_for(size_t{0}, starts.size(), [&](size_t i) {
    Eigen::Isometry3d rig_from_objcentre = starts[i].rig_from_objcentre;
    StatusOr<FrameSummary> summary = trackers[i]->Initialize(images, &rig_from_objcentre);
    if (!summary.ok()) {
      statuses[i] = summary.status();
      return;
    }
    candidates[i].summary = *summary;
    candidates[i].grid_energy = starts[i].energy;
    candidates[i].rig_from_object = rig_from_objcentre * objcentre_from_template;
  });
  for (const Status& status : statuses) BCOT_RETURN_IF_ERROR(status);
  return candidates;
}

double IntersectionOverUnion(const cv::Mat1b& a, const cv::Mat1b& b) {
  const int both = cv::countNonZero(a & b);
  const int either = cv::countNonZero(a | b);
  return either == 0 ? 1.0 : double(both) / either;
}

// Ranks the refined candidates by their energy at the rank scale and keeps the best of each
// group of same-silhouette answers.
std::vector<InitCandidate> RankDistinct(std::vector<InitCandidate> candidates,
                                        const PoseScorer& scorer, const Mesh& mesh,
                                        double same_iou) {
  const Eigen::Isometry3d template_from_objcentre = mesh.objcentre_from_template().inverse();
  std::vector<std::vector<cv::Mat1b>> masks(candidates.size());
  tbb::parallel_for(size_t{0}, candidates.size(), [&](size_t i) {
    const Eigen::Isometry3d rig_from_objcentre =
        candidates[i].rig_from_object * template_from_objcentre;
    candidates[i].energy = candidates[i].summary.usable() ? scorer.Score(rig_from_objcentre)
                                                          : std::numeric_limits<double>::infinity();
    masks[i] = scorer.Masks(rig_from_objcentre);
  });
  std::vector<size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return candidates[a].energy < candidates[b].energy; });
  std::vector<size_t> kept;
  for (size_t i : order) {
    const auto same = std::find_if(kept.begin(), kept.end(), [&](size_t k) {
      for (size_t v = 0; v < masks[i].size(); ++v) {
        if (IntersectionOverUnion(masks[i][v], masks[k][v]) <= same_iou) return false;
      }
      return true;
    });
    if (same == kept.end()) {
      kept.push_back(i);
    } else {
      ++candidates[*same].merged;
    }
  }
  std::vector<InitCandidate> distinct;
  for (size_t i : kept) distinct.push_back(candidates[i]);
  return distinct;
}

std::string PathStem(const std::string& path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / p.stem()).string();
}

std::string PathExtension(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension.empty() ? ".txt" : extension;
}

// <stem>.cand<k> (k >= 1) or <stem> (k = 0).
std::string CandidateStem(const InitOutputs& outputs, int k) {
  return PathStem(outputs.pose_path) + (k == 0 ? "" : fmt::format(".cand{}", k));
}

// The image with the pose's contour drawn in every view's overlay file.
Status WriteOverlays(const std::string& stem, const Eigen::Isometry3d& rig_from_object,
                     const Sequence& sequence, const RayCaster& caster,
                     const std::vector<cv::Mat3b>& images) {
  for (int v = 0; v < sequence.rig.size(); ++v) {
    const RigCamera& camera = sequence.rig[v];
    const std::vector<ContourPoint> contour =
        caster.ExtractContour(camera.camera, camera.cam_from_rig * rig_from_object);
    cv::Mat overlay = images[v].clone();
    const int thickness = std::max(1, camera.camera.width / 640);
    DrawContour(contour, cv::Scalar(0, 255, 0), &overlay, Eigen::Vector2d::Zero(), 1.0, thickness);
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", overlay, png)) {
      return Status::Internal("cannot encode the overlay of " + camera.camera.name);
    }
    BCOT_RETURN_IF_ERROR(WriteFileAtomic(stem + "_" + camera.camera.name + ".png",
                                         std::string(png.begin(), png.end())));
  }
  return Status::Ok();
}

// The clicks of InitializeSequenceDir's motion search (see initializer.h).
StatusOr<std::vector<ImageClick>> ClicksOnMovingObject(const Sequence& sequence,
                                                       const std::vector<MovingObjectView>& views,
                                                       double mesh_diameter, int frame) {
  std::vector<ImageClick> clicks;
  std::vector<RigRay> rays;
  std::string changed;
  int largest = -1;
  for (int v = 0; v < static_cast<int>(views.size()); ++v) {
    changed += fmt::format("{}{} {:.2f} %", changed.empty() ? "" : ", ", views[v].camera,
                           100.0 * views[v].changed_fraction);
    if (!views[v].found) continue;
    clicks.push_back({views[v].camera, views[v].centroid_px});
    rays.push_back(PixelRayInRig(sequence.rig[v], views[v].centroid_px));
    if (largest < 0 || views[v].area_fraction > views[largest].area_fraction) {
      largest = static_cast<int>(clicks.size()) - 1;
    }
  }
  if (clicks.empty()) {
    return Status::InvalidInput(fmt::format(
        "no moving object found at frame {} (changed pixels: {}); give --click CAM:X,Y on the "
        "object's centre",
        frame, changed));
  }
  if (rays.size() >= 2) {
    const StatusOr<Eigen::Vector3d> centre = TriangulateRays(rays);
    double miss = std::numeric_limits<double>::infinity();
    if (centre.ok()) {
      miss = 0.0;
      for (const RigRay& ray : rays) miss = std::max(miss, DistanceToRay(ray, *centre));
    }
    if (miss > 0.5 * mesh_diameter) return std::vector<ImageClick>{clicks[largest]};
  }
  return clicks;
}

}  // namespace

StatusOr<InitResult> FindInitialPose(const Sequence& sequence, const RayCaster& caster,
                                     const std::vector<cv::Mat3b>& images,
                                     const InitRequest& request, const InitOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_RETURN_IF_ERROR(CheckInitRequest(sequence, request));
  BCOT_CHECK(static_cast<int>(images.size()) == sequence.rig.size());
  const InitializerOptions& search = options.search;
  InitResult result;
  const auto search_start = Clock::now();
  const PoseScorer coarse(caster, sequence.rig, images,
                          ScorerOptions(search, search.search_width_px));
  BCOT_ASSIGN_OR_RETURN(
      const std::vector<ScoredPose> starts,
      SearchGrid(sequence, coarse, caster.mesh().diameter(), request, search, &result));
  result.search_seconds = SecondsSince(search_start);

  const auto refine_start = Clock::now();
  BCOT_ASSIGN_OR_RETURN(std::vector<InitCandidate> refined,
                        Refine(sequence, caster, images, starts, options));
  const PoseScorer ranker(caster, sequence.rig, images,
                          ScorerOptions(search, search.rank_width_px));
  result.candidates = RankDistinct(std::move(refined), ranker, caster.mesh(), search.same_iou);
  result.refine_seconds = SecondsSince(refine_start);
  if (result.candidates.empty() || !std::isfinite(result.candidates.front().energy)) {
    return Status::InvalidInput("no refined candidate shows the object in any view");
  }
  return result;
}

std::vector<std::string> InitPosePaths(const InitOutputs& outputs) {
  std::vector<std::string> paths = {outputs.pose_path};
  for (int k = 1; k <= outputs.num_candidates; ++k) {
    paths.push_back(CandidateStem(outputs, k) + PathExtension(outputs.pose_path));
  }
  return paths;
}

Status CheckInitOutputs(const InitOutputs& outputs) {
  if (outputs.overwrite) return Status::Ok();
  for (const std::string& path : InitPosePaths(outputs)) {
    std::error_code error;
    if (std::filesystem::exists(path, error)) {
      return Status::InvalidConfig(
          fmt::format("{} exists; pass --overwrite to replace it (or --out FILE)", path));
    }
  }
  return Status::Ok();
}

Status WriteInitOutputs(const InitOutputs& outputs, const InitResult& result,
                        const Sequence& sequence, const RayCaster& caster,
                        const std::vector<cv::Mat3b>& images, std::vector<std::string>* written) {
  BCOT_CHECK(!result.candidates.empty());
  const std::vector<std::string> paths = InitPosePaths(outputs);
  for (int k = 0; k <= outputs.num_candidates; ++k) {
    // File 0 is the best answer, file k >= 1 the k-th best.
    const int index = std::max(0, k - 1);
    if (index >= static_cast<int>(result.candidates.size())) break;
    const Eigen::Isometry3d& rig_from_object = result.candidates[index].rig_from_object;
    BCOT_RETURN_IF_ERROR(WritePoseFile(paths[k], {rig_from_object}));
    BCOT_RETURN_IF_ERROR(
        WriteOverlays(CandidateStem(outputs, k), rig_from_object, sequence, caster, images));
    if (written != nullptr) written->push_back(paths[k]);
  }
  return Status::Ok();
}

StatusOr<InitResult> InitializeSequenceDir(const std::string& sequence_dir,
                                           const InitRequest& request, const InitOptions& options,
                                           const InitOutputs& outputs) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  BCOT_ASSIGN_OR_RETURN(const Sequence sequence,
                        LoadSequence(sequence_dir, /*require_init_pose=*/false));
  InitRequest resolved = request;
  std::vector<MovingObjectView> moving_object;
  if (request.clicks.empty() && !request.distance_mm.has_value() && request.frame >= 0 &&
      request.frame < sequence.num_frames) {
    BCOT_RETURN_IF_ERROR(CheckInitOutputs(outputs));  // before the search, not after it
    BCOT_ASSIGN_OR_RETURN(moving_object,
                          FindMovingObject(sequence, request.frame, options.search.motion));
  }
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  if (!moving_object.empty()) {
    BCOT_ASSIGN_OR_RETURN(resolved.clicks, ClicksOnMovingObject(sequence, moving_object,
                                                                mesh.diameter(), request.frame));
  }
  BCOT_RETURN_IF_ERROR(CheckInitRequest(sequence, resolved));
  BCOT_RETURN_IF_ERROR(CheckInitOutputs(outputs));
  std::vector<cv::Mat3b> images;
  for (int v = 0; v < sequence.rig.size(); ++v) {
    BCOT_ASSIGN_OR_RETURN(cv::Mat3b image, ReadCameraImage(sequence.image_paths[v][request.frame],
                                                           sequence.rig[v].camera));
    images.push_back(image);
  }
  const RayCaster caster(mesh);
  BCOT_ASSIGN_OR_RETURN(InitResult result,
                        FindInitialPose(sequence, caster, images, resolved, options));
  result.moving_object = moving_object;
  if (!moving_object.empty()) result.found_clicks = resolved.clicks;
  BCOT_RETURN_IF_ERROR(
      WriteInitOutputs(outputs, result, sequence, caster, images, &result.pose_files));
  return result;
}

std::string FormatInitSummary(const InitResult& result) {
  std::string text;
  if (!result.moving_object.empty()) {
    text += "moving object:";
    for (const MovingObjectView& view : result.moving_object) {
      text += view.found ? fmt::format(" {} region {:.2f} % of the image at ({:.1f}, {:.1f});",
                                       view.camera, 100.0 * view.area_fraction,
                                       view.centroid_px.x(), view.centroid_px.y())
                         : fmt::format(" {} none;", view.camera);
    }
    text += " clicks taken:";
    for (const ImageClick& click : result.found_clicks) {
      text +=
          fmt::format(" --click {}:{:.0f},{:.0f}", click.camera, click.pixel.x(), click.pixel.y());
    }
    text += "\n";
  }
  text += fmt::format(
      "centre ({:.1f}, {:.1f}, {:.1f}) mm in the rig from {}; {} poses scored in {:.1f} s, "
      "refined in {:.1f} s\n",
      result.centre_in_rig.x(), result.centre_in_rig.y(), result.centre_in_rig.z(),
      result.centre_source, result.poses_scored, result.search_seconds, result.refine_seconds);
  text +=
      "  rank  energy    grid_energy  refined_starts  rotation_to_best_deg  "
      "translation_to_best_mm\n";
  const InitCandidate& best = result.candidates.front();
  for (size_t i = 0; i < result.candidates.size(); ++i) {
    const InitCandidate& c = result.candidates[i];
    text += fmt::format(
        "  {:<4}  {:<8.5f}  {:<11.5f}  {:<14}  {:<20.1f}  {:.1f}\n", i + 1, c.energy, c.grid_energy,
        c.merged, RotationDistanceDeg(c.rig_from_object.linear(), best.rig_from_object.linear()),
        (c.rig_from_object.translation() - best.rig_from_object.translation()).norm());
  }
  if (result.candidates.size() < 2) {
    text += "  margin: no second distinct candidate\n";
  } else {
    const double margin = result.candidates[1].energy - best.energy;
    text +=
        fmt::format("  margin to the second distinct candidate: {:.5f} ({:.1f} % of the best)\n",
                    margin, 100.0 * margin / std::max(best.energy, 1e-12));
  }
  return text;
}

}  // namespace bcot

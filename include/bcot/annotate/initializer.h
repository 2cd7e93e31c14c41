// bcot init: the object's pose at one frame without a hand-written init_pose.txt (issue 15).
//
// Position. The object centre (O_o origin, the mesh's bounding-box centre) comes from clicks on
// it: with clicks in two or more views, the least-squares point of their rays
// (core/triangulation.h); with one click, the point on its ray at `distance_mm` when given, else
// the depth along the ray is searched together with the orientation (below).
//
// Orientation. Every rotation R of a super-Fibonacci grid over SO(3) (core/rotation_grid.h)
// gives a candidate rig_from_objcentre = (R, centre), scored by the joint region energy of all
// views at a coarse scale (cameras and images resized to about search_width_px wide) with
// colour models learned AT THE CANDIDATE: per view, render its silhouette, learn a global
// fg/bg colour model from it, build the region template (band around the contour) and
// evaluate RBOT's energy F (region_cost.h) there. A pose that puts the silhouette on the object
// separates the colours cleanly and gets a low energy; a wrong one mixes object and background
// on both sides. The score is the mean F per band pixel over all views (a sum would prefer
// poses with short contours). Candidates are scored in parallel (TBB).
// One click without a distance: first depths along the ray (geometric steps covering
// projected object sizes min_extent_fraction..max_extent_fraction of the image) times a coarse
// rotation grid, then the full grid at the best depth.
//
// Refinement. The best `refine_candidates` grid poses at least `distinct_deg` apart are each
// refined by the frame solver (MultiViewTracker::Initialize, the bootstrap of `bcot annotate`,
// with the annotate options), re-scored with the same energy at rank_width_px, and ranked.
// Refined poses whose silhouettes overlap with IoU > same_iou in every view are the same
// answer (near-symmetries of the mesh): only the best of them is kept.
//
// Frames: rig_from_objcentre internally, rig_from_object (O_t, the pose-file convention) in
// results; mm and px at capture resolution.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/annotate/moving_object_finder.h"
#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/optim/frame_problem.h"
#include "bcot/render/ray_caster.h"

namespace bcot {

struct InitializerOptions {
  // Rotations of the orientation grid; >= 100. 5,000: every rotation lies within ~9° of one.
  int grid_rotations = 5000;
  // Width (px) the views are resized to for the grid search (never enlarged); >= 16.
  // 160: 4× smaller than 640×512, 8× than 1280×1024.
  int search_width_px = 160;
  // Width (px) of the re-scoring of refined candidates; >= 16.
  int rank_width_px = 320;
  // Half-width (px, at the scoring scale) of the band the energy is summed over; > 0.
  double band_px = 5.0;
  // Histogram bins per colour channel of the per-candidate colour models; divides 256.
  int bins_per_channel = 16;
  // Background samples within this distance (px, at the scoring scale) of the silhouette; > 0.
  int background_band_px = 12;
  // Grid poses refined by the frame solver; >= 1.
  int refine_candidates = 8;
  // Refined grid poses are at least this far apart (deg); >= 0.
  double distinct_deg = 20.0;
  // Two refined poses are one answer when their silhouettes overlap with IoU above this in
  // every view; in (0, 1].
  double same_iou = 0.97;
  // One click without distance: depths searched along its ray, >= 2, with this many
  // rotations each, >= 1, over projected object sizes (longest bounding-box side over the
  // clicked image's shorter side) in [min_extent_fraction, max_extent_fraction] ⊂ (0, 2].
  int depth_steps = 48;
  int depth_grid_rotations = 300;
  double min_extent_fraction = 0.08;
  double max_extent_fraction = 0.9;
  // Without clicks: how the moving object is found (moving_object_finder.h).
  MovingObjectOptions motion;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// The options of `bcot init`: the annotate options (the refinement is annotate's frame-0
// bootstrap) and the search (YAML section `init:`).
struct InitOptions {
  AnnotateOptions annotate;
  InitializerOptions search;
  Status Validate() const;
};

const OptionSchema<InitOptions>& InitOptionSchema();
// Reads `path` (empty = defaults; an annotate config is a valid init config), then applies
// `--set` overrides.
StatusOr<InitOptions> ReadInitOptions(const std::string& path,
                                      const std::vector<std::string>& overrides);

// A click on the object's centre in one view (pixel coordinates of that camera's image).
struct ImageClick {
  std::string camera;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
};

// Parses `--click CAM:X,Y` ("cam0:312.5,240"); kInvalidConfig naming --click when malformed.
StatusOr<ImageClick> ParseImageClick(const std::string& text);

struct InitRequest {
  int frame = 0;
  std::vector<ImageClick> clicks;
  // One click only: the object centre's distance (mm) from that camera's centre along the ray.
  std::optional<double> distance_mm;
};

// kInvalidConfig naming --click / --frame / --distance-mm: an unknown camera (listing the
// rig's), a camera clicked twice, a click outside its image, a frame outside the sequence,
// no click, a distance that is not > 0 or given with more than one click.
Status CheckInitRequest(const Sequence& sequence, const InitRequest& request);

struct InitCandidate {
  Eigen::Isometry3d rig_from_object = Eigen::Isometry3d::Identity();  // O_t, refined
  double grid_energy = 0.0;  // score of the grid pose it was refined from (search scale)
  double energy = 0.0;       // score after refinement (rank scale); lower is better
  FrameSummary summary;      // the refinement's last solve
  int merged = 1;            // refined grid poses that ended at this answer (IoU > same_iou)
};

struct InitResult {
  // Distinct answers (see the header comment), best (lowest energy) first; never empty.
  std::vector<InitCandidate> candidates;
  Eigen::Vector3d centre_in_rig = Eigen::Vector3d::Zero();  // the searched centre (mm)
  std::string centre_source;  // "2 clicks", "1 click at 600 mm", "1 click, depth searched"
  int poses_scored = 0;       // grid (and depth) poses scored
  double search_seconds = 0.0;
  double refine_seconds = 0.0;
  std::vector<std::string> pose_files;  // written by InitializeSequenceDir, pose_path first
  // InitializeSequenceDir without clicks: the views where the moving object was looked for
  // (moving_object_finder.h), and the clicks taken from them.
  std::vector<MovingObjectView> moving_object;
  std::vector<ImageClick> found_clicks;
};

// The search and refinement on the frame's images (rig order, capture size). The request must
// pass CheckInitRequest (CHECKed in part).
StatusOr<InitResult> FindInitialPose(const Sequence& sequence, const RayCaster& caster,
                                     const std::vector<cv::Mat3b>& images,
                                     const InitRequest& request, const InitOptions& options);

// Where `bcot init` writes: `pose_path` (default <seq>/init_pose.txt), its overlays
// <stem>_<camera>.png, and for k = 1..num_candidates <stem>.cand<k>.txt with overlays
// <stem>.cand<k>_<camera>.png (<stem> = pose_path without its extension).
struct InitOutputs {
  std::string pose_path;
  int num_candidates = 0;
  bool overwrite = false;
};

// The pose files InitOutputs names (the main one first).
std::vector<std::string> InitPosePaths(const InitOutputs& outputs);
// kInvalidConfig naming the file and --overwrite when a pose file exists and !overwrite.
Status CheckInitOutputs(const InitOutputs& outputs);
// Writes the files (atomically). The best candidate goes to pose_path; candidate k to its
// cand file when k <= candidates found (a cand file beyond them is neither written nor
// removed). `written` (may be null) receives the pose files written, pose_path first.
Status WriteInitOutputs(const InitOutputs& outputs, const InitResult& result,
                        const Sequence& sequence, const RayCaster& caster,
                        const std::vector<cv::Mat3b>& images,
                        std::vector<std::string>* written = nullptr);

// The whole command: load the sequence and its frame, check the request and the outputs
// before any work, search, write (result.pose_files). Every camera of the rig is used (the
// annotate options' views.* are not). Without clicks (and without a distance) the object is
// found by its motion (FindMovingObject): a click at the moving region's centroid in every
// view where one is found; when the rays of two or more such clicks pass farther than half the
// mesh's diameter from their triangulated point, only the view with the largest region is
// kept (its depth then searched). kInvalidInput when no view shows a moving region.
StatusOr<InitResult> InitializeSequenceDir(const std::string& sequence_dir,
                                           const InitRequest& request, const InitOptions& options,
                                           const InitOutputs& outputs);

// A few lines for stderr: the centre, the timing, the candidates with their energies and the
// margin of the best over the second distinct one.
std::string FormatInitSummary(const InitResult& result);

}  // namespace bcot

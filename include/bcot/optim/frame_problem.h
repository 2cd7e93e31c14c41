// One frame, all views: the joint region energy of DESIGN.md "Joint energy" (paper eq. 7–8,
// S.20–22) minimised by Ceres over ONE parameter block rig_from_objcentre (Se3Manifold, the
// object-centred update of eq. 4), coarse to fine and then in rounds (DESIGN.md "Rounds";
// supplement §C.1: annotation 5 rounds × 7 iterations; configs/annotate.yaml runs 2 before
// the edge stage, which places the contour):
//
//   for level l = levels−1 .. 1, then `rounds` times at level 0:
//     every view: ray-cast the silhouette at the current pose (Embree), build its
//                 RegionTemplate (band, posteriors) and add its RegionCostFunction (dense),
//                 and/or build its CorrespondenceLines and add its
//                 CorrespondenceLineCostFunction (sparse), as options.energy says
//     Ceres: `iterations` Levenberg-Marquardt iterations on Σ_views w_v · Σ_x F(x)
//     (level 0) stop early when the round moved the pose less than the round tolerances
//
// Pyramid. Level l samples the energy at scale 2^l: pixels every stride_px·2^l, band
// band_px·2^l, Heaviside slope heaviside_slope / 2^l, all in full-resolution coordinates.
// This is the coarse-to-fine schedule of RBOT's image pyramid in the quantities that matter
// (capture range grows with the band, pixel count falls by 2^l, the energy is smoother) but
// keeps the colour posteriors at capture resolution: the image is never resampled, so the
// colour model learned at full resolution applies at every level unchanged. The coarse levels
// only bring the pose into the band of level 0: a smoother energy has a slightly different
// minimum (measured 0.2° on a bunny at level 2), so they run once, before the rounds, never
// between them.
// Coarse check. Their smoother, wider energy can also be decided by what surrounds the object
// rather than by its contour: around a 60–80 px object a band of 48 px is mostly background,
// and on a Cycles scene of such an object, with a same-coloured one beside it, the coarse
// minimum lay 15–22° away on most frames, from where the rounds did not always return
// (docs/notes/issue12_coarse_levels.md). So when coarse levels ran, the first round also
// linearises the views at the pose the solve started from and compares the level-0 energy per
// residual term (the band's pixel count changes with the pose) there and at the coarse
// result; the rounds start from the lower of the two (FrameSummary::coarse_rejected when that
// is the start). One more level-0 linearisation per view and frame, saved when the coarse
// levels moved no corner of the mesh's bounding box by coarse_check_min_shift_px in any view:
// the level-0 rounds, whose band is several times wider, start from either pose alike.
//
// Sparse viewpoint model. With options.lines_from_viewpoint_model (energy sparse only) the
// region rounds do not ray-cast: each view's lines lie along the points of the model's nearest
// viewpoint (SparseViewpointModel, each viewpoint built once), projected at the current pose.
// The edge stage still renders the exact silhouette (docs/sparse_viewpoint_model.md).
//
// Monocular tracking is the same code with one view. Failure is data: the Summary says what
// happened; the pose is only written when the solve produced a finite energy.
//
// Thread safety: Solve is const; one FrameProblem may serve several threads as long as each
// passes its own views and pose. Within a solve the views are linearised (and their edge lines
// measured) concurrently on the calling TBB arena; their terms enter the problem in view order,
// so the result does not depend on the number of threads.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bcot/core/camera.h"
#include "bcot/core/chroma_restoration.h"
#include "bcot/core/chroma_sampling.h"
#include "bcot/core/rotational_symmetry.h"
#include "bcot/core/status.h"
#include "bcot/optim/color_model.h"
#include "bcot/optim/correspondence_lines.h"
#include "bcot/optim/edge_lines.h"
#include "bcot/optim/pose_gaussian_cost.h"
#include "bcot/optim/region_cost.h"
#include "bcot/optim/region_template.h"
#include "bcot/render/ray_caster.h"
#include "bcot/render/sparse_viewpoint_model.h"

namespace bcot {

// Which region energy a frame problem minimises (DESIGN.md "Region energy" and "Sparse
// variant"): the dense band energy of eq. 6, the correspondence-line energy, or their sum.
enum class RegionEnergy { kDense, kSparse, kCombined };

const char* RegionEnergyName(RegionEnergy energy);

// The robust loss ρ of the edge residuals. The measurement errors of edge lines are not
// symmetric: lines whose rim carries no step at the geometric edge (grazing reflections and
// highlights matching the background, docs/notes/issue12_rim_profiles.md) are found up to 2 px
// inside it, while the well-measured lines form a core centred on it. A redescending loss
// gives such lines little influence (Cauchy: weight 1/(1 + (r/s)²)); Huber only bounds it.
enum class EdgeRobustLoss { kHuber, kCauchy, kTukey };

// The final edge-alignment stage (edge_lines.h): after the region rounds, `rounds` times
// { ray-cast the silhouette at the current pose, measure every view's edge lines (the centre of
// the image's blurred step along each contour normal), `iterations` Levenberg-Marquardt
// iterations on ½Σ ρ(r²) of their residuals (CorrespondenceLineCostFunction, one residual
// block per line so that ρ acts on each line; threshold robust_scale in σ units) }, stopping
// early like the region rounds. The region energy is not part of it: its minimum is biased
// where a shaded rim moves the colour posteriors' crossing inward, the edge's is not. Skipped
// (the region result kept) when all views together have fewer than min_lines lines.
struct EdgeRefineOptions {
  // On by default (annotation); the temporal window takes each frame's edge pose posterior as
  // its data term (window_problem.h). configs/track.yaml switches it off for speed.
  bool enabled = true;
  // Re-rendered edge solves with robust_loss; >= 1.
  int rounds = 1;
  // Ceres iterations per edge solve; >= 1.
  int iterations = 5;
  // Loss of each line's residual and its threshold (units of the line's σ); scale > 0.
  // Cauchy: docs/notes/issue12_robust_edges.md (Huber and Tukey measured beside it).
  EdgeRobustLoss robust_loss = EdgeRobustLoss::kCauchy;
  double robust_scale = 3.0;
  // Re-rendered solves after those `rounds`, each line with Tukey's biweight loss at
  // redescending_scale (σ units): a line farther than that from the contour then pulls not at
  // all, where Cauchy's tail still pulls with weight ~(s/r)². Shaded, glossy and same-coloured
  // rims put a one-sided group of lines inside the edge; that pull is what biases the pose
  // towards them. A redescending loss lets the solve's start decide which lines it keeps, so it
  // comes once the rounds above have brought the contour close (from the region result, often
  // 0.5 px off, it drops good lines). docs/notes/issue12_redescending_round.md; >= 0, 0 = none.
  // The scale (> 0): about twice the lines' actual spread, which is 2-4 times their σ from the
  // profile fit (6, 7, 8 and 10 measured alike; 4.5 drops good lines).
  int redescending_rounds = 1;
  double redescending_scale = 7.0;
  // Fewest lines over all views for the stage to run; >= 6 (six pose parameters).
  int min_lines = 20;
  // Measurement along each line.
  EdgeLineOptions lines;
  // Off (default): a view whose chroma was subsampled has its last round's lines corrected for
  // the codec's chroma blur, line by line (edge_lines.h). On: the last round measures them on the
  // view's image with its chroma restored from the luma around the object (EdgeImageOf,
  // core/chroma_restoration.h) as 4:4:4. The region stage and the earlier rounds read the decoded
  // image either way (docs/notes/issue12_jpeg_chroma.md).
  ChromaRestorationOptions chroma_restoration;
  Status Validate() const;
};

struct FrameProblemOptions {
  // Rounds at full resolution (each re-renders the templates at the current pose); >= 1.
  // Annotation: 2 (then the edge stage; the paper ran 5, docs/notes/issue19_speed.md).
  int rounds = 5;
  // Ceres iterations per coarse level and per round; >= 1. Annotation: 7.
  int iterations = 7;
  // Pyramid levels (see the header comment); in [1, 6]. 1 = full resolution only; L runs
  // levels L−1..1 once before the rounds.
  int pyramid_levels = 3;
  // Rounds (each re-renders the templates) on every coarse level; >= 1. The linearised
  // template is only valid within about a band of the pose it was rendered at, so a large
  // inter-frame motion needs several re-linearisations before level 0.
  int coarse_rounds = 1;
  // Keep the coarse levels' pose only when the level-0 energy per term there is not above the
  // start's (see "Coarse check" above); false = always keep it.
  bool coarse_check = true;
  // The check runs only when the coarse levels moved a corner of the mesh's bounding box by at
  // least this much (px) in some view; >= 0, 0 = always. 3: within a quarter of annotation's
  // level-0 band; the Cycles scenes the check was made for moved 15–22° (tens of px) when it
  // mattered (docs/notes/issue19_speed.md, "Skipping the coarse check").
  double coarse_check_min_shift_px = 3.0;
  // Stop after a round that moved the pose by less than both tolerances (rotation in degrees,
  // translation in mm); >= 0, 0 = always run every round.
  double round_tolerance_deg = 1e-4;
  double round_tolerance_mm = 1e-3;
  // Damping of every solve towards the pose its templates were rendered at (pose_damping_cost.h):
  // σ_t (mm) and σ_r (deg) of ½N(|Δt|²/σ_t² + |Δφ|²/σ_r²), N the level's residual count;
  // >= 0, 0 switches the term off. Large values damp little.
  double damping_translation_mm = 0.0;
  double damping_rotation_deg = 0.0;
  // Band, stride and contour sampling of the templates at level 0.
  RegionTemplateOptions region;
  // Residual form, Heaviside slope (at level 0) and probability floor. Its view_weight is
  // ignored: each FrameView carries its own weight.
  RegionCostOptions cost;
  // The energy: dense (eq. 6 over the band), sparse (correspondence lines) or combined (the
  // sum; lines.weight scales the sparse part). YAML: cost.energy. Combined by default: on the
  // 90° binocular synthetic protocol and the real BCOT Cat frames it was never the worst of
  // the three and lost the fewest synthetic frames (see scripts/bench_precision.sh).
  RegionEnergy energy = RegionEnergy::kCombined;
  // Correspondence lines of the sparse energy at level 0; coarse levels multiply its lengths
  // by 2^l like the dense band.
  CorrespondenceLineOptions lines;
  // The lines of the region rounds along a sparse viewpoint model's points instead of a
  // silhouette rendered at each linearisation (see "Sparse viewpoint model" above); needs
  // energy = sparse (the dense template renders the silhouette anyway). YAML:
  // lines.viewpoint_model.
  bool lines_from_viewpoint_model = false;
  // The final edge-alignment stage (after the rounds at level 0).
  EdgeRefineOptions edge;
  // Threads Ceres may use to evaluate residuals; >= 1.
  int num_threads = 1;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// One view of a frame. Non-owning: everything must outlive the Solve call.
struct FrameView {
  const Camera* camera = nullptr;
  Eigen::Isometry3d cam_from_rig = Eigen::Isometry3d::Identity();
  const cv::Mat3b* image = nullptr;  // camera->width × camera->height
  const ColorModel* color_model = nullptr;
  double weight = 1.0;  // w_v >= 0 of eq. 8
  // Posteriors of the full-resolution (level 0) rounds; null = color_model.
  const ColorModel* refine_color_model = nullptr;
  // How `image`'s chroma was stored (a subsampled JPEG's is corrected for by the edge stage).
  ChromaSampling chroma = ChromaSampling::Full();
};

enum class FrameTermination {
  kConverged,      // a round moved the pose by less than the round tolerances
  kMaxRounds,      // every round ran
  kNotVisible,     // no view had a single band pixel at some level: pose left as it was
  kSolverFailure,  // Ceres reported failure or the energy was not finite: pose left as it was
};

const char* FrameTerminationName(FrameTermination termination);

struct FrameViewSummary {
  int pixels = 0;       // band pixels of the view at level 0 in the last round
  int lines = 0;        // correspondence lines of the view at level 0 in the last round
  int edge_lines = 0;   // edge lines of the view in the last edge round (0 without it)
  double energy = 0.0;  // w·Σ F of the view at the final pose (level 0 template of the last round)
};

struct FrameSummary {
  FrameTermination termination = FrameTermination::kMaxRounds;
  int rounds = 0;               // full-resolution rounds run
  int iterations = 0;           // Ceres iterations over all levels and rounds
  double initial_energy = 0.0;  // Σ views, level 0 template of round 1 at its start pose
  double final_energy = 0.0;    // Σ views at the final pose, level 0 template of the last round
  double last_round_rotation_deg = 0.0;  // pose change made by the last round
  double last_round_translation_mm = 0.0;
  // The coarse check found the coarse levels' pose worse than the start: the rounds started
  // from the start pose.
  bool coarse_rejected = false;
  // The coarse check ran (coarse levels ran, coarse_check on, they moved the object by at least
  // coarse_check_min_shift_px).
  bool coarse_checked = false;
  std::vector<FrameViewSummary> views;  // in the order of the FrameView list
  std::string message;                  // why, when not kConverged / kMaxRounds

  // The pose is a solve result (not left unchanged by a failure).
  bool usable() const {
    return termination == FrameTermination::kConverged ||
           termination == FrameTermination::kMaxRounds;
  }
};

// The level-0 template of one view in the last round of a solve, with everything a
// RegionCostFunction needs to evaluate that view's region energy at another pose (the
// temporal window re-uses it, see window_problem.h). The template is shared and immutable.
struct ViewLinearisation {
  Camera camera;
  Eigen::Isometry3d cam_from_rig = Eigen::Isometry3d::Identity();
  // The dense term (null when the energy is sparse) and its level-0 options, view_weight = w_v.
  std::shared_ptr<const RegionTemplate> region_template;
  RegionCostOptions cost;
  // The sparse term (null when the energy is dense) and its weight w_v · lines.weight.
  std::shared_ptr<const CorrespondenceLines> lines;
  double line_weight = 0.0;
  // Set when the frame ended with the edge stage, the same on every view of the frame: the
  // frame's pose posterior from its edge lines (mean = the frame's final pose, information =
  // JᵀJ of the whitened edge residuals of all views at that pose; pose_gaussian_cost.h). The
  // window uses it in place of the frame's region terms (window_problem.h).
  std::shared_ptr<const PoseGaussian> edge_posterior;
};

class FrameProblem {
 public:
  // `caster` (the object's mesh) must outlive the problem; `options` must be valid (CHECKed:
  // validate user input with FrameProblemOptions::Validate first) with a resolved edge
  // response (CHECKed: MultiViewTracker resolves ImageResponse::Kind::kAuto).
  // `symmetry`: the mesh's rotational symmetry in O_t (render/symmetry_detection.h), if any;
  // every solve then keeps the angle about its axis where it started (AxisLockedSe3Manifold).
  // `viewpoint_model`: the sparse viewpoint model of the caster's mesh, required (CHECKed) with
  // options.lines_from_viewpoint_model, unused otherwise; must outlive the problem.
  FrameProblem(const RayCaster& caster, const FrameProblemOptions& options,
               const std::optional<RotationalSymmetry>& symmetry = std::nullopt,
               const SparseViewpointModel* viewpoint_model = nullptr);

  // Minimises the joint energy starting from *rig_from_objcentre and writes the result there
  // (unless !summary.usable()). Views with weight 0 or the object out of view contribute no
  // residuals. CHECKs that views are complete and images match their cameras.
  // When `linearisations` is not null it receives the level-0 templates of the last round
  // (views without band pixels left out); it is cleared when !summary.usable(). These are the
  // region rounds' templates also after an edge stage, which adds its pose posterior to every
  // entry (ViewLinearisation::edge_posterior). Energies in the summary are those of the region
  // rounds.
  FrameSummary Solve(const std::vector<FrameView>& views, Eigen::Isometry3d* rig_from_objcentre,
                     std::vector<ViewLinearisation>* linearisations = nullptr) const;

  // The edge stage alone (options().edge, run also when edge.enabled is false) from
  // *rig_from_objcentre, which receives the result; false (pose unchanged) when all views
  // together have fewer than edge.min_lines lines or Ceres failed. Same view requirements as
  // Solve (colour models are not used).
  bool SolveEdges(const std::vector<FrameView>& views, Eigen::Isometry3d* rig_from_objcentre) const;

  const RayCaster& caster() const { return caster_; }
  const FrameProblemOptions& options() const { return options_; }
  // The model given to the constructor (null when none was given).
  const SparseViewpointModel* viewpoint_model() const { return viewpoint_model_; }
  // The symmetry given to the constructor, in O_o.
  const std::optional<RotationalSymmetry>& symmetry_in_objcentre() const {
    return symmetry_in_objcentre_;
  }

 private:
  // The edge stage (EdgeRefineOptions) from and into `parameters` (7 ambient); false (the
  // caller restores the region result) when too few lines or Ceres failed. `posterior` (may
  // be null) receives the pose posterior of the last edge solve, or null when its normal
  // matrix is singular.
  bool RefineEdges(const std::vector<FrameView>& views, double* parameters, FrameSummary* summary,
                   std::shared_ptr<const PoseGaussian>* posterior) const;

  const RayCaster& caster_;
  const SparseViewpointModel* viewpoint_model_;  // with options_.lines_from_viewpoint_model
  // The mesh's creases, found once when the edge stage measures them (edge.lines.crease_contours).
  std::vector<Crease> creases_;
  FrameProblemOptions options_;
  std::optional<RotationalSymmetry> symmetry_in_objcentre_;  // O_o
};

}  // namespace bcot

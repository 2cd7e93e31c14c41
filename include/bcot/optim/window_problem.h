// The temporal smoothing window (DESIGN.md "Temporal smoothing window"): after the per-frame
// joint solves, windows of W consecutive frames are refined jointly. One ceres::Problem per
// window holds, for every frame t of the window, the region residuals of all its views — the
// level-0 templates its own per-frame solve ended with (ViewLinearisation, frame_problem.h) —
// and motion priors (motion_prior_cost.h) on every span of consecutive frames touching the
// window, separately for the translation and the rotation part. Parameter blocks are
// rig_from_objcentre (Se3Manifold), solved with SPARSE_NORMAL_CHOLESKY (SuiteSparse): the
// normal equations are block-banded (7×7 blocks, bandwidth 3 with an acceleration model).
//
// Energy of a window [s, e):
//   Σ_t D_t(T_t)  +  Σ_spans [ ½ρ_ρ(‖W_ρ·Δ_ρ‖²) + ½ρ_φ(‖W_φ·Δ_φ‖²) ]
// D_t, the data term of frame t: Σ_views w_v·Σ_x F_t,x(T_t) (its region templates), or, when
// frame t's solve ended with the edge stage (FrameProblemOptions::edge) and edge_posterior is
// on, ½ eᵀH_t e, the Gaussian pose posterior of its edge solve (pose_gaussian_cost.h: mean the
// per-frame pose, H_t = Σ ρ'·JᵀJ of its whitened, robustly weighted edge residuals, each view
// discounted as a whole for the error its lines share, divided by their a posteriori variance
// factor when that exceeds 1: frame_problem.cc EdgePosterior). Why the posterior and not the region
// terms: the region minimum is biased under shaded rims (edge_lines.h) and the window, refining on
// it, pulled the poses back towards that bias (window_problem_test: mean error 0.035 → 0.059 mm
// with the edge stage on); and not the edge lines themselves: re-measuring them is not possible
// without the images, and the lines at the final pose hold the same information to second
// order as H_t does, at 6 residuals per frame instead of hundreds. Both H_t and the prior are
// whitened Gaussians (−log likelihoods in σ units), so their balance is statistical, not tuned.
// Δ_ρ, Δ_φ: the translation and rotation rows of the part's prior — ConstantVelocityCost on
// (t−1, t, t+1) (change of velocity) or ConstantAccelerationCost on (t−1, …, t+2) (change of
// acceleration), per MotionModel; W = diag(1/σ); ρ_ρ, ρ_φ Cauchy losses whose scales are given
// in physical units (robust_translation_mm, robust_rotation_deg; ρ(s) = s when 0).
// The prior is a Gaussian negative log-likelihood with standard deviations σ, the same currency
// as F (a −log likelihood per pixel).
// Anchors (keyframes, set by hand): an anchored frame t in the window adds ½‖diag(1/σ_k)·e‖²,
// e the displacement of T_t from the anchor pose (PoseGaussianCost; σ_k = keyframe_sigma_*),
// a strong prior that keeps the window from moving a hand-set pose away.
//
// Why this form (scripts/bench_window.sh, handheld-like binocular sequences): with one
// constant-velocity term and one Cauchy loss on the whole 6-vector, translation jitter fell by
// only 28–43 % (rotation ÷3.5–4.3), for two reasons, both in the prior:
//   - the shared loss: the rotation noise of the per-frame solves was ~2σ of the rotation prior,
//     the translation noise ~0.7σ, so the rotation part pushed every triple into the Cauchy's
//     down-weighted range and switched the translation prior off with it; a separate loss per
//     part, its scale a physical threshold (what separates a real change of motion from
//     noise is its size against the measurement noise, not against σ), fixes that;
//   - the model: a hand accelerates smoothly; the true change of the centre's velocity per
//     frame (median 0.14–0.22 mm/frame², p90 up to 0.5) exceeds the acceleration noise of the
//     per-frame solves (~0.07–0.1 mm/frame²), so a constant-velocity prior either bends the
//     real motion or leaves the noise; the change of acceleration is 3–7× smaller (median
//     0.02–0.06 mm/frame³), so the translation holds a constant acceleration. The rotation's
//     true changes of angular velocity are at or below its noise, and constant velocity is best
//     there (a constant-acceleration rotation prior lagged at the velocity step).
// Not the reason: the templates are not re-rendered inside the window, but the window moves the
// object centre by 0.02–0.03 mm on average (at most 0.15 mm, ~0.2 px at 600 mm), well inside
// the band where the linearised template holds; nor the per-axis weights: each rig axis is seen
// laterally by one camera of the 90° rig, and the per-frame translation noise differs by ~1.5×
// between axes (x, z above y), which the region terms' own curvature already weighs.
//
// Sliding scheme (step S = W − overlap):
//   window k covers frames [s_k, e_k), s_k = k·S, e_k = min(s_k + W, N);
//   free:      the frames of the window that have templates (a frame whose solve failed has
//              none and keeps its pose: it only conditions its neighbours);
//   conditioned on neighbours, held constant: the C = ContextFrames() frames before s_k (final
//              already: committed by earlier windows) and after e_k (their per-frame poses:
//              the best estimate available; C = 2, or 3 with an acceleration model), so
//              the priors at the borders see the motion on both sides and the window does not
//              bend the trajectory at its ends;
//   committed: frames [s_k, s_k + S) are final after window k; the overlap [s_k + S, e_k) is
//              solved again by window k+1 (from window k's result) with more right context.
// W = 0 solves the whole sequence as one window.
//
// Memory: WindowSmoother keeps the templates of at most W + C frames (the current window and
// the C look-ahead frames its priors need) and releases a frame's templates once it is
// committed; only the poses (N × 7 doubles) are kept for the whole sequence. Re-rendering the
// templates per window instead would need each frame's image and its colour-model state
// (the models blend over time), i.e. more memory or a second pass over the images; a bounded
// buffer of templates (~100 bytes × a few thousand band pixels per view and frame) is cheaper.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/core/status.h"
#include "bcot/optim/frame_problem.h"
#include "bcot/optim/motion_prior_cost.h"
#include "bcot/optim/pose_gaussian_cost.h"

namespace bcot {

// Motion model of one part (translation or rotation) of the window's prior.
enum class MotionModel {
  kConstantVelocity,      // ConstantVelocityCost on (t−1, t, t+1)
  kConstantAcceleration,  // ConstantAccelerationCost on (t−1, t, t+1, t+2)
};

struct WindowProblemOptions {
  // Refine the per-frame poses with the window (annotation: on, configs/annotate.yaml;
  // tracking: off, configs/track.yaml); false = per-frame poses as solved.
  bool enabled = true;
  // Frames per window W: 0 = the whole sequence in one window, else >= 3.
  int size = 30;
  // Frames shared by consecutive windows; in [0, size − 1] (ignored when size = 0).
  int overlap = 10;
  // Ceres Levenberg-Marquardt iterations per window; >= 1.
  int iterations = 10;
  // Form of the priors (motion_prior_cost.h): kDecoupled = centre motion in the rig frame and
  // body spin; kSe3 = body twist on SE(3).
  MotionPriorForm prior = MotionPriorForm::kDecoupled;
  // Motion model of each part of the prior (why these defaults: the header comment).
  MotionModel translation_model = MotionModel::kConstantAcceleration;
  MotionModel rotation_model = MotionModel::kConstantVelocity;
  // Standard deviations of the prior: the change per frame of the part's modelled quantity —
  // velocity (constant-velocity model, per frame²) or acceleration (constant-acceleration
  // model, per frame³) — per axis (x, y, z: rig axes for the translation of kDecoupled, object
  // axes otherwise); each > 0. Rotation in degrees, translation in mm; the prior weights are
  // W = diag(1/σ) (rad, mm).
  // Defaults measured by scripts/bench_window.sh (handheld-like synth, binocular 640×512) with
  // the edge posterior as the data term (calibrated: its predicted per-frame sd, ~0.02–0.025 mm
  // and ~0.035° per axis in window_problem_test, matches the per-frame errors there): the
  // smooth handheld motion's true change of acceleration is 0.014–0.022 mm/frame³ rms;
  // σ_ρ = 0.1 keeps translation jitter at the level of the former region-term window
  // (0.15 there) without bending the velocity steps (0.07 and 0.05: smoother on smooth
  // motion, 1.5–3.6× the error on the step frames).
  std::array<double, 3> rotation_sigma_deg = {0.1, 0.1, 0.1};
  std::array<double, 3> translation_sigma_mm = {0.1, 0.1, 0.1};
  // Robust prior, per part: the change per frame of the modelled quantity (translation in mm,
  // rotation in deg, per frame² or frame³) beyond which a span of frames is treated as a real
  // change of motion and its prior fades, so a sudden motion change is followed, not smoothed
  // away. Each part has its own Cauchy loss ρ(s) = c²·log(1 + s/c²) on its whitened residual,
  // c = threshold / σ̄ (σ̄ the geometric mean of the part's three σ; exact for isotropic σ).
  // Set above the noise of the per-frame solves in that quantity (bench: changes of velocity
  // ~0.1–0.2°/frame², changes of acceleration ~0.1–0.2 mm/frame³) and below the motion
  // changes to follow; each >= 0, 0 = plain quadratic prior for that part.
  double robust_translation_mm = 0.5;
  double robust_rotation_deg = 0.3;
  // Raise each window's σ to the motion's own (empirical Bayes, AdaptedPriorOptions): the
  // configured σ above are then the floor, fit for smooth handheld motion, and a faster motion
  // (a turntable, a thrown or swung object) is not bent toward the prior's model. Needs the
  // frames' edge posteriors for the noise's share: windows without any keep the configured σ.
  bool adaptive_prior = true;
  // A frame whose solve ended with the edge stage carries its edge pose posterior
  // (ViewLinearisation::edge_posterior): true = that Gaussian is the frame's data term in the
  // window, in place of its region terms; false = the region terms (whose minimum is biased
  // under shaded rims and pulls the window back towards it).
  bool edge_posterior = true;
  // Prior of an anchored frame (a keyframe) toward its hand-set pose: σ of the translation
  // (mm, each axis of the object-centred frame) and of the rotation (deg); finite, > 0. Set to
  // the accuracy the keyframes were set with; small = the window keeps the keyframe pose.
  double keyframe_sigma_translation_mm = 0.5;
  double keyframe_sigma_rotation_deg = 0.25;
  // Threads Ceres may use; >= 1.
  int num_threads = 1;

  // diag(W) of the prior costs: (1/σ_ρ in 1/mm, 1/σ_φ in 1/rad).
  Vector6d PriorWeights() const;
  // Frames before and after a window its priors reach: 3 with an acceleration model, else 2.
  int ContextFrames() const;
  // Cauchy scales c of the translation and rotation parts in σ units (0 = quadratic).
  double TranslationCauchyScale() const;
  double RotationCauchyScale() const;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

// Covariances of the per-frame poses' noise (their edge posteriors' prediction, averaged over a
// window): the object centre's translation in rig axes (mm²) and the rotation in the object's
// frame (rad², the frame of the body angular velocities the prior differences).
struct PerFrameNoise {
  Eigen::Matrix3d translation_mm2 = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rotation_rad2 = Eigen::Matrix3d::Zero();
};

// `options` with each part's prior σ raised to what the motion of `per_frame` (consecutive
// per-frame poses rig_from_objcentre, the window and its context) shows. The part's modelled
// quantity (change per frame of velocity or acceleration, window_problem.h) is differenced from
// the poses: a k-th difference d_t has covariance m²·I + c·Σ, m² the motion's variance per axis
// (the prior's model: the same on every axis) and Σ the covariance of the noise that changes
// from frame to frame (c = 6 for second and 20 for third differences of white noise). Σ is
// taken from `noise` (the edge posteriors' prediction, Σ_n), in one of two ways:
// - Σ_n about isotropic (largest eigenvalue < 10 × the smallest: two or more cameras): per axis,
//   with D_k = median ‖d_t‖² / 2.367 (2.367 the median of χ²₃) and D_{k+1} the same of the
//   (k+1)-th differences, D_k = m² + c_k·a and D_{k+1} = 2·m² + c_{k+1}·a (a difference of the
//   motion's white changes doubles their variance; white noise's grows from 6 to 20, or from 20
//   to 70). That gives the white noise's variance a, kept within [0, tr(Σ_n)/3]: the prediction
//   also holds the error's slow part, which differences do not see (on the Cycles scenes it
//   hid the rotation's motion entirely). m² = D_k − c_k·a.
// - Σ_n strongly anisotropic (one camera: its depth): Σ = α·Σ_n, α in [0, 1] the share of the
//   predicted noise that changes between frames (the slow part of a single camera's depth error
//   does not show in differences, and its posterior's prediction was calibrated on two
//   cameras). In each principal direction e_i of Σ_n (eigenvalue λ_i) the robust variance s_i²
//   of e_iᵀd_t (median of the squares ÷ 0.455, the median of χ²₁) is m² + α·c·λ_i; m² >= 0 and
//   α are fitted to the three by weighted least squares. The directions of large noise give α,
//   the others show the motion the noise would otherwise hide.
//   σ² = max(σ_configured², m²)   on every axis.
// Fewer than 5 spans: `options` unchanged.
WindowProblemOptions AdaptedPriorOptions(const WindowProblemOptions& options,
                                         const std::vector<Eigen::Isometry3d>& per_frame,
                                         const PerFrameNoise& noise);

struct WindowSummary {
  int first = 0;  // frames [first, end)
  int end = 0;
  int free_frames = 0;        // frames with a data term (the others were held)
  int edge_frames = 0;        // of those, frames whose data term is their edge posterior
  int iterations = 0;         // Ceres iterations
  double initial_cost = 0.0;  // Ceres cost (region energy + ½‖prior‖²) at the per-frame poses
  double final_cost = 0.0;
  // The prior σ the window ran with (raised by adaptive_prior where the motion asked for it).
  double translation_sigma_mm = 0.0;  // geometric mean of the three axes
  double rotation_sigma_deg = 0.0;
  bool usable = true;   // false: Ceres failed, the window's poses were left unchanged
  std::string message;  // Ceres' message when !usable
};

class WindowProblem {
 public:
  // `options` must be valid (CHECKed). `symmetry_in_objcentre`: the object's rotational
  // symmetry in O_o, if any; the window then keeps every frame's angle about its axis
  // (AxisLockedSe3Manifold).
  explicit WindowProblem(
      const WindowProblemOptions& options,
      const std::optional<RotationalSymmetry>& symmetry_in_objcentre = std::nullopt);

  // Refines (*rig_from_objcentre)[first, end) in one problem (see the header comment):
  // frame_views[t − first] are frame t's templates (empty = held constant); the C =
  // options().ContextFrames() poses before first and after end, where they exist, condition the
  // priors and are held constant. `anchors` (may be null): rig_from_objcentre by frame of the
  // anchored frames (see the header comment).
  // CHECKs 0 <= first < end <= size and frame_views.size() == end − first.
  WindowSummary Solve(int first, int end,
                      const std::vector<const std::vector<ViewLinearisation>*>& frame_views,
                      std::vector<Eigen::Isometry3d>* rig_from_objcentre,
                      const std::map<int, Eigen::Isometry3d>* anchors = nullptr) const;

  const WindowProblemOptions& options() const { return options_; }
  const std::optional<RotationalSymmetry>& symmetry_in_objcentre() const {
    return symmetry_in_objcentre_;
  }

 private:
  // The Gaussian of an anchor at `rig_from_objcentre` with the keyframe sigmas.
  PoseGaussian AnchorGaussian(const Eigen::Isometry3d& rig_from_objcentre) const;

  WindowProblemOptions options_;
  std::optional<RotationalSymmetry> symmetry_in_objcentre_;
};

// Runs the sliding windows over a sequence as its frames arrive, with bounded memory.
// Not thread-safe.
class WindowSmoother {
 public:
  // `options` must be valid (CHECKed); `symmetry_in_objcentre` as for WindowProblem.
  explicit WindowSmoother(
      const WindowProblemOptions& options,
      const std::optional<RotationalSymmetry>& symmetry_in_objcentre = std::nullopt);

  // Appends the next frame: its per-frame pose and templates (empty when its solve failed).
  // Solves every window whose frames and look-ahead have all arrived.
  void Push(const Eigen::Isometry3d& rig_from_objcentre, std::vector<ViewLinearisation> views);
  // Anchors frames (rig_from_objcentre by frame index) toward hand-set poses; call before the
  // first Push.
  void SetAnchors(std::map<int, Eigen::Isometry3d> anchors);
  // Solves the remaining windows; call once after the last Push.
  void Finish();

  // Every pushed frame's pose: refined where its window ran, the per-frame pose otherwise.
  const std::vector<Eigen::Isometry3d>& rig_from_objcentre() const { return poses_; }
  const std::vector<WindowSummary>& windows() const { return windows_; }
  // Frames whose templates are held now (the memory bound: <= W + C while streaming).
  int buffered_frames() const { return static_cast<int>(buffer_.size()); }

 private:
  // Solves the window starting at next_start_ and ending at `end`, then commits and releases.
  void SolveWindow(int end);

  // The noise of frames [first, end) predicted by their edge posteriors (frames without one
  // are left out); none when no frame has one.
  std::optional<PerFrameNoise> PredictedNoise(int first, int end) const;

  WindowProblem problem_;
  std::vector<Eigen::Isometry3d> poses_;
  std::vector<Eigen::Isometry3d> per_frame_poses_;     // as pushed
  std::deque<std::vector<ViewLinearisation>> buffer_;  // frames [buffer_first_, poses_.size())
  int buffer_first_ = 0;
  int next_start_ = 0;
  bool finished_ = false;
  std::vector<WindowSummary> windows_;
  std::map<int, Eigen::Isometry3d> anchors_;
};

}  // namespace bcot

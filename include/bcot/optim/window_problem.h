// The temporal smoothing window (DESIGN.md "Temporal smoothing window"): after the per-frame
// joint solves, windows of W consecutive frames are refined jointly. One ceres::Problem per
// window holds, for every frame t of the window, the region residuals of all its views — the
// level-0 templates its own per-frame solve ended with (ViewLinearisation, frame_problem.h) —
// and the constant-velocity priors (motion_prior_cost.h) on every triple (t−1, t, t+1) touching
// the window. Parameter blocks are rig_from_objcentre (Se3Manifold), solved with
// SPARSE_NORMAL_CHOLESKY (SuiteSparse): the normal equations are block-tridiagonal (7×7 blocks).
//
// Energy of a window [s, e):  Σ_t Σ_views w_v·Σ_x F_t,x(T_t)  +  ½ Σ_t ‖W·(ξ_{t−1,t} − ξ_{t,t+1})‖²
// (with robust_scale > 0 the prior term is ρ(‖·‖²) with a Cauchy loss, see the options).
// The first term is each frame's own region energy, linearised where its solve ended (the
// templates are not re-rendered: the window moves poses by a fraction of a pixel, well inside
// the band). The prior is a Gaussian negative log-likelihood of the change of body velocity with
// standard deviations σ (W = diag(1/σ)), the same currency as F (a −log likelihood per pixel).
//
// Sliding scheme (step S = W − overlap):
//   window k covers frames [s_k, e_k), s_k = k·S, e_k = min(s_k + W, N);
//   free:      the frames of the window that have templates (a frame whose solve failed has
//              none and keeps its pose: it only conditions its neighbours);
//   conditioned on neighbours, held constant: s_k−2, s_k−1 (final already: committed by earlier
//              windows) and e_k, e_k+1 (their per-frame poses: the best estimate available), so
//              the priors at the borders see the motion on both sides and the window does not
//              bend the trajectory at its ends;
//   committed: frames [s_k, s_k + S) are final after window k; the overlap [s_k + S, e_k) is
//              solved again by window k+1 (from window k's result) with more right context.
// W = 0 solves the whole sequence as one window.
//
// Memory: WindowSmoother keeps the templates of at most W + 2 frames (the current window and
// the two look-ahead frames its priors need) and releases a frame's templates once it is
// committed; only the poses (N × 7 doubles) are kept for the whole sequence. Re-rendering the
// templates per window instead would need each frame's image and its colour-model state
// (the models blend over time), i.e. more memory or a second pass over the images; a bounded
// buffer of templates (~100 bytes × a few thousand band pixels per view and frame) is cheaper.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <deque>
#include <string>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/core/status.h"
#include "bcot/optim/frame_problem.h"
#include "bcot/optim/motion_prior_cost.h"

namespace bcot {

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
  // Form of the constant-velocity prior (motion_prior_cost.h): kDecoupled = centre velocity in
  // the rig frame and body angular velocity; kSe3 = body twist on SE(3).
  MotionPriorForm prior = MotionPriorForm::kDecoupled;
  // Standard deviations of the prior: the change of velocity per frame expected between
  // consecutive frame steps, per axis (x, y, z: rig axes for the translation of kDecoupled,
  // object axes otherwise); each > 0. Rotation in degrees, translation in mm; the prior
  // weights are W = diag(1/σ) (rad, mm).
  // Defaults measured by scripts/bench_window.sh (handheld-like synth, binocular 640×512).
  std::array<double, 3> rotation_sigma_deg = {0.05, 0.05, 0.05};
  std::array<double, 3> translation_sigma_mm = {0.1, 0.1, 0.1};
  // Robust prior: the whitened velocity change ‖W·(ξ₁ − ξ₂)‖ (in σ) beyond which a triple is
  // treated as a real change of motion and its prior fades (Cauchy loss with this scale:
  // ρ(s) = c²·log(1 + s/c²)), so a sudden motion change is followed, not smoothed away;
  // >= 0, 0 = plain quadratic prior.
  double robust_scale = 2.0;
  // Threads Ceres may use; >= 1.
  int num_threads = 1;

  // diag(W) for ConstantVelocityCost: (1/σ_ρ in 1/mm, 1/σ_φ in 1/rad).
  Vector6d PriorWeights() const;
  // Lists every violation (field, value, rule) in one kInvalidConfig status.
  Status Validate() const;
};

struct WindowSummary {
  int first = 0;  // frames [first, end)
  int end = 0;
  int free_frames = 0;        // frames with region residuals (the others were held)
  int iterations = 0;         // Ceres iterations
  double initial_cost = 0.0;  // Ceres cost (region energy + ½‖prior‖²) at the per-frame poses
  double final_cost = 0.0;
  bool usable = true;   // false: Ceres failed, the window's poses were left unchanged
  std::string message;  // Ceres' message when !usable
};

class WindowProblem {
 public:
  // `options` must be valid (CHECKed).
  explicit WindowProblem(const WindowProblemOptions& options);

  // Refines (*rig_from_objcentre)[first, end) in one problem (see the header comment):
  // frame_views[t − first] are frame t's templates (empty = held constant); poses first−2,
  // first−1, end, end+1, where they exist, condition the priors and are held constant.
  // CHECKs 0 <= first < end <= size and frame_views.size() == end − first.
  WindowSummary Solve(int first, int end,
                      const std::vector<const std::vector<ViewLinearisation>*>& frame_views,
                      std::vector<Eigen::Isometry3d>* rig_from_objcentre) const;

  const WindowProblemOptions& options() const { return options_; }

 private:
  WindowProblemOptions options_;
};

// Runs the sliding windows over a sequence as its frames arrive, with bounded memory.
// Not thread-safe.
class WindowSmoother {
 public:
  // `options` must be valid (CHECKed).
  explicit WindowSmoother(const WindowProblemOptions& options);

  // Appends the next frame: its per-frame pose and templates (empty when its solve failed).
  // Solves every window whose frames and look-ahead have all arrived.
  void Push(const Eigen::Isometry3d& rig_from_objcentre, std::vector<ViewLinearisation> views);
  // Solves the remaining windows; call once after the last Push.
  void Finish();

  // Every pushed frame's pose: refined where its window ran, the per-frame pose otherwise.
  const std::vector<Eigen::Isometry3d>& rig_from_objcentre() const { return poses_; }
  const std::vector<WindowSummary>& windows() const { return windows_; }
  // Frames whose templates are held now (the memory bound: <= W + 2 while streaming).
  int buffered_frames() const { return static_cast<int>(buffer_.size()); }

 private:
  // Solves the window starting at next_start_ and ending at `end`, then commits and releases.
  void SolveWindow(int end);

  WindowProblem problem_;
  std::vector<Eigen::Isometry3d> poses_;
  std::deque<std::vector<ViewLinearisation>> buffer_;  // frames [buffer_first_, poses_.size())
  int buffer_first_ = 0;
  int next_start_ = 0;
  bool finished_ = false;
  std::vector<WindowSummary> windows_;
};

}  // namespace bcot

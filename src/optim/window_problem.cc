#include "bcot/optim/window_problem.h"

#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include "bcot/core/se3.h"
#include "bcot/core/violations.h"
#include "bcot/optim/correspondence_line_cost.h"
#include "bcot/optim/motion_prior_cost.h"
#include "bcot/optim/pose_gaussian_cost.h"
#include "bcot/optim/region_cost.h"
#include "bcot/optim/se3_manifold.h"

namespace bcot {
namespace {

// The first differences of `values`; applied k times, the k-th.
std::vector<Eigen::Vector3d> Differences(const std::vector<Eigen::Vector3d>& values) {
  std::vector<Eigen::Vector3d> differences;
  for (size_t t = 0; t + 1 < values.size(); ++t) differences.push_back(values[t + 1] - values[t]);
  return differences;
}
std::vector<Eigen::Vector3d> Differences(std::vector<Eigen::Vector3d> values, int k) {
  for (int order = 0; order < k; ++order) values = Differences(values);
  return values;
}

// Robust variance of `values`' squares' distribution: the median of the squares ÷ `median`
// (the median of the χ² the squares follow when the values are Gaussian of unit variance).
double RobustVariance(std::vector<double> squares, double median) {
  const size_t mid = squares.size() / 2;
  std::nth_element(squares.begin(), squares.begin() + mid, squares.end());
  return squares[mid] / median;
}

// Medians of χ²₁ and χ²₃ (the latter as 3 × 0.789, the median of χ²₃/3).
constexpr double kMedianChiSquare1 = 0.4549;
constexpr double kMedianChiSquare3 = 3.0 * 0.789;

// The variance of the k-th difference of unit white noise: 1 + 4 + 1 = 6 (k = 2), 1 + 9 + 9 +
// 1 = 20 (k = 3), 1 + 16 + 36 + 16 + 1 = 70 (k = 4).
double WhiteNoiseFactor(int k) { return k == 2 ? 6.0 : k == 3 ? 20.0 : 70.0; }

// m² for about isotropic noise of predicted variance `predicted` per axis (header of
// AdaptedPriorOptions): the white noise's variance a is told from the motion by how the
// differences' variance grows with one more difference, ×2 for the motion's white changes and
// c_{k+1}/c_k for white noise. With D_k = m² + c_k·a and D_{k+1} = 2m² + c_{k+1}·a,
// a = (D_{k+1} − 2·D_k) / (c_{k+1} − 2·c_k), kept within [0, predicted].
double IsotropicMotionVariance(const std::vector<Eigen::Vector3d>& differences, double predicted,
                               int k) {
  std::vector<double> squares;
  for (const Eigen::Vector3d& d : differences) squares.push_back(d.squaredNorm());
  const double variance = RobustVariance(squares, kMedianChiSquare3);
  squares.clear();
  for (const Eigen::Vector3d& d : Differences(differences)) squares.push_back(d.squaredNorm());
  const double next_variance = RobustVariance(squares, kMedianChiSquare3);
  const double white = std::clamp(
      (next_variance - 2.0 * variance) / (WhiteNoiseFactor(k + 1) - 2.0 * WhiteNoiseFactor(k)), 0.0,
      predicted);
  return std::max(0.0, variance - WhiteNoiseFactor(k) * white);
}

// m² for strongly anisotropic predicted noise (`principal`: its eigen-decomposition; header of
// AdaptedPriorOptions): per principal direction s_i² = m² + α·c_k·λ_i, fitted by least squares
// with m² >= 0 and α in [0, 1], each s_i² weighted by its inverse variance (∝ its expected value
// squared: the observed one first, then the fit's).
double AnisotropicMotionVariance(const std::vector<Eigen::Vector3d>& differences,
                                 const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>& principal,
                                 int k) {
  const Eigen::Vector3d g = WhiteNoiseFactor(k) * principal.eigenvalues().cwiseMax(0.0);
  Eigen::Vector3d s2;
  std::vector<double> squares(differences.size());
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d direction = principal.eigenvectors().col(i);
    for (size_t t = 0; t < differences.size(); ++t) {
      squares[t] = std::pow(direction.dot(differences[t]), 2);
    }
    s2[i] = RobustVariance(squares, kMedianChiSquare1);
  }
  const double smallest_expected = 1e-6 * g.maxCoeff();  // keeps every weight finite
  double motion = 0.0, alpha = 1.0;
  for (int pass = 0; pass < 4; ++pass) {
    Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
    Eigen::Vector2d right = Eigen::Vector2d::Zero();
    Eigen::Vector3d weights;
    for (int i = 0; i < 3; ++i) {
      const double expected =
          std::max(pass == 0 ? s2[i] : motion + alpha * g[i], smallest_expected);
      weights[i] = 1.0 / (expected * expected);
      const Eigen::Vector2d row(1.0, g[i]);
      normal += weights[i] * row * row.transpose();
      right += weights[i] * s2[i] * row;
    }
    alpha = std::clamp(normal.ldlt().solve(right)[1], 0.0, 1.0);
    motion = std::max(0.0, weights.dot(s2 - alpha * g) / weights.sum());
  }
  return motion;
}

// The motion's variance m² per axis in its k-th differences `differences`, with the share of
// the predicted noise `noise` that changes between frames removed (header of
// AdaptedPriorOptions); −1 when there are fewer than 5 differences.
double MotionVariance(const std::vector<Eigen::Vector3d>& differences, const Eigen::Matrix3d& noise,
                      int k) {
  if (differences.size() < 5) return -1.0;
  // Below this ratio of the largest to the smallest noise variance, the noise's scale and the
  // motion cannot be told apart along its directions from a window's spans (each s_i², a
  // median of some 35 squares, is known to about ±40 %).
  constexpr double kSeparableNoiseRatio = 10.0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(noise);
  const Eigen::Vector3d eigenvalues = principal.eigenvalues().cwiseMax(0.0);
  if (eigenvalues.minCoeff() > 0.0 &&
      eigenvalues.maxCoeff() >= kSeparableNoiseRatio * eigenvalues.minCoeff()) {
    return AnisotropicMotionVariance(differences, principal, k);
  }
  return IsotropicMotionVariance(differences, eigenvalues.sum() / 3.0, k);
}

// σ_k = max(σ_k, m·unit) on each axis; unchanged when m² < 0 (too few spans).
void RaiseSigmas(double motion_variance, double unit, std::array<double, 3>* sigmas) {
  if (motion_variance < 0.0) return;
  const double motion = std::sqrt(motion_variance) * unit;
  for (double& sigma : *sigmas) sigma = std::max(sigma, motion);
}

}  // namespace

WindowProblemOptions AdaptedPriorOptions(const WindowProblemOptions& options,
                                         const std::vector<Eigen::Isometry3d>& per_frame,
                                         const PerFrameNoise& noise) {
  WindowProblemOptions adapted = options;
  // Translation: the object centre in the rig frame; its velocity is the first difference.
  std::vector<Eigen::Vector3d> centres;
  for (const Eigen::Isometry3d& pose : per_frame) centres.push_back(pose.translation());
  const int translation_order =
      options.translation_model == MotionModel::kConstantAcceleration ? 3 : 2;
  RaiseSigmas(MotionVariance(Differences(centres, translation_order), noise.translation_mm2,
                             translation_order),
              1.0, &adapted.translation_sigma_mm);
  // Rotation: the body angular velocity ω_t = Log(R_tᵀR_{t+1}) is the first difference.
  std::vector<Eigen::Vector3d> velocities;
  for (size_t t = 0; t + 1 < per_frame.size(); ++t) {
    velocities.push_back(
        LogSO3(Eigen::Matrix3d(per_frame[t].linear().transpose() * per_frame[t + 1].linear())));
  }
  // Differences of ω of order 1 (velocity model) or 2 (acceleration) are differences of order
  // 2 or 3 of the accumulated angles.
  std::vector<Eigen::Vector3d> angles = {Eigen::Vector3d::Zero()};
  for (const Eigen::Vector3d& w : velocities) angles.push_back(angles.back() + w);
  const int rotation_order = options.rotation_model == MotionModel::kConstantAcceleration ? 3 : 2;
  RaiseSigmas(
      MotionVariance(Differences(angles, rotation_order), noise.rotation_rad2, rotation_order),
      180.0 / kPi, &adapted.rotation_sigma_deg);
  return adapted;
}

// A prior term spans 3 (velocity) or 4 (acceleration) frames, so a term touching the window
// reaches that many frames − 1 out of it.
int WindowProblemOptions::ContextFrames() const {
  const bool acceleration = translation_model == MotionModel::kConstantAcceleration ||
                            rotation_model == MotionModel::kConstantAcceleration;
  return acceleration ? 3 : 2;
}

Vector6d WindowProblemOptions::PriorWeights() const {
  Vector6d weights;
  for (int k = 0; k < 3; ++k) {
    weights[k] = 1.0 / translation_sigma_mm[k];
    weights[3 + k] = 1.0 / (rotation_sigma_deg[k] * kPi / 180.0);
  }
  return weights;
}

double WindowProblemOptions::TranslationCauchyScale() const {
  const double sigma_mm =
      std::cbrt(translation_sigma_mm[0] * translation_sigma_mm[1] * translation_sigma_mm[2]);
  return robust_translation_mm / sigma_mm;
}

double WindowProblemOptions::RotationCauchyScale() const {
  const double sigma_deg =
      std::cbrt(rotation_sigma_deg[0] * rotation_sigma_deg[1] * rotation_sigma_deg[2]);
  return robust_rotation_deg / sigma_deg;
}

Status WindowProblemOptions::Validate() const {
  std::vector<std::string> violations;
  if (size != 0 && size < 3) {
    violations.push_back(fmt::format("size = {}, must be 0 (whole sequence) or >= 3", size));
  }
  if (size != 0 && (overlap < 0 || overlap > size - 1)) {
    violations.push_back(
        fmt::format("overlap = {}, must be in [0, size − 1 = {}]", overlap, std::max(size - 1, 0)));
  }
  if (size == 0 && overlap < 0) {
    violations.push_back(fmt::format("overlap = {}, must be >= 0", overlap));
  }
  if (iterations < 1) {
    violations.push_back(fmt::format("iterations = {}, must be >= 1", iterations));
  }
  const char* axes[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    if (!(rotation_sigma_deg[k] > 0.0) || !std::isfinite(rotation_sigma_deg[k])) {
      violations.push_back(fmt::format("rotation_sigma_deg = {} ({}), must be finite and > 0",
                                       rotation_sigma_deg[k], axes[k]));
    }
    if (!(translation_sigma_mm[k] > 0.0) || !std::isfinite(translation_sigma_mm[k])) {
      violations.push_back(fmt::format("translation_sigma_mm = {} ({}), must be finite and > 0",
                                       translation_sigma_mm[k], axes[k]));
    }
  }
  for (const auto& [name, value] : {std::pair{"robust_translation_mm", robust_translation_mm},
                                    std::pair{"robust_rotation_deg", robust_rotation_deg}}) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      violations.push_back(fmt::format("{} = {}, must be finite and >= 0", name, value));
    }
  }
  for (const auto& [name, value] :
       {std::pair{"keyframe_sigma_translation_mm", keyframe_sigma_translation_mm},
        std::pair{"keyframe_sigma_rotation_deg", keyframe_sigma_rotation_deg}}) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      violations.push_back(fmt::format("{} = {}, must be finite and > 0", name, value));
    }
  }
  if (num_threads < 1) {
    violations.push_back(fmt::format("num_threads = {}, must be >= 1", num_threads));
  }
  return internal::JoinViolations("window", violations);
}

WindowProblem::WindowProblem(const WindowProblemOptions& options,
                             const std::optional<RotationalSymmetry>& symmetry_in_objcentre)
    : options_(options), symmetry_in_objcentre_(symmetry_in_objcentre) {
  BCOT_CHECK(options_.Validate().ok());
}

PoseGaussian WindowProblem::AnchorGaussian(const Eigen::Isometry3d& rig_from_objcentre) const {
  PoseGaussian gaussian;
  gaussian.mean = rig_from_objcentre;
  const double translation_weight = 1.0 / options_.keyframe_sigma_translation_mm;
  const double rotation_weight = 1.0 / (options_.keyframe_sigma_rotation_deg * M_PI / 180.0);
  gaussian.sqrt_information.diagonal() << translation_weight, translation_weight,
      translation_weight, rotation_weight, rotation_weight, rotation_weight;
  return gaussian;
}

WindowSummary WindowProblem::Solve(
    int first, int end, const std::vector<const std::vector<ViewLinearisation>*>& frame_views,
    std::vector<Eigen::Isometry3d>* rig_from_objcentre,
    const std::map<int, Eigen::Isometry3d>* anchors) const {
  BCOT_CHECK(rig_from_objcentre != nullptr);
  const int num_frames = static_cast<int>(rig_from_objcentre->size());
  BCOT_CHECK(0 <= first && first < end && end <= num_frames);
  BCOT_CHECK(static_cast<int>(frame_views.size()) == end - first);
  WindowSummary summary;
  summary.first = first;
  summary.end = end;
  summary.translation_sigma_mm =
      std::cbrt(options_.translation_sigma_mm[0] * options_.translation_sigma_mm[1] *
                options_.translation_sigma_mm[2]);
  summary.rotation_sigma_deg =
      std::cbrt(options_.rotation_sigma_deg[0] * options_.rotation_sigma_deg[1] *
                options_.rotation_sigma_deg[2]);

  // Parameter blocks for the window and its context frames [lo, hi).
  const int context = options_.ContextFrames();
  const int lo = std::max(0, first - context);
  const int hi = std::min(num_frames, end + context);
  std::vector<PoseParameters> parameters(hi - lo);
  std::vector<bool> free(hi - lo, false);
  const std::unique_ptr<ceres::Manifold> manifold = NewPoseManifold(symmetry_in_objcentre_);
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (int t = lo; t < hi; ++t) {
    parameters[t - lo] = ToPoseParameters((*rig_from_objcentre)[t]);
    double* block = parameters[t - lo].data();
    problem.AddParameterBlock(block, kPoseAmbientSize, manifold.get());
    const bool in_window = t >= first && t < end;
    if (in_window && frame_views[t - first] != nullptr && !frame_views[t - first]->empty()) {
      free[t - lo] = true;
      ++summary.free_frames;
      const std::vector<ViewLinearisation>& views = *frame_views[t - first];
      if (anchors != nullptr) {
        const auto anchor = anchors->find(t);
        if (anchor != anchors->end()) {
          problem.AddResidualBlock(new PoseGaussianCost(AnchorGaussian(anchor->second)), nullptr,
                                   block);
        }
      }
      if (options_.edge_posterior && views.front().edge_posterior != nullptr) {
        // The frame's edge posterior replaces its region terms (window_problem.h).
        ++summary.edge_frames;
        problem.AddResidualBlock(new PoseGaussianCost(*views.front().edge_posterior), nullptr,
                                 block);
        continue;
      }
      for (const ViewLinearisation& view : views) {
        if (view.region_template != nullptr) {
          AddRegionResidualBlocks(view.camera, view.cam_from_rig, view.region_template, view.cost,
                                  block, &problem);
        }
        if (view.lines != nullptr) {
          problem.AddResidualBlock(
              new CorrespondenceLineCostFunction(view.camera, view.cam_from_rig, view.lines,
                                                 view.line_weight),
              nullptr, block);
        }
      }
    } else {
      problem.SetParameterBlockConstant(block);
    }
  }
  if (summary.free_frames == 0) return summary;

  // Two prior terms per span of frames, the translation rows and the rotation rows of the
  // part's cost (the other part's weights zero), each with its own model and loss.
  const Vector6d weights = options_.PriorWeights();
  struct Part {
    Vector6d weights;
    MotionModel model;
    double scale;
  };
  Part parts[] = {{weights, options_.translation_model, options_.TranslationCauchyScale()},
                  {weights, options_.rotation_model, options_.RotationCauchyScale()}};
  parts[0].weights.tail<3>().setZero();
  parts[1].weights.head<3>().setZero();
  for (const Part& part : parts) {
    const int span = part.model == MotionModel::kConstantAcceleration ? 4 : 3;
    for (int t = lo; t + span <= hi; ++t) {
      bool touches_free = false;
      std::vector<double*> blocks;
      for (int k = t; k < t + span; ++k) {
        touches_free = touches_free || free[k - lo];
        blocks.push_back(parameters[k - lo].data());
      }
      if (!touches_free) continue;
      ceres::LossFunction* loss = part.scale > 0.0 ? new ceres::CauchyLoss(part.scale) : nullptr;
      ceres::CostFunction* cost =
          span == 4 ? static_cast<ceres::CostFunction*>(
                          new ConstantAccelerationCost(part.weights, options_.prior))
                    : new ConstantVelocityCost(part.weights, options_.prior);
      problem.AddResidualBlock(cost, loss, blocks);
    }
  }

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  solver_options.max_num_iterations = options_.iterations;
  solver_options.num_threads = options_.num_threads;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, &problem, &ceres_summary);
  summary.iterations = static_cast<int>(ceres_summary.iterations.size()) - 1;
  summary.initial_cost = ceres_summary.initial_cost;
  summary.final_cost = ceres_summary.final_cost;
  if (!ceres_summary.IsSolutionUsable() || !std::isfinite(ceres_summary.final_cost)) {
    summary.usable = false;
    summary.message = ceres_summary.message;
    return summary;
  }
  for (int t = first; t < end; ++t) {
    if (free[t - lo]) (*rig_from_objcentre)[t] = FromPoseParameters(parameters[t - lo].data());
  }
  return summary;
}

WindowSmoother::WindowSmoother(const WindowProblemOptions& options,
                               const std::optional<RotationalSymmetry>& symmetry_in_objcentre)
    : problem_(options, symmetry_in_objcentre) {}

void WindowSmoother::Push(const Eigen::Isometry3d& rig_from_objcentre,
                          std::vector<ViewLinearisation> views) {
  BCOT_CHECK(!finished_);
  poses_.push_back(rig_from_objcentre);
  per_frame_poses_.push_back(rig_from_objcentre);
  buffer_.push_back(std::move(views));
  const int size = problem_.options().size;
  if (size == 0) return;  // whole sequence: everything waits for Finish
  // Window [next_start_, next_start_ + W) runs once its look-ahead frames have arrived.
  while (next_start_ + size + problem_.options().ContextFrames() <=
         static_cast<int>(poses_.size())) {
    SolveWindow(next_start_ + size);
  }
}

void WindowSmoother::SetAnchors(std::map<int, Eigen::Isometry3d> anchors) {
  BCOT_CHECK(poses_.empty());
  anchors_ = std::move(anchors);
}

void WindowSmoother::Finish() {
  BCOT_CHECK(!finished_);
  finished_ = true;
  const int num_frames = static_cast<int>(poses_.size());
  const int size = problem_.options().size;
  while (next_start_ < num_frames) {
    const int end = size == 0 ? num_frames : std::min(next_start_ + size, num_frames);
    SolveWindow(end);
    if (end == num_frames) break;
  }
  buffer_.clear();
  buffer_first_ = num_frames;
}

std::optional<PerFrameNoise> WindowSmoother::PredictedNoise(int first, int end) const {
  PerFrameNoise noise;
  int frames = 0;
  for (int t = std::max(first, buffer_first_); t < end; ++t) {
    const std::vector<ViewLinearisation>& views = buffer_[t - buffer_first_];
    if (views.empty() || views.front().edge_posterior == nullptr) continue;
    const Matrix6d& u = views.front().edge_posterior->sqrt_information;
    const Matrix6d covariance = (u.transpose() * u).inverse();
    // The tangent (ρ, φ) is in the object-centred frame (se3_manifold.h): the centre moves by
    // R·ρ in rig axes; φ is the body rotation the prior's angular velocities are taken in.
    const Eigen::Matrix3d rotation = per_frame_poses_[t].linear();
    noise.translation_mm2 += rotation * covariance.topLeftCorner<3, 3>() * rotation.transpose();
    noise.rotation_rad2 += covariance.bottomRightCorner<3, 3>();
    ++frames;
  }
  if (frames == 0) return std::nullopt;
  noise.translation_mm2 /= frames;
  noise.rotation_rad2 /= frames;
  return noise;
}

void WindowSmoother::SolveWindow(int end) {
  const int first = next_start_;
  std::vector<const std::vector<ViewLinearisation>*> frame_views;
  for (int t = first; t < end; ++t) frame_views.push_back(&buffer_[t - buffer_first_]);
  const WindowProblemOptions& configured = problem_.options();
  const int hi = std::min(static_cast<int>(poses_.size()), end + configured.ContextFrames());
  const std::optional<PerFrameNoise> noise =
      configured.adaptive_prior ? PredictedNoise(first, hi) : std::nullopt;
  if (noise.has_value()) {
    const int lo = std::max(0, first - configured.ContextFrames());
    const std::vector<Eigen::Isometry3d> span(per_frame_poses_.begin() + lo,
                                              per_frame_poses_.begin() + hi);
    const WindowProblem adapted(AdaptedPriorOptions(configured, span, *noise),
                                problem_.symmetry_in_objcentre());
    windows_.push_back(adapted.Solve(first, end, frame_views, &poses_, &anchors_));
  } else {
    windows_.push_back(problem_.Solve(first, end, frame_views, &poses_, &anchors_));
  }
  const int size = problem_.options().size;
  const int step = size == 0 ? end - first : size - problem_.options().overlap;
  next_start_ = std::min(first + step, end);
  // Frames before the next window are committed: release their templates.
  while (buffer_first_ < next_start_ && !buffer_.empty()) {
    buffer_.pop_front();
    ++buffer_first_;
  }
}

}  // namespace bcot

#include "bcot/optim/frame_problem.h"

#include <ceres/crs_matrix.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/core/violations.h"
#include "bcot/optim/correspondence_line_cost.h"
#include "bcot/optim/pose_damping_cost.h"
#include "bcot/optim/se3_manifold.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/mesh.h"

namespace bcot {

Status FrameProblemOptions::Validate() const {
  std::vector<std::string> violations;
  if (rounds < 1) violations.push_back(fmt::format("rounds = {}, must be >= 1", rounds));
  if (iterations < 1) {
    violations.push_back(fmt::format("iterations = {}, must be >= 1", iterations));
  }
  if (pyramid_levels < 1 || pyramid_levels > 6) {
    violations.push_back(fmt::format("pyramid_levels = {}, must be in [1, 6]", pyramid_levels));
  }
  if (!(round_tolerance_deg >= 0.0) || !std::isfinite(round_tolerance_deg)) {
    violations.push_back(
        fmt::format("round_tolerance_deg = {}, must be finite and >= 0", round_tolerance_deg));
  }
  if (!(round_tolerance_mm >= 0.0) || !std::isfinite(round_tolerance_mm)) {
    violations.push_back(
        fmt::format("round_tolerance_mm = {}, must be finite and >= 0", round_tolerance_mm));
  }
  if (!(damping_translation_mm >= 0.0) || !std::isfinite(damping_translation_mm)) {
    violations.push_back(fmt::format("damping_translation_mm = {}, must be finite and >= 0",
                                     damping_translation_mm));
  }
  if (!(damping_rotation_deg >= 0.0) || !std::isfinite(damping_rotation_deg)) {
    violations.push_back(
        fmt::format("damping_rotation_deg = {}, must be finite and >= 0", damping_rotation_deg));
  }
  if (!(coarse_check_min_shift_px >= 0.0) || !std::isfinite(coarse_check_min_shift_px)) {
    violations.push_back(fmt::format("coarse_check_min_shift_px = {}, must be finite and >= 0",
                                     coarse_check_min_shift_px));
  }
  if (coarse_rounds < 1) {
    violations.push_back(fmt::format("coarse_rounds = {}, must be >= 1", coarse_rounds));
  }
  if (num_threads < 1) {
    violations.push_back(fmt::format("num_threads = {}, must be >= 1", num_threads));
  }
  const Status region_status = region.Validate();
  if (!region_status.ok()) violations.push_back(region_status.message());
  const Status cost_status = cost.Validate();
  if (!cost_status.ok()) violations.push_back(cost_status.message());
  if (energy != RegionEnergy::kDense && energy != RegionEnergy::kSparse &&
      energy != RegionEnergy::kCombined) {
    violations.push_back(
        fmt::format("energy = {}, must be dense, sparse or combined", static_cast<int>(energy)));
  }
  if (energy != RegionEnergy::kDense && lines.weight == 0.0) {
    violations.push_back("lines.weight = 0, must be > 0 when the sparse energy is used");
  }
  if (lines_from_viewpoint_model && energy != RegionEnergy::kSparse) {
    violations.push_back(
        "lines_from_viewpoint_model = true, needs energy = sparse (the dense energy renders the "
        "silhouette anyway)");
  }
  const Status lines_status = lines.Validate();
  if (!lines_status.ok()) violations.push_back(lines_status.message());
  const Status edge_status = edge.Validate();
  if (!edge_status.ok()) violations.push_back(edge_status.message());
  return internal::JoinViolations("frame_problem", violations);
}

Status EdgeRefineOptions::Validate() const {
  std::vector<std::string> violations;
  if (rounds < 1) violations.push_back(fmt::format("rounds = {}, must be >= 1", rounds));
  if (iterations < 1) {
    violations.push_back(fmt::format("iterations = {}, must be >= 1", iterations));
  }
  if (!(robust_scale > 0.0) || !std::isfinite(robust_scale)) {
    violations.push_back(fmt::format("robust_scale = {}, must be finite and > 0", robust_scale));
  }
  if (redescending_rounds < 0) {
    violations.push_back(
        fmt::format("redescending_rounds = {}, must be >= 0", redescending_rounds));
  }
  if (!(redescending_scale > 0.0) || !std::isfinite(redescending_scale)) {
    violations.push_back(
        fmt::format("redescending_scale = {}, must be finite and > 0", redescending_scale));
  }
  if (min_lines < 6) violations.push_back(fmt::format("min_lines = {}, must be >= 6", min_lines));
  for (const Status& status : {lines.Validate(), chroma_restoration.Validate()}) {
    if (!status.ok()) violations.push_back(status.message());
  }
  return internal::JoinViolations("edge", violations);
}

const char* RegionEnergyName(RegionEnergy energy) {
  switch (energy) {
    case RegionEnergy::kDense:
      return "dense";
    case RegionEnergy::kSparse:
      return "sparse";
    case RegionEnergy::kCombined:
      return "combined";
  }
  return "unknown";
}

const char* FrameTerminationName(FrameTermination termination) {
  switch (termination) {
    case FrameTermination::kConverged:
      return "converged";
    case FrameTermination::kMaxRounds:
      return "max_rounds";
    case FrameTermination::kNotVisible:
      return "not_visible";
    case FrameTermination::kSolverFailure:
      return "solver_failure";
  }
  return "unknown";
}

namespace {

// One Ceres solve of a 6-dof pose problem (the region rounds and the edge stage): dense normal
// Cholesky, silent.
ceres::Solver::Summary SolvePose(int max_iterations, int num_threads, ceres::Problem* problem) {
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = max_iterations;
  solver_options.num_threads = num_threads;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, problem, &summary);
  return summary;
}

// The template and cost options of pyramid level `level` (scale 2^level, see the header).
struct LevelOptions {
  RegionTemplateOptions region;
  RegionCostOptions cost;
  CorrespondenceLineOptions lines;
};

LevelOptions OptionsAtLevel(const FrameProblemOptions& options, int level) {
  const int scale = 1 << level;
  LevelOptions result;
  result.region = options.region;
  result.region.band_px *= scale;
  result.region.stride_px *= scale;
  result.region.contour.sample_spacing_px *= scale;
  result.cost = options.cost;
  result.cost.heaviside_slope /= scale;
  result.lines = options.lines;
  result.lines.scale_px *= scale;
  result.lines.half_length_px *= scale;
  result.lines.min_side_px *= scale;
  result.lines.slope_px *= scale;
  result.lines.min_sigma_px *= scale;
  result.lines.max_sigma_px *= scale;
  return result;
}

// One view's linearisation at one level: the energy evaluators of its dense template and of
// its correspondence lines (either may be absent).
struct ViewTemplate {
  int view = 0;
  std::shared_ptr<const RegionTemplate> region_template;        // null without a dense term
  RegionCostOptions cost;                                       // with the view's weight
  std::unique_ptr<RegionCostFunction> energy;                   // w·Σ F over every pixel
  std::shared_ptr<const CorrespondenceLines> lines;             // null without a sparse term
  double line_weight = 0.0;                                     // w_v · lines.weight
  std::unique_ptr<CorrespondenceLineCostFunction> line_energy;  // ½Σ r² over every line

  double Energy(const double* parameters) const {
    double total = 0.0;
    if (energy != nullptr) total += energy->Energy(parameters);
    if (line_energy != nullptr) total += line_energy->Energy(parameters);
    return total;
  }
};

double TotalEnergy(const std::vector<ViewTemplate>& templates, const double* parameters) {
  double total = 0.0;
  for (const ViewTemplate& t : templates) total += t.Energy(parameters);
  return total;
}

// Adds PoseDampingCost towards `linearisation_pose` when the options switch it on.
void AddDamping(const FrameProblemOptions& options, const std::vector<ViewTemplate>& templates,
                const Eigen::Isometry3d& linearisation_pose, double* parameters,
                ceres::Problem* problem) {
  if (options.damping_translation_mm == 0.0 && options.damping_rotation_deg == 0.0) return;
  double residual_count = 0.0;
  for (const ViewTemplate& t : templates) {
    if (t.energy != nullptr) residual_count += t.energy->num_residuals();
    if (t.line_energy != nullptr) residual_count += t.line_energy->num_residuals();
  }
  const double root = std::sqrt(residual_count);
  const double translation_scale =
      options.damping_translation_mm > 0.0 ? root / options.damping_translation_mm : 0.0;
  const double rotation_scale = options.damping_rotation_deg > 0.0
                                    ? root / (options.damping_rotation_deg * kPi / 180.0)
                                    : 0.0;
  problem->AddResidualBlock(
      new PoseDampingCost(linearisation_pose, translation_scale, rotation_scale), nullptr,
      parameters);
}

// The loss of one edge line's whitened residual: `kind` with threshold `scale`, owned by the
// caller.
ceres::LossFunction* EdgeLoss(EdgeRobustLoss kind, double scale) {
  switch (kind) {
    case EdgeRobustLoss::kHuber:
      return new ceres::HuberLoss(scale);
    case EdgeRobustLoss::kCauchy:
      return new ceres::CauchyLoss(scale);
    case EdgeRobustLoss::kTukey:
      return new ceres::TukeyLoss(scale);
  }
  return nullptr;
}

// The Gaussian pose posterior of an edge solve at its optimum `pose` (DESIGN.md "Temporal
// window"), in the tangent of Se3Manifold; null when singular. Its information is
//   H = Σ_v c_v · Σ_{i ∈ v} ρ'(r_i²) J_iᵀJ_i,   c_v = min(1, k / √S_v),   S_v = Σ_{i ∈ v} ρ(r_i²),
// divided by the a posteriori variance factor Σ_v h(S_v)/(n − 6) when that exceeds 1 (h the
// Huber ρ of threshold k on S_v; k = kPosteriorViewScale). Each line counts with the weight ρ'
// the solve's robust loss gave it, and each view is discounted as a whole: the lines of a
// contour share much of their error (local appearance, facets, the silhouette's sampling), so
// a view's information grows like √n_v, not n_v. So discounted, the predicted standard
// deviation matches the per-frame errors (WindowSequenceTest.EdgePosteriorPredictsThe-
// PerFrameErrors: 0.023 mm predicted, 0.022–0.024 mm measured); counting the lines as
// independent predicts about half, and the window then smooths too little.
// That discount was calibrated with lines ~3.5 px apart along the contour. Denser lines share
// even more of their error (the blur and the bilinear samples span neighbouring pixels), so
// each line enters with the weight w_i = min(1, spacing / kPosteriorLineSpacingPx) in H, S_v
// and n (n = Σ w_i): lines one pixel apart then count as the lines 3.5 px apart they refine,
// and the prediction stays calibrated (0.0230 mm / 0.0363° predicted, 0.0197 mm / 0.0421°
// measured; unweighted 0.0168 mm / 0.0265°).
constexpr double kPosteriorViewScale = 3.0;
constexpr double kPosteriorLineSpacingPx = 3.5;

// (EdgePosterior, continued.) The lines' weights are those of the solve's loss (`loss_kind` at
// `loss_scale`). For a body of revolution (`symmetry`, O_o) no line observes the turn about its
// axis, so H is singular along its twist. Neither the solves nor the window move along it
// (AxisLockedSe3Manifold); H gets the mean of its eigenvalues along it, so that it can be
// inverted, which changes nothing in the directions the window estimates.
std::shared_ptr<const PoseGaussian> EdgePosterior(
    const std::vector<std::pair<int, std::shared_ptr<const CorrespondenceLines>>>& measured,
    const std::vector<FrameView>& views, EdgeRobustLoss loss_kind, double loss_scale,
    const Eigen::Isometry3d& pose, const std::optional<RotationalSymmetry>& symmetry) {
  PoseParameters x = ToPoseParameters(pose);
  ceres::Problem problem;
  std::vector<int> view_of_row;  // index into `measured`
  std::vector<double> line_weight(measured.size(), 1.0);
  for (size_t m = 0; m < measured.size(); ++m) {
    const auto& [v, lines] = measured[m];
    if (lines->line_spacing_px > 0.0) {
      line_weight[m] = std::min(1.0, lines->line_spacing_px / kPosteriorLineSpacingPx);
    }
    problem.AddResidualBlock(new CorrespondenceLineCostFunction(
                                 *views[v].camera, views[v].cam_from_rig, lines, views[v].weight),
                             nullptr, x.data());
    view_of_row.insert(view_of_row.end(), lines->lines.size(), static_cast<int>(m));
  }
  problem.SetManifold(x.data(), new Se3Manifold());
  double cost = 0.0;
  std::vector<double> residuals;
  ceres::CRSMatrix jacobian;
  if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, &residuals, nullptr, &jacobian)) {
    return nullptr;
  }
  if (jacobian.num_cols != kPoseTangentSize || jacobian.num_rows <= kPoseTangentSize ||
      static_cast<int>(view_of_row.size()) != jacobian.num_rows) {
    return nullptr;
  }
  const std::unique_ptr<ceres::LossFunction> loss(EdgeLoss(loss_kind, loss_scale));
  std::vector<Matrix6d> view_information(measured.size(), Matrix6d::Zero());
  std::vector<double> view_cost(measured.size(), 0.0);  // S_v
  double num_rows = 0.0;                                // Σ_i w_i
  for (int row = 0; row < jacobian.num_rows; ++row) {
    Vector6d j = Vector6d::Zero();
    for (int k = jacobian.rows[row]; k < jacobian.rows[row + 1]; ++k) {
      j[jacobian.cols[k]] = jacobian.values[k];
    }
    double rho[3];
    loss->Evaluate(residuals[row] * residuals[row], rho);
    const double w = line_weight[view_of_row[row]];
    num_rows += w;
    view_information[view_of_row[row]] += w * rho[1] * j * j.transpose();
    view_cost[view_of_row[row]] += w * rho[0];
  }
  constexpr double k = kPosteriorViewScale;
  Matrix6d information = Matrix6d::Zero();
  double discounted_cost = 0.0;
  for (size_t m = 0; m < measured.size(); ++m) {
    const double s = view_cost[m];
    information += (s > k * k ? k / std::sqrt(s) : 1.0) * view_information[m];
    discounted_cost += s > k * k ? 2.0 * k * std::sqrt(s) - k * k : s;
  }
  if (!(num_rows > kPoseTangentSize)) return nullptr;
  const double variance_factor = discounted_cost / (num_rows - kPoseTangentSize);
  if (variance_factor > 1.0) information /= variance_factor;
  if (symmetry.has_value()) {
    const Vector6d twist = symmetry->Twist().normalized();
    information += information.trace() / kPoseTangentSize * twist * twist.transpose();
  }
  auto gaussian = std::make_shared<PoseGaussian>();
  gaussian->mean = pose;
  if (!SqrtInformation(information, &gaussian->sqrt_information)) return nullptr;
  return gaussian;
}

// One solve of the frame: the coarse levels L−1..1 `coarse_rounds` times each, then `rounds`
// rounds at level 0 (see the header).
struct Step {
  int level;
  int round;  // −1 on coarse levels
};

std::vector<Step> CoarseToFineSteps(const FrameProblemOptions& options) {
  std::vector<Step> steps;
  for (int level = options.pyramid_levels - 1; level >= 1; --level) {
    for (int round = 0; round < options.coarse_rounds; ++round) steps.push_back({level, -1});
  }
  for (int round = 0; round < options.rounds; ++round) steps.push_back({0, round});
  return steps;
}

// Linearises view `v` at `linearisation_pose` for one step: renders its silhouette and builds
// the dense template and/or the correspondence lines (options.energy) with their cost
// functions; at level 0 it records their sizes in `view_summary`. Empty when the view has no
// term at this pose (not visible, or weight 0). Reads only its own view: the views of a step
// are linearised concurrently (Solve), and their terms added to the problem in view order
// (AddViewTerms), so the result does not depend on the scheduling.
std::optional<ViewTemplate> LineariseView(const RayCaster& caster,
                                          const SparseViewpointModel* viewpoint_model,
                                          const FrameProblemOptions& options, const FrameView& view,
                                          int v, int level, const LevelOptions& level_options,
                                          const Eigen::Isometry3d& linearisation_pose,
                                          FrameViewSummary* view_summary) {
  if (view.weight == 0.0) return std::nullopt;
  const Eigen::Isometry3d cam_from_template =
      view.cam_from_rig * linearisation_pose * caster.mesh().objcentre_from_template();
  const ColorModel& color_model = level == 0 && view.refine_color_model != nullptr
                                      ? *view.refine_color_model
                                      : *view.color_model;
  ViewTemplate t;
  t.view = v;
  // The lines along the viewpoint model's points need no render (validated: energy sparse).
  Silhouette silhouette;
  std::vector<ProjectedContourPoint> model_points;
  if (options.lines_from_viewpoint_model) {
    model_points = viewpoint_model->Project(viewpoint_model->Nearest(cam_from_template),
                                            *view.camera, cam_from_template);
  } else {
    // The template reads the render's model points on its stride only.
    silhouette = RenderSilhouette(caster, *view.camera, cam_from_template,
                                  level_options.region.contour, level_options.region.stride_px);
  }
  if (options.energy != RegionEnergy::kSparse) {
    StatusOr<RegionTemplate> region_template =
        BuildRegionTemplate(caster, *view.camera, view.cam_from_rig, linearisation_pose,
                            *view.image, color_model, silhouette, level_options.region);
    // Options were validated and the view checked by Solve: a failure here is a bug.
    BCOT_CHECK(region_template.ok());
    if (!region_template->pixels.empty()) {
      t.region_template =
          std::make_shared<const RegionTemplate>(std::move(region_template).value());
      t.cost = level_options.cost;
      t.cost.view_weight = view.weight;
      const int pixel_count = static_cast<int>(t.region_template->pixels.size());
      t.energy = std::make_unique<RegionCostFunction>(*view.camera, view.cam_from_rig,
                                                      t.region_template, 0, pixel_count, t.cost);
      if (level == 0) view_summary->pixels = pixel_count;
    }
  }
  if (options.energy != RegionEnergy::kDense) {
    StatusOr<CorrespondenceLines> lines =
        options.lines_from_viewpoint_model
            ? BuildCorrespondenceLines(caster, *view.camera, view.cam_from_rig, linearisation_pose,
                                       *view.image, color_model, model_points, level_options.lines)
            : BuildCorrespondenceLines(caster, *view.camera, view.cam_from_rig, linearisation_pose,
                                       *view.image, color_model, silhouette, level_options.lines);
    BCOT_CHECK(lines.ok());
    if (!lines->lines.empty()) {
      t.lines = std::make_shared<const CorrespondenceLines>(std::move(lines).value());
      t.line_weight = view.weight * level_options.lines.weight;
      t.line_energy = std::make_unique<CorrespondenceLineCostFunction>(
          *view.camera, view.cam_from_rig, t.lines, t.line_weight);
      if (level == 0) view_summary->lines = static_cast<int>(t.lines->lines.size());
    }
  }
  if (t.energy == nullptr && t.line_energy == nullptr) return std::nullopt;
  return t;
}

// LineariseView of every view, concurrently; `view_summaries` (one per view) receive what it
// records at level 0.
std::vector<std::optional<ViewTemplate>> LineariseViews(
    const RayCaster& caster, const SparseViewpointModel* viewpoint_model,
    const FrameProblemOptions& options, const std::vector<FrameView>& views, int level,
    const LevelOptions& level_options, const Eigen::Isometry3d& linearisation_pose,
    std::vector<FrameViewSummary>* view_summaries) {
  std::vector<std::optional<ViewTemplate>> linearised(views.size());
  tbb::parallel_for(size_t{0}, views.size(), [&](size_t v) {
    linearised[v] = LineariseView(caster, viewpoint_model, options, views[v], static_cast<int>(v),
                                  level, level_options, linearisation_pose, &(*view_summaries)[v]);
  });
  return linearised;
}

// The energy of the linearised views at `parameters` per residual term (band pixels and
// lines), which compares poses whose bands hold different numbers of pixels; +∞ without terms.
double EnergyPerTerm(const std::vector<std::optional<ViewTemplate>>& linearised,
                     const double* parameters) {
  double energy = 0.0;
  size_t terms = 0;
  for (const std::optional<ViewTemplate>& t : linearised) {
    if (!t.has_value()) continue;
    energy += t->Energy(parameters);
    if (t->region_template != nullptr) terms += t->region_template->pixels.size();
    if (t->lines != nullptr) terms += t->lines->lines.size();
  }
  return terms > 0 ? energy / static_cast<double>(terms) : std::numeric_limits<double>::infinity();
}

// The largest image distance (px) between the projections of a corner of the mesh's bounding
// box at pose `a` and at pose `b`, over the corners and views; +∞ when a corner lies behind a
// camera at either pose.
double MaxCornerShiftPx(const Mesh& mesh, const std::vector<FrameView>& views,
                        const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d objcentre_from_template = mesh.objcentre_from_template();
  double shift = 0.0;
  for (const FrameView& view : views) {
    const Eigen::Isometry3d cam_from_template_a = view.cam_from_rig * a * objcentre_from_template;
    const Eigen::Isometry3d cam_from_template_b = view.cam_from_rig * b * objcentre_from_template;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d point((corner & 1) ? mesh.bbox_max().x() : mesh.bbox_min().x(),
                                  (corner & 2) ? mesh.bbox_max().y() : mesh.bbox_min().y(),
                                  (corner & 4) ? mesh.bbox_max().z() : mesh.bbox_min().z());
      const Eigen::Vector3d in_cam_a = cam_from_template_a * point;
      const Eigen::Vector3d in_cam_b = cam_from_template_b * point;
      if (in_cam_a.z() <= 0.0 || in_cam_b.z() <= 0.0) {
        return std::numeric_limits<double>::infinity();
      }
      shift =
          std::max(shift, (view.camera->Project(in_cam_a) - view.camera->Project(in_cam_b)).norm());
    }
  }
  return shift;
}

// Adds the residual blocks of a linearised view on `parameters` to `problem`.
void AddViewTerms(const ViewTemplate& t, const FrameView& view, double* parameters,
                  ceres::Problem* problem) {
  if (t.region_template != nullptr) {
    AddRegionResidualBlocks(*view.camera, view.cam_from_rig, t.region_template, t.cost, parameters,
                            problem);
  }
  if (t.lines != nullptr) {
    problem->AddResidualBlock(
        new CorrespondenceLineCostFunction(*view.camera, view.cam_from_rig, t.lines, t.line_weight),
        nullptr, parameters);
  }
}

// The energy of every view and their total at `parameters` (the end of a round).
void RecordEnergies(const std::vector<ViewTemplate>& templates, const double* parameters,
                    FrameSummary* summary) {
  summary->final_energy = 0.0;
  for (const ViewTemplate& t : templates) {
    const double energy = t.Energy(parameters);
    summary->views[t.view].energy = energy;
    summary->final_energy += energy;
  }
}

// The views' linearisations of a round, for the temporal window.
std::vector<ViewLinearisation> LinearisationsOf(const std::vector<FrameView>& views,
                                                const std::vector<ViewTemplate>& templates) {
  std::vector<ViewLinearisation> linearisations;
  for (const ViewTemplate& t : templates) {
    linearisations.push_back({*views[t.view].camera, views[t.view].cam_from_rig, t.region_template,
                              t.cost, t.lines, t.line_weight, nullptr});
  }
  return linearisations;
}

// Records how far a round moved the pose; true when both motions are below the round
// tolerances (the frame has converged).
bool RecordRoundMotion(const FrameProblemOptions& options, const Eigen::Isometry3d& round_start,
                       const Eigen::Isometry3d& round_end, FrameSummary* summary) {
  summary->last_round_rotation_deg = RotationDistanceDeg(round_start.linear(), round_end.linear());
  summary->last_round_translation_mm = (round_end.translation() - round_start.translation()).norm();
  return summary->last_round_rotation_deg < options.round_tolerance_deg &&
         summary->last_round_translation_mm < options.round_tolerance_mm;
}

}  // namespace

FrameProblem::FrameProblem(const RayCaster& caster, const FrameProblemOptions& options,
                           const std::optional<RotationalSymmetry>& symmetry,
                           const SparseViewpointModel* viewpoint_model)
    : caster_(caster), viewpoint_model_(viewpoint_model), options_(options) {
  BCOT_CHECK(viewpoint_model_ != nullptr || !options_.lines_from_viewpoint_model);
  if (symmetry.has_value()) {
    symmetry_in_objcentre_ = symmetry->Transformed(caster_.mesh().objcentre_from_template());
  }
  const Status status = options_.Validate();
  BCOT_CHECK(status.ok());
  BCOT_CHECK(options_.edge.lines.response.IsResolved());
  if (options_.edge.enabled && options_.edge.lines.crease_contours) {
    creases_ = FindCreases(caster_.mesh(), options_.edge.lines.crease_min_angle_deg);
  }
}

FrameSummary FrameProblem::Solve(const std::vector<FrameView>& views,
                                 Eigen::Isometry3d* rig_from_objcentre,
                                 std::vector<ViewLinearisation>* linearisations) const {
  BCOT_CHECK(rig_from_objcentre != nullptr);
  for (const FrameView& view : views) {
    BCOT_CHECK(view.camera != nullptr && view.image != nullptr && view.color_model != nullptr);
    BCOT_CHECK(view.image->cols == view.camera->width && view.image->rows == view.camera->height);
    BCOT_CHECK(view.weight >= 0.0 && std::isfinite(view.weight));
  }
  FrameSummary summary;
  summary.views.resize(views.size());
  const Eigen::Isometry3d start = *rig_from_objcentre;
  PoseParameters x = ToPoseParameters(start);
  if (linearisations != nullptr) linearisations->clear();
  auto fail = [&](FrameTermination termination, std::string message) {
    if (linearisations != nullptr) linearisations->clear();
    summary.termination = termination;
    summary.message = std::move(message);
    *rig_from_objcentre = start;
    return summary;
  };

  summary.termination = FrameTermination::kMaxRounds;
  for (const Step& step : CoarseToFineSteps(options_)) {
    const std::string where = step.round < 0 ? fmt::format("level {}", step.level)
                                             : fmt::format("round {}", step.round + 1);
    const LevelOptions level_options = OptionsAtLevel(options_, step.level);
    Eigen::Isometry3d linearisation_pose = FromPoseParameters(x.data());
    std::vector<std::optional<ViewTemplate>> linearised =
        LineariseViews(caster_, viewpoint_model_, options_, views, step.level, level_options,
                       linearisation_pose, &summary.views);
    // Every coarse level has run before round 1 (a failed one ends the solve).
    if (step.round == 0 && options_.pyramid_levels > 1 && options_.coarse_check &&
        MaxCornerShiftPx(caster_.mesh(), views, start, linearisation_pose) >=
            options_.coarse_check_min_shift_px) {
      // The coarse check (frame_problem.h): the rounds start where the level-0 energy is lower.
      summary.coarse_checked = true;
      std::vector<FrameViewSummary> start_summaries(views.size());
      std::vector<std::optional<ViewTemplate>> at_start =
          LineariseViews(caster_, viewpoint_model_, options_, views, step.level, level_options,
                         start, &start_summaries);
      const PoseParameters start_x = ToPoseParameters(start);
      if (EnergyPerTerm(at_start, start_x.data()) < EnergyPerTerm(linearised, x.data())) {
        x = start_x;
        linearisation_pose = start;
        linearised = std::move(at_start);
        summary.views = std::move(start_summaries);
        summary.coarse_rejected = true;
      }
    }
    std::vector<ViewTemplate> templates;
    ceres::Problem problem;
    for (size_t v = 0; v < views.size(); ++v) {
      if (!linearised[v].has_value()) continue;
      AddViewTerms(*linearised[v], views[v], x.data(), &problem);
      templates.push_back(std::move(*linearised[v]));
    }
    if (templates.empty()) {
      return fail(FrameTermination::kNotVisible, where + ": the object is outside every view");
    }
    if (step.round == 0) summary.initial_energy = TotalEnergy(templates, x.data());
    AddDamping(options_, templates, linearisation_pose, x.data(), &problem);
    problem.SetManifold(x.data(), NewPoseManifold(symmetry_in_objcentre_).release());

    const ceres::Solver::Summary ceres_summary =
        SolvePose(options_.iterations, options_.num_threads, &problem);
    summary.iterations += static_cast<int>(ceres_summary.iterations.size()) - 1;
    if (!ceres_summary.IsSolutionUsable()) {
      return fail(FrameTermination::kSolverFailure, where + ": " + ceres_summary.message);
    }
    if (step.round < 0) continue;

    RecordEnergies(templates, x.data(), &summary);
    if (!std::isfinite(summary.final_energy)) {
      return fail(FrameTermination::kSolverFailure, where + ": the energy is not finite");
    }
    summary.rounds = step.round + 1;
    if (linearisations != nullptr) *linearisations = LinearisationsOf(views, templates);
    if (RecordRoundMotion(options_, linearisation_pose, FromPoseParameters(x.data()), &summary)) {
      summary.termination = FrameTermination::kConverged;
      break;
    }
  }
  if (options_.edge.enabled) {
    const FrameSummary region_summary = summary;
    const PoseParameters region_x = x;
    std::shared_ptr<const PoseGaussian> posterior;
    if (!RefineEdges(views, x.data(), &summary, linearisations != nullptr ? &posterior : nullptr)) {
      // Too few edge lines or a failed solve: keep the region result.
      x = region_x;
      summary = region_summary;
    } else if (linearisations != nullptr && posterior != nullptr) {
      for (ViewLinearisation& linearisation : *linearisations) {
        linearisation.edge_posterior = posterior;
      }
    }
  }
  *rig_from_objcentre = FromPoseParameters(x.data());
  return summary;
}

bool FrameProblem::SolveEdges(const std::vector<FrameView>& views,
                              Eigen::Isometry3d* rig_from_objcentre) const {
  BCOT_CHECK(rig_from_objcentre != nullptr);
  for (const FrameView& view : views) {
    BCOT_CHECK(view.camera != nullptr && view.image != nullptr);
    BCOT_CHECK(view.image->cols == view.camera->width && view.image->rows == view.camera->height);
    BCOT_CHECK(view.weight >= 0.0 && std::isfinite(view.weight));
  }
  PoseParameters x = ToPoseParameters(*rig_from_objcentre);
  FrameSummary summary;
  summary.views.resize(views.size());
  if (!RefineEdges(views, x.data(), &summary, nullptr)) return false;
  *rig_from_objcentre = FromPoseParameters(x.data());
  return true;
}

bool FrameProblem::RefineEdges(const std::vector<FrameView>& views, double* parameters,
                               FrameSummary* summary,
                               std::shared_ptr<const PoseGaussian>* posterior) const {
  if (posterior != nullptr) posterior->reset();
  const EdgeRefineOptions& edge = options_.edge;
  const Eigen::Isometry3d objcentre_from_template = caster_.mesh().objcentre_from_template();
  // Model points are read from the contour only: a coarse point stride saves closest hits.
  constexpr int kPointStridePx = 64;
  const int total_rounds = edge.rounds + edge.redescending_rounds;
  for (int round = 0; round < total_rounds; ++round) {
    const Eigen::Isometry3d linearisation_pose = FromPoseParameters(parameters);
    // The views' lines are measured concurrently, then added in view order.
    std::vector<std::shared_ptr<const CorrespondenceLines>> view_lines(views.size());
    tbb::parallel_for(size_t{0}, views.size(), [&](size_t v) {
      const FrameView& view = views[v];
      if (view.weight == 0.0) return;
      const Silhouette silhouette = RenderSilhouette(
          caster_, *view.camera, view.cam_from_rig * linearisation_pose * objcentre_from_template,
          options_.region.contour, kPointStridePx);
      // The correction for subsampled chroma costs about nine times a line's own fit
      // (scripts/bench_edge_fit.sh); the earlier rounds only bring the contour within a fraction
      // of a pixel, the last one's lines place the pose, so only they are corrected
      // (docs/notes/issue12_jpeg_chroma.md).
      // The restoration (EdgeRefineOptions::chroma_restoration) likewise serves the last round.
      const EdgeImage measured_on =
          round + 1 == total_rounds ? EdgeImageOf(*view.image, view.chroma, edge.chroma_restoration,
                                                  silhouette, edge.lines)
                                    : EdgeImage{*view.image, ChromaSampling::Full()};
      StatusOr<CorrespondenceLines> lines = BuildEdgeLines(
          caster_, *view.camera, view.cam_from_rig, linearisation_pose, measured_on.image,
          silhouette, edge.lines, measured_on.sampling, &creases_);
      BCOT_CHECK(lines.ok());
      view_lines[v] = std::make_shared<const CorrespondenceLines>(std::move(lines).value());
    });
    std::vector<std::pair<int, std::shared_ptr<const CorrespondenceLines>>> measured;
    int total_lines = 0;
    for (size_t v = 0; v < views.size(); ++v) {
      if (view_lines[v] == nullptr || view_lines[v]->lines.empty()) continue;
      total_lines += static_cast<int>(view_lines[v]->lines.size());
      measured.emplace_back(static_cast<int>(v), view_lines[v]);
    }
    if (total_lines < edge.min_lines) return false;
    const bool redescending = round >= edge.rounds;
    const EdgeRobustLoss loss_kind = redescending ? EdgeRobustLoss::kTukey : edge.robust_loss;
    const double loss_scale = redescending ? edge.redescending_scale : edge.robust_scale;
    ceres::Problem problem;
    for (const auto& [v, shared] : measured) {
      const FrameView& view = views[v];
      for (int i = 0; i < static_cast<int>(shared->lines.size()); ++i) {
        problem.AddResidualBlock(new CorrespondenceLineCostFunction(*view.camera, view.cam_from_rig,
                                                                    shared, view.weight, i, 1),
                                 EdgeLoss(loss_kind, loss_scale), parameters);
      }
    }
    problem.SetManifold(parameters, NewPoseManifold(symmetry_in_objcentre_).release());
    const ceres::Solver::Summary ceres_summary =
        SolvePose(edge.iterations, options_.num_threads, &problem);
    summary->iterations += static_cast<int>(ceres_summary.iterations.size()) - 1;
    if (!ceres_summary.IsSolutionUsable()) return false;
    for (FrameViewSummary& view_summary : summary->views) view_summary.edge_lines = 0;
    for (const auto& [v, lines] : measured) {
      summary->views[v].edge_lines = static_cast<int>(lines->lines.size());
    }
    const Eigen::Isometry3d round_end = FromPoseParameters(parameters);
    if (posterior != nullptr) {
      *posterior =
          EdgePosterior(measured, views, loss_kind, loss_scale, round_end, symmetry_in_objcentre_);
    }
    const double moved_deg = RotationDistanceDeg(linearisation_pose.linear(), round_end.linear());
    const double moved_mm = (round_end.translation() - linearisation_pose.translation()).norm();
    if (moved_deg < options_.round_tolerance_deg && moved_mm < options_.round_tolerance_mm) {
      // Converged under this loss: on to the redescending rounds, if any are still to come.
      if (round >= edge.rounds || edge.redescending_rounds == 0) break;
      round = edge.rounds - 1;
    }
  }
  return true;
}

}  // namespace bcot

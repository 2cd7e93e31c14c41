// Where the edge stage's measurement puts the image edge relative to the true contour (issue
// 12), run by scripts/bench_edge_bias.sh; not a test.
//
// For a sequence with ground truth (`bcot synth` or scripts/pbr_synth.sh), per camera and frame
// the silhouette's edge lines of the edge stage (BuildEdgeLines, bcot/optim/edge_lines.h, with
// the config's `edge:` options but without the inner contours' lines, occlusion and crease,
// which occlusion_edge_probe and the crease note measure, and each camera's chroma sampling as
// edge.chroma_sampling resolves it, read as the stage's last round reads them: with
// edge.chroma_restoration on, on the frame restored around the object, EdgeImageOf) are measured
// at the ground-truth pose, whose contour is the true silhouette
// (pbr_gt_check proves it to a few hundredths of a pixel for the Blender renders). A line's μ is
// then the measurement's own error along the outward normal (+ = the image edge is found
// outside the true contour). Lines are binned by the direction of their normal in the image:
// up (n_y < −0.7; the upper rim), down (n_y > 0.7), left, right. A bias of the pose comes from
// a difference between opposite bins (a shift) or from all bins together (a scale, i.e. depth).
//
// Usage: edge_bias_probe --sequence DIR [--config FILE] [--set key=value]... [--frames N]
//                        [--dump FILE] [--dump-fits FILE] [--blur-exposure E] [--coverage-mask]
// --dump writes one line per measured edge line: camera, frame, bin, centre, normal, μ, σ, then
// the linear RGB profile (window_px/step_px samples each side, R G B per sample).
// --blur-exposure E (with --dump; frames 1 .. N−2): each dump line ends with "BLUR" and the
// true contour's crossings of the line (px along the outward normal, nan when none) at 8 times
// spread evenly over an exposure of E frames centred on the frame: what a motion-blurred image
// averages (CamFromTemplateOverExposure, ContourCrossingsOverExposure).
// --dump-fits writes one line per measured edge line: camera, frame, bin, then the profile fit's
// μ, σ_μ (unfloored), blur width w (px) and step b (EdgeFit; FitEdgeAcross again on the line).
// --coverage-mask measures on gt/mask/<camera>/NNNNNN.png instead of the images (written by
// scripts/pbr_synth.sh: Blender's anti-aliased object coverage, 16 bit), mapped to a grey object
// on a grey background and read as linear: what the geometry, the pixel conventions and the fit
// alone make of the offsets, with no light, material or noise.
// --at ANN measures at an annotation's poses instead of the ground truth (see --help).
// --attribute adds what those lines do to the pose, to first order: per frame, one Gauss-Newton
// step of the edge stage's problem (all cameras' lines, Cauchy weights at edge.robust_scale)
// from the true pose, δ = −H⁻¹ Σ_i w_i J_iᵀ r_i, is split into the parts of each camera's rims
// (the sums over its lines of one bin). Each part moves the object's bounding-box centre; the
// table gives that move in every camera's frame (mm, + = along the camera's x / y / z, as
// pbr_errors' bias: y + = down), averaged over frames, and the parts' total. A second table
// gives each part's rotation about the first camera's axes (deg, as pbr_errors --rotation). So
// it tells which rims of which camera make a bias of the annotation.
// --solve-out DIR runs the whole edge stage instead (FrameProblem::SolveEdges: its Cauchy and
// Tukey rounds) on every frame, from the true pose or --at's, and writes the poses it ends at
// to DIR/rig_from_object.txt for pbr_errors: where the stage's fixed point lies, with no region
// stage, tracking or window (docs/notes/issue12_redescending_round.md).
// Prints per camera: lines measured / candidates, and per bin count, mean μ and its standard
// error (px); then the quantiles of μ per bin over all cameras.
#include <ceres/crs_matrix.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/annotate/annotator.h"
#include "bcot/core/annotation_poses.h"
#include "bcot/core/image_io.h"
#include "bcot/core/linear_rgb.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/core/sequence.h"
#include "bcot/optim/correspondence_line_cost.h"
#include "bcot/optim/edge_lines.h"
#include "bcot/optim/frame_problem.h"
#include "bcot/optim/response_estimation.h"
#include "bcot/optim/se3_manifold.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "ground_truth_sequence.h"

namespace {

constexpr std::array<const char*, 4> kBins = {"up", "down", "left", "right"};

int BinOf(const Eigen::Vector2d& normal) {
  if (normal.y() < -0.7) return 0;
  if (normal.y() > 0.7) return 1;
  return normal.x() < 0 ? 2 : 3;
}

struct Accumulator {
  int count = 0;
  double sum = 0.0, sum_squares = 0.0;
  std::vector<double> values;
  void Add(double value) {
    ++count;
    sum += value;
    sum_squares += value * value;
    values.push_back(value);
  }
  double Quantile(double q) const {
    if (values.empty()) return 0.0;
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    return sorted[static_cast<size_t>(q * (sorted.size() - 1))];
  }
  double Mean() const { return count > 0 ? sum / count : 0.0; }
  double StandardError() const {
    if (count < 2) return 0.0;
    const double variance = (sum_squares - count * Mean() * Mean()) / (count - 1);
    return std::sqrt(std::max(0.0, variance) / count);
  }
};

// The coverage c in [0, 1] of gt/mask/<camera>/NNNNNN.png as the 8-bit grey image 50 + 150·c:
// an object of linear level 0.78 on a background of 0.2, both clear of edge.clip_level.
bcot::StatusOr<cv::Mat3b> CoverageAsImage(const std::string& sequence_dir,
                                          const std::string& camera, int frame) {
  BCOT_ASSIGN_OR_RETURN(const cv::Mat mask,
                        bcot::bench::ReadCoverageMask(sequence_dir, camera, frame));
  cv::Mat grey;
  mask.convertTo(grey, CV_8U, 150.0 / 65535.0, 50.0);
  cv::Mat3b image;
  cv::cvtColor(grey, image, cv::COLOR_GRAY2BGR);
  return image;
}

int Fail(const std::string& message) {
  std::fprintf(stderr, "edge_bias_probe: %s\n", message.c_str());
  return 1;
}

// Where the probe's images come from: the sequence's frames, or under --coverage-mask its
// coverage masks drawn as images (CoverageAsImage).
struct ProbeImages {
  const bcot::Sequence& sequence;
  std::string sequence_dir;
  bool coverage_mask = false;

  // The image of camera `v` (rig index) in frame `f`.
  bcot::StatusOr<cv::Mat3b> Read(int v, int f) const {
    return coverage_mask
               ? CoverageAsImage(sequence_dir, sequence.rig[v].camera.name, f)
               : bcot::ReadCameraImage(sequence.image_paths[v][f], sequence.rig[v].camera);
  }
};

// The views of frame `f`, their images read from `source` into `images` (which the views point
// into), each camera's chroma sampling from `chroma`.
bcot::Status ReadFrameViews(const ProbeImages& source, int f,
                            const std::vector<bcot::ChromaSampling>& chroma,
                            std::vector<cv::Mat3b>* images, std::vector<bcot::FrameView>* views) {
  const bcot::Sequence& sequence = source.sequence;
  images->clear();
  for (int v = 0; v < sequence.rig.size(); ++v) {
    bcot::StatusOr<cv::Mat3b> image = source.Read(v, f);
    if (!image.ok()) return image.status();
    images->push_back(*image);
  }
  views->clear();
  for (int v = 0; v < sequence.rig.size(); ++v) {
    bcot::FrameView view;
    view.camera = &sequence.rig[v].camera;
    view.cam_from_rig = sequence.rig[v].cam_from_rig;
    view.image = &(*images)[v];
    view.chroma = chroma[v];
    views->push_back(view);
  }
  return bcot::Status::Ok();
}

constexpr int kBlurSubframes = 8;
using ExposurePoses = std::array<Eigen::Isometry3d, kBlurSubframes>;

// cam_from_template of the true pose at kBlurSubframes times spread evenly over an exposure of
// `exposure` frames centred on frame f (0 < f < N − 1). Over the exposure the object turns at
// the central angular velocity of frames f − 1 .. f + 1 about its centre, which follows the
// parabola through their centres.
ExposurePoses CamFromTemplateOverExposure(const Eigen::Isometry3d& cam_from_rig,
                                          const bcot::bench::GroundTruthSequence& truth, int f,
                                          double exposure) {
  const Eigen::Isometry3d before = truth.RigFromObjcentre(f - 1);
  const Eigen::Isometry3d now = truth.RigFromObjcentre(f);
  const Eigen::Isometry3d after = truth.RigFromObjcentre(f + 1);
  const Eigen::Vector3d spin = 0.5 * bcot::LogSO3(after.linear() * before.linear().transpose());
  const Eigen::Vector3d velocity = 0.5 * (after.translation() - before.translation());
  const Eigen::Vector3d acceleration =
      after.translation() - 2.0 * now.translation() + before.translation();
  ExposurePoses poses;
  for (int j = 0; j < kBlurSubframes; ++j) {
    const double tau = exposure * ((j + 0.5) / kBlurSubframes - 0.5);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = bcot::ExpSO3(tau * spin) * now.linear();
    pose.translation() = now.translation() + tau * velocity + 0.5 * tau * tau * acceleration;
    poses[j] = cam_from_rig * pose * truth.mesh.objcentre_from_template();
  }
  return poses;
}

// The contour's crossing (inside → outside) of a line nearest to its centre, px along the
// outward normal, NaN when none lies within ±6 px: `inside(t)` sampled every 0.25 px, then
// bisected.
template <typename Inside>
double NearestCrossing(const Inside& inside) {
  double nearest = std::numeric_limits<double>::quiet_NaN();
  bool was_inside = inside(-6.0);
  for (double t = -5.75; t <= 6.0 + 1e-9; t += 0.25) {
    const bool is_inside = inside(t);
    if (was_inside && !is_inside) {
      double lo = t - 0.25, hi = t;
      for (int b = 0; b < 7; ++b) {
        const double mid = 0.5 * (lo + hi);
        (inside(mid) ? lo : hi) = mid;
      }
      const double crossing = 0.5 * (lo + hi);
      if (!(std::abs(crossing) >= std::abs(nearest))) nearest = crossing;
    }
    was_inside = is_inside;
  }
  return nearest;
}

// The true contour's crossings of a line (centre, outward normal) at the exposure's times, by
// ray casting.
std::array<double, kBlurSubframes> ContourCrossingsOverExposure(const bcot::RayCaster& caster,
                                                                const bcot::Camera& camera,
                                                                const ExposurePoses& poses,
                                                                const Eigen::Vector2d& centre,
                                                                const Eigen::Vector2d& normal) {
  std::array<double, kBlurSubframes> crossings{};
  for (int j = 0; j < kBlurSubframes; ++j) {
    crossings[j] = NearestCrossing([&](double t) {
      return caster.Intersect(camera, poses[j], centre + t * normal).has_value();
    });
  }
  return crossings;
}

// --attribute (see the header): the first-order pose error of each camera's rims.
void PrintAttribution(
    const bcot::bench::GroundTruthSequence& loaded,
    const std::vector<std::vector<std::shared_ptr<const bcot::CorrespondenceLines>>>& frame_lines,
    double robust_scale) {
  using namespace bcot;
  const Sequence& sequence = loaded.sequence;
  const int cameras = sequence.rig.size();
  const int groups = cameras * static_cast<int>(kBins.size());
  const Eigen::Vector3d centre =
      loaded.mesh.objcentre_from_template() * loaded.mesh.bbox_center();  // in O_o
  // sums over frames: move of the centre per group, in each camera's frame
  std::vector<std::vector<Eigen::Vector3d>> moved(
      groups, std::vector<Eigen::Vector3d>(cameras, Eigen::Vector3d::Zero()));
  // sums over frames: rotation per group (deg), about the first camera's axes
  std::vector<Eigen::Vector3d> turned(groups, Eigen::Vector3d::Zero());
  std::vector<int> group_lines(groups, 0);
  std::vector<double> group_mu(groups, 0.0);
  // The edge stage's loss (configs/annotate.yaml's, EdgeRobustLoss::kCauchy).
  const ceres::CauchyLoss loss(robust_scale);
  int solved = 0;
  for (size_t f = 0; f < frame_lines.size(); ++f) {
    const Eigen::Isometry3d truth = loaded.RigFromObjcentre(static_cast<int>(f));
    PoseParameters x = ToPoseParameters(truth);
    ceres::Problem problem;
    std::vector<int> group_of_row;
    for (int v = 0; v < cameras; ++v) {
      const std::shared_ptr<const CorrespondenceLines>& lines = frame_lines[f][v];
      if (lines == nullptr) continue;
      problem.AddResidualBlock(
          new CorrespondenceLineCostFunction(sequence.rig[v].camera, sequence.rig[v].cam_from_rig,
                                             lines, 1.0),
          nullptr, x.data());
      for (const CorrespondenceLine& line : lines->lines) {
        const int g = v * static_cast<int>(kBins.size()) + BinOf(line.normal);
        group_of_row.push_back(g);
        ++group_lines[g];
        group_mu[g] += line.mean_px;
      }
    }
    if (group_of_row.size() < 6) continue;
    problem.SetManifold(x.data(), new Se3Manifold());
    double cost = 0.0;
    std::vector<double> residuals;
    ceres::CRSMatrix jacobian;
    if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, &residuals, nullptr,
                          &jacobian)) {
      continue;
    }
    using Vector6d = Eigen::Matrix<double, 6, 1>;
    Eigen::Matrix<double, 6, 6> h = Eigen::Matrix<double, 6, 6>::Zero();
    std::vector<Vector6d> gradient(groups, Vector6d::Zero());  // Σ w J r per group
    for (int row = 0; row < jacobian.num_rows; ++row) {
      Vector6d j = Vector6d::Zero();
      for (int k = jacobian.rows[row]; k < jacobian.rows[row + 1]; ++k) {
        j[jacobian.cols[k]] = jacobian.values[k];
      }
      const double r = residuals[row];
      double rho[3];
      loss.Evaluate(r * r, rho);
      const double w = rho[1];  // the IRLS weight ρ'(r²)
      h += w * j * j.transpose();
      gradient[group_of_row[row]] += w * r * j;
    }
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(h);
    if (solver.info() != Eigen::Success) continue;
    ++solved;
    for (int g = 0; g < groups; ++g) {
      const Vector6d delta = -solver.solve(gradient[g]);  // (ρ, φ) in O_o
      const Eigen::Vector3d in_rig =
          truth.linear() * (delta.head<3>() + delta.tail<3>().cross(centre));
      for (int c = 0; c < cameras; ++c) {
        moved[g][c] += sequence.rig[c].cam_from_rig.linear() * in_rig;
      }
      turned[g] +=
          (180.0 / M_PI) * sequence.rig[0].cam_from_rig.linear() * truth.linear() * delta.tail<3>();
    }
  }
  if (solved == 0) return;
  std::printf(
      "\nfirst-order move of the bounding-box centre (mm, each camera's axes) by the rims "
      "of each camera, mean over %d frames\n",
      solved);
  std::printf("%-6s %-5s %6s %8s", "rims", "", "lines", "mean μ");
  for (int c = 0; c < cameras; ++c) {
    std::printf(" | %-5s %7s %7s %7s", sequence.rig[c].camera.name.c_str(), "x", "y", "z");
  }
  std::printf("\n");
  std::vector<Eigen::Vector3d> total(cameras, Eigen::Vector3d::Zero());
  for (int g = 0; g < groups; ++g) {
    const int v = g / static_cast<int>(kBins.size());
    std::printf("%-6s %-5s %6d %+8.3f", sequence.rig[v].camera.name.c_str(),
                kBins[g % kBins.size()], group_lines[g],
                group_lines[g] > 0 ? group_mu[g] / group_lines[g] : 0.0);
    for (int c = 0; c < cameras; ++c) {
      const Eigen::Vector3d mean = moved[g][c] / solved;
      total[c] += mean;
      std::printf(" | %-5s %+7.3f %+7.3f %+7.3f", "", mean.x(), mean.y(), mean.z());
    }
    std::printf("\n");
  }
  std::printf("%-6s %-5s %6s %8s", "total", "", "", "");
  for (int c = 0; c < cameras; ++c) {
    std::printf(" | %-5s %+7.3f %+7.3f %+7.3f", "", total[c].x(), total[c].y(), total[c].z());
  }
  std::printf("\n");
  std::printf("\nfirst-order rotation (deg, about %s's x / y / z) by the rims of each camera\n",
              sequence.rig[0].camera.name.c_str());
  Eigen::Vector3d total_turn = Eigen::Vector3d::Zero();
  for (int g = 0; g < groups; ++g) {
    const Eigen::Vector3d mean = turned[g] / solved;
    total_turn += mean;
    std::printf("%-6s %-5s %+7.3f %+7.3f %+7.3f\n",
                sequence.rig[g / static_cast<int>(kBins.size())].camera.name.c_str(),
                kBins[g % kBins.size()], mean.x(), mean.y(), mean.z());
  }
  std::printf("%-6s %-5s %+7.3f %+7.3f %+7.3f\n", "total", "", total_turn.x(), total_turn.y(),
              total_turn.z());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bcot;
  CLI::App app{"Edge-stage measurement at the ground-truth pose, binned by normal direction"};
  std::string sequence_dir, config_path;
  std::vector<std::string> overrides;
  int max_frames = 0;
  std::string dump_path;
  app.add_option("--sequence", sequence_dir, "Sequence with gt/")->required();
  app.add_option("--config", config_path, "annotate config (its edge: section is used)");
  app.add_option("--set", overrides, "Override of the config (repeatable)");
  app.add_option("--frames", max_frames, "Only the first N frames (0 = all)");
  app.add_option("--dump", dump_path, "Write every measured line's profile to this file");
  double blur_exposure = 0.0;
  app.add_option("--blur-exposure", blur_exposure,
                 "With --dump: the true contour's crossings of each line over an exposure of "
                 "this many frames (motion blur), at most 1")
      ->check(CLI::Range(0.0, 1.0));
  std::string fits_path;
  app.add_option("--dump-fits", fits_path, "Write every measured line's profile fit to this file");
  int response_frames = 0;
  app.add_option("--response-frames", response_frames,
                 "Score the response candidates (EstimateImageResponse: polarity slope and spread, "
                 "px) on every 5th of the first N frames from the true pose, then exit");
  std::vector<std::string> candidate_tables;
  app.add_option("--candidate-table", candidate_tables,
                 "With --response-frames: also score this response table (repeatable)");
  std::string at_annotation;
  app.add_option("--at", at_annotation,
                 "Measure at this annotation's poses (its rig_from_object.txt) instead of the "
                 "ground truth: μ is then the offset from that pose's contour, and --attribute "
                 "the first-order step the lines would take from there (0 at the edge stage's "
                 "fixed point)");
  double shift_px = 0.0;
  app.add_option("--shift-test", shift_px,
                 "Also measure every line with its contour point moved by ± this (px) along the "
                 "normal: a line that sees a fixed image edge moves its μ by ∓ the same")
      ->check(CLI::Range(0.0, 2.0));
  bool attribute = false;
  app.add_flag("--attribute", attribute,
               "Also the first-order pose error each camera's rims cause (see the header)");
  std::string solve_out;
  app.add_option("--solve-out", solve_out,
                 "Run the edge stage (FrameProblem::SolveEdges: its edge.rounds and "
                 "edge.redescending_rounds re-rendered solves) on every frame from the measured "
                 "poses (the truth, or --at's) and write the poses it ends at as an annotation "
                 "directory (rig_from_object.txt) for pbr_errors, then exit");
  bool coverage_mask = false;
  app.add_flag("--coverage-mask", coverage_mask,
               "Measure on gt/mask (the renderer's anti-aliased object coverage) instead of the "
               "images");
  CLI11_PARSE(app, argc, argv);

  const StatusOr<AnnotateOptions> options = ReadAnnotateOptions(config_path, overrides);
  if (!options.ok()) return Fail(options.status().message());
  StatusOr<bench::GroundTruthSequence> loaded = bench::LoadGroundTruthSequence(sequence_dir);
  if (!loaded.ok()) return Fail(loaded.status().message());
  if (!at_annotation.empty()) {
    StatusOr<std::vector<Eigen::Isometry3d>> poses = ReadAnnotationPoses(at_annotation);
    if (!poses.ok()) return Fail(poses.status().message());
    if (poses->size() != loaded->truth.size()) {
      return Fail(fmt::format("{}: {} poses for {} frames", at_annotation, poses->size(),
                              loaded->truth.size()));
    }
    loaded->truth = *std::move(poses);
  }
  const Sequence* sequence = &loaded->sequence;
  const std::vector<Eigen::Isometry3d>* gt = &loaded->truth;
  const Mesh* mesh = &loaded->mesh;
  const RayCaster caster(*mesh);
  // edge.response auto (the annotate default) is the tracker's to estimate; measured here
  // directly, the lines are decoded as sRGB unless --set edge.response=... says otherwise.
  FrameProblemOptions frame = options->tracker.frame;
  if (!frame.edge.lines.response.IsResolved()) frame.edge.lines.response = ImageResponse();
  if (coverage_mask) frame.edge.lines.response = ImageResponse::Gamma(1.0);
  EdgeLineOptions edge = frame.edge.lines;  // the silhouette's lines (header)
  edge.occlusion_contours = false;
  edge.crease_contours = false;
  const int frames =
      max_frames > 0 ? std::min(max_frames, sequence->num_frames) : sequence->num_frames;
  // Each camera's chroma sampling as the annotation resolves it (edge.chroma_sampling); the
  // coverage is full-resolution colour.
  std::vector<ChromaSampling> chroma(sequence->rig.size(), ChromaSampling::Full());
  for (int v = 0; v < sequence->rig.size() && !coverage_mask; ++v) {
    const StatusOr<ChromaSampling> resolved =
        ResolveChromaSampling(*sequence, v, options->chroma_sampling);
    if (!resolved.ok()) return Fail(resolved.status().message());
    chroma[v] = *resolved;
  }

  const ProbeImages images_of{*sequence, sequence_dir, coverage_mask};

  if (!solve_out.empty()) {
    const FrameProblem problem(caster, frame);
    std::vector<Eigen::Isometry3d> poses;
    for (int f = 0; f < frames; ++f) {
      std::vector<cv::Mat3b> images;
      std::vector<FrameView> views;
      const Status read = ReadFrameViews(images_of, f, chroma, &images, &views);
      if (!read.ok()) return Fail(read.message());
      Eigen::Isometry3d rig_from_objcentre = loaded->RigFromObjcentre(f);
      if (!problem.SolveEdges(views, &rig_from_objcentre)) {
        return Fail(fmt::format("frame {}: the edge stage failed", f));
      }
      poses.push_back(rig_from_objcentre * mesh->objcentre_from_template());
    }
    std::filesystem::create_directories(solve_out);
    const Status written = WritePoseFile(solve_out + "/rig_from_object.txt", poses);
    if (!written.ok()) return Fail(written.message());
    return 0;
  }

  if (response_frames > 0) {
    const FrameProblem problem(caster, frame);
    ResponseEstimationOptions estimation;
    for (const std::string& path : candidate_tables) {
      StatusOr<std::vector<float>> table = ReadResponseTable(path);
      if (!table.ok()) return Fail(table.status().message());
      ImageResponse response;
      response.kind = ImageResponse::Kind::kTable;
      response.table_file = path;
      response.table = *std::move(table);
      estimation.candidates.push_back(response);
    }
    for (int f = 0; f < std::min(response_frames, sequence->num_frames); f += 5) {
      std::vector<cv::Mat3b> images;
      std::vector<FrameView> views;
      const Status read = ReadFrameViews(images_of, f, chroma, &images, &views);
      if (!read.ok()) return Fail(read.message());
      const StatusOr<ResponseEstimate> estimate =
          EstimateImageResponse(problem, views, loaded->RigFromObjcentre(f), estimation);
      if (!estimate.ok()) return Fail(estimate.status().message());
      std::printf("frame %3d best %-10s |", f, estimate->response.Name().c_str());
      for (const ResponseScore& score : estimate->scores) {
        std::printf(" %s slope %+.3f±%.3f spread %.3f±%.3f (%d)", score.response.Name().c_str(),
                    score.slope_px, score.slope_standard_error_px, score.spread_px,
                    score.spread_standard_error_px, score.lines);
      }
      std::printf("\n");
    }
    return 0;
  }
  std::printf("%-6s %9s", "camera", "lines");
  for (const char* bin : kBins) std::printf(" | %-5s %5s %8s %6s", bin, "n", "mean", "se");
  std::printf(" | %8s\n", "all");
  std::array<Accumulator, 4> total{};
  std::FILE* dump = dump_path.empty() ? nullptr : std::fopen(dump_path.c_str(), "w");
  if (!dump_path.empty() && dump == nullptr) return Fail("cannot write " + dump_path);
  std::FILE* fits = fits_path.empty() ? nullptr : std::fopen(fits_path.c_str(), "w");
  if (!fits_path.empty() && fits == nullptr) return Fail("cannot write " + fits_path);
  const int half = static_cast<int>(std::floor(edge.window_px / edge.step_px + 1e-9));
  const LinearTable linear(edge.response);
  // The measured lines per frame and camera (--attribute).
  std::vector<std::vector<std::shared_ptr<const CorrespondenceLines>>> frame_lines(
      frames, std::vector<std::shared_ptr<const CorrespondenceLines>>(sequence->rig.size()));
  for (int v = 0; v < sequence->rig.size(); ++v) {
    const RigCamera& camera = sequence->rig[v];
    std::array<Accumulator, 4> bins{};
    std::array<Accumulator, 4> shift_bins{}, stable_bins{};
    int candidates = 0, measured = 0;
    for (int f = 0; f < frames; ++f) {
      const StatusOr<cv::Mat3b> image = images_of.Read(v, f);
      if (!image.ok()) return Fail(image.status().message());
      const Eigen::Isometry3d rig_from_objcentre = loaded->RigFromObjcentre(f);
      std::optional<ExposurePoses> exposure_poses;
      if (dump != nullptr && blur_exposure > 0.0 && f > 0 && f + 1 < sequence->num_frames) {
        exposure_poses =
            CamFromTemplateOverExposure(camera.cam_from_rig, *loaded, f, blur_exposure);
      }
      const Silhouette silhouette =
          RenderSilhouette(caster, camera.camera, camera.cam_from_rig * (*gt)[f], ContourOptions{});
      // Measured as the edge stage's last round measures them (restored chroma with
      // edge.chroma_restoration).
      const EdgeImage measured_on =
          EdgeImageOf(*image, chroma[v], frame.edge.chroma_restoration, silhouette, edge);
      const StatusOr<CorrespondenceLines> lines =
          BuildEdgeLines(caster, camera.camera, camera.cam_from_rig, rig_from_objcentre,
                         measured_on.image, silhouette, edge, measured_on.sampling);
      if (!lines.ok()) return Fail(lines.status().message());
      if (attribute && !lines->lines.empty()) {
        frame_lines[f][v] = std::make_shared<const CorrespondenceLines>(*lines);
      }
      candidates += lines->candidates;
      for (const CorrespondenceLine& line : lines->lines) {
        ++measured;
        bins[BinOf(line.normal)].Add(line.mean_px);
        total[BinOf(line.normal)].Add(line.mean_px);
        if (shift_px > 0.0) {
          EdgeFit inward, outward;
          const bool found = FitEdgeAcross(measured_on.image, linear,
                                           line.centre - shift_px * line.normal, line.normal, edge,
                                           &inward, measured_on.sampling) == EdgeAcross::kFound &&
                             FitEdgeAcross(measured_on.image, linear,
                                           line.centre + shift_px * line.normal, line.normal, edge,
                                           &outward, measured_on.sampling) == EdgeAcross::kFound;
          // The image edge's position along the normal from each of the three anchors.
          const double spread =
              found ? std::max({std::abs(inward.mean_px - shift_px - line.mean_px),
                                std::abs(outward.mean_px + shift_px - line.mean_px)})
                    : std::numeric_limits<double>::infinity();
          shift_bins[BinOf(line.normal)].Add(found ? spread : 9.0);
          if (spread <= 0.1) stable_bins[BinOf(line.normal)].Add(line.mean_px);
        }
        EdgeFit fit;
        if (fits != nullptr &&
            FitEdgeAcross(measured_on.image, linear, line.centre, line.normal, edge, &fit,
                          measured_on.sampling) == EdgeAcross::kFound) {
          std::fprintf(fits, "%s %d %s %+.4f %.4f %.4f %+.5f\n", camera.camera.name.c_str(), f,
                       kBins[BinOf(line.normal)], fit.mean_px, fit.sigma_px, fit.width_px,
                       fit.step);
        }
        if (dump == nullptr) continue;
        std::fprintf(dump, "%s %d %s %.3f %.3f %.4f %.4f %+.4f %.4f", camera.camera.name.c_str(), f,
                     kBins[BinOf(line.normal)], line.centre.x(), line.centre.y(), line.normal.x(),
                     line.normal.y(), line.mean_px, line.sigma_px);
        for (int k = -half; k <= half; ++k) {
          const Eigen::Vector3d rgb = SampleLinearRgb(measured_on.image, linear,
                                                      line.centre + k * edge.step_px * line.normal);
          std::fprintf(dump, " %.4f %.4f %.4f", rgb.x(), rgb.y(), rgb.z());
        }
        if (exposure_poses.has_value()) {
          std::fprintf(dump, " BLUR");
          for (double crossing : ContourCrossingsOverExposure(
                   caster, camera.camera, *exposure_poses, line.centre, line.normal)) {
            std::fprintf(dump, " %.3f", crossing);
          }
        }
        std::fprintf(dump, "\n");
      }
    }
    Accumulator all;
    std::printf("%-6s %4d/%-4d", camera.camera.name.c_str(), measured, candidates);
    for (const Accumulator& bin : bins) {
      std::printf(" | %-5s %5d %+8.3f %6.3f", "", bin.count, bin.Mean(), bin.StandardError());
      all.count += bin.count;
      all.sum += bin.sum;
    }
    std::printf(" | %+8.3f\n", all.Mean());
    if (shift_px > 0.0) {
      std::printf("%-6s %9s", "  moved", "");
      for (const Accumulator& bin : shift_bins) {
        int stable = 0;
        for (double d : bin.values) stable += d <= 0.1;
        std::printf(" | %-5s %5d %7.0f%% %6.3f", "", bin.count,
                    bin.count > 0 ? 100.0 * stable / bin.count : 0.0, bin.Quantile(0.5));
      }
      std::printf(" |  (lines, share within 0.1 px, median disagreement px)\n");
      std::printf("%-6s %9s", "  stable", "");
      for (const Accumulator& bin : stable_bins) {
        std::printf(" | %-5s %5d %+8.3f %6.3f", "", bin.count, bin.Mean(), bin.StandardError());
      }
      std::printf(" |  (mean μ of the lines within 0.1 px)\n");
    }
  }
  if (dump != nullptr) std::fclose(dump);
  if (fits != nullptr) std::fclose(fits);
  std::printf("%-6s %9s", "all", "");
  for (const Accumulator& bin : total) {
    std::printf(" | %-5s %5d %+8.3f %6.3f", "", bin.count, bin.Mean(), bin.StandardError());
  }
  std::printf("\nquantiles of μ over all cameras (10 / 25 / 50 / 75 / 90 %%):\n");
  for (size_t b = 0; b < kBins.size(); ++b) {
    std::printf("  %-5s", kBins[b]);
    for (double q : {0.1, 0.25, 0.5, 0.75, 0.9}) std::printf(" %+7.3f", total[b].Quantile(q));
    std::printf("\n");
  }
  if (attribute) PrintAttribution(*loaded, frame_lines, frame.edge.robust_scale);
  return 0;
}

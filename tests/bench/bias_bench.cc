// Bias benchmark of the joint solver under realistic boundary conditions (shaded rims, soft
// light, low object/background contrast), run by scripts/bench_bias.sh; not a test.
//
// One row per run: `bcot synth` a sequence (--synth-config, default
// configs/synth/shaded_rim.yaml, plus --synth-set overrides: light direction, material), track
// frames 1..N−1 from the ground truth of frame 0 with every camera (MultiViewTracker::Track with
// the annotate config, the per-frame solve of `bcot annotate`; then its temporal window when the
// config has it on, as `bcot annotate` does), and print per camera, in that
// camera's frame at the object's bounding-box centre: mean rotation error, mean |t| per axis,
// mean signed t per axis ± its standard deviation (the bias), lost frames (> 5° or 50 mm,
// reset to the truth), CPU ms/frame (with the window); plus the boundary contrast of the images at
// the true pose.
//
// Boundary contrast (per view, over the true contour of every 5th frame): mean ‖I(inside) −
// I(outside)‖ / mean ‖I(outside) − I(outside far)‖, with I the mean 8-bit RGB over s ∈ [−3, −1]
// (inside), [1, 3] (outside) and [4, 6] (outside far) px along the outward contour normal.
//
// --evidence adds, per view at the true pose of every 5th frame, the signed contour offsets
// along the outward normal (px, negative = inward) of (a) the region measurement (the
// correspondence line's μ with a local colour model learned at the truth) and (b) the edge
// measurement (edge_lines.h), split by where the normal points in the image: lower rim (n_y >
// 0.7), upper rim (n_y < −0.7), sides; with the mean linear luminance just inside (shading).
//
// Usage: bias_bench --config configs/annotate.yaml --work DIR --label NAME [--frames N]
//          [--synth-config FILE] [--synth-set key=value]... [--set key=value]... [--header]
//          [--evidence]
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/core/sequence.h"
#include "bcot/optim/color_model.h"
#include "bcot/optim/correspondence_lines.h"
#include "bcot/optim/edge_lines.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/optim/silhouette.h"
#include "bcot/optim/window_problem.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"
#include "ground_truth_sequence.h"

namespace bcot {
namespace {

struct CameraStats {
  double rotation = 0.0;
  Eigen::Vector3d abs_sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d square_sum = Eigen::Vector3d::Zero();
  int frames = 0;
};

int Fail(const Status& status) {
  std::fprintf(stderr, "bias_bench: %s\n", status.message().c_str());
  return 1;
}

Eigen::Vector3d Bilinear(const cv::Mat3b& image, const Eigen::Vector2d& p) {
  const int x0 = static_cast<int>(std::floor(p.x()));
  const int y0 = static_cast<int>(std::floor(p.y()));
  const double fx = p.x() - x0, fy = p.y() - y0;
  auto at = [&](int x, int y) {
    const cv::Vec3b& v = image(y, x);
    return Eigen::Vector3d(v[2], v[1], v[0]);
  };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

// Mean colour over s in [from, to] (step 0.5) along the normal; false when outside the image.
bool BandMean(const cv::Mat3b& image, const ContourPoint& point, double from, double to,
              Eigen::Vector3d* mean) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (double s = from; s <= to + 1e-9; s += 0.5) {
    const Eigen::Vector2d q = point.pixel + s * point.normal;
    if (!(q.x() >= 0 && q.y() >= 0 && q.x() < image.cols - 1 && q.y() < image.rows - 1)) {
      return false;
    }
    sum += Bilinear(image, q);
    ++count;
  }
  *mean = sum / count;
  return true;
}

// Offsets binned by normal direction: 0 lower rim, 1 upper rim, 2 sides.
struct Bins {
  double sum[3] = {0, 0, 0};
  double shade[3] = {0, 0, 0};
  int count[3] = {0, 0, 0};
  void Add(const Eigen::Vector2d& normal, double offset, double shading) {
    const int bin = normal.y() > 0.7 ? 0 : normal.y() < -0.7 ? 1 : 2;
    sum[bin] += offset;
    shade[bin] += shading;
    ++count[bin];
  }
  std::string Format() const {
    std::string out;
    for (int b = 0; b < 3; ++b) {
      out += count[b] > 0
                 ? fmt::format(" {:+.3f} ({:.3f}) |", sum[b] / count[b], shade[b] / count[b])
                 : std::string(" – |");
    }
    return out;
  }
};

}  // namespace
}  // namespace bcot

int main(int argc, char** argv) {
  using namespace bcot;
  CLI::App app{"Bias benchmark: signed pose error per camera under shaded rims"};
  std::string config_path, work_dir, label;
  std::string synth_config = BCOT_SOURCE_DIR "/configs/synth/shaded_rim.yaml";
  int num_frames = 20;
  std::vector<std::string> synth_overrides, annotate_overrides;
  bool header = false, evidence = false;
  app.add_option("--config", config_path, "annotate config")->required();
  app.add_option("--work", work_dir, "Directory for the synthetic sequences (reused)")->required();
  app.add_option("--label", label, "Row label")->required();
  app.add_option("--frames", num_frames, "Frames");
  app.add_option("--synth-config", synth_config, "Synth config");
  app.add_option("--synth-set", synth_overrides, "Override of the synth config (repeatable)");
  app.add_option("--set", annotate_overrides, "Override of the annotate config (repeatable)");
  app.add_flag("--header", header, "Print the table header first");
  app.add_flag("--evidence", evidence, "Print contour offsets at the truth by rim side");
  CLI11_PARSE(app, argc, argv);
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 1);

  StatusOr<AnnotateOptions> options = ReadAnnotateOptions(config_path, annotate_overrides);
  if (!options.ok()) return Fail(options.status());
  std::vector<std::string> overrides = synth_overrides;
  overrides.push_back(fmt::format("motion.num_frames={}", num_frames));
  StatusOr<SynthOptions> synth = ReadSynthOptions(synth_config, overrides);
  if (!synth.ok()) return Fail(synth.status());
  // One directory per distinct synth setting.
  const std::string key = std::to_string(std::hash<std::string>{}(FormatSynthOptions(*synth)));
  const std::string dir = work_dir + "/" + key;
  StatusOr<bench::GroundTruthSequence> loaded =
      bench::SynthesizeOrLoad(dir, label, [&](const std::string& out) {
        SynthOptions threaded = *synth;
        threaded.render.threads = 2;
        return Synthesize(threaded, out);
      });
  if (!loaded.ok()) return Fail(loaded.status());
  const Sequence* sequence = &loaded->sequence;
  const std::vector<Eigen::Isometry3d>* truth = &loaded->truth;
  const Mesh* mesh = &loaded->mesh;
  const RayCaster caster(*mesh);
  const int num_views = sequence->rig.size();
  std::vector<int> cameras(num_views);
  std::iota(cameras.begin(), cameras.end(), 0);
  auto load_images = [&](int frame) { return bench::ReadFrameImages(*sequence, cameras, frame); };

  // Boundary contrast and evidence at the truth.
  std::vector<double> contrast_num(num_views, 0.0), contrast_den(num_views, 0.0);
  std::vector<Bins> region_bins(num_views), edge_bins(num_views);
  for (int frame = 0; frame < sequence->num_frames; frame += 5) {
    const std::vector<cv::Mat3b> images = load_images(frame);
    for (int c = 0; c < num_views; ++c) {
      const Camera& camera = sequence->rig[c].camera;
      const Eigen::Isometry3d cam_from_rig = sequence->rig[c].cam_from_rig;
      const Silhouette silhouette = RenderSilhouette(caster, camera, cam_from_rig * (*truth)[frame],
                                                     options->tracker.frame.region.contour);
      for (size_t i = 0; i < silhouette.contour.size(); i += 4) {
        const ContourPoint& p = silhouette.contour[i];
        Eigen::Vector3d in, out, far;
        if (!BandMean(images[c], p, -3, -1, &in) || !BandMean(images[c], p, 1, 3, &out) ||
            !BandMean(images[c], p, 4, 6, &far)) {
          continue;
        }
        contrast_num[c] += (in - out).norm();
        contrast_den[c] += (out - far).norm();
      }
      if (!evidence) continue;
      ColorModelOptions local = options->tracker.color;
      local.kind = ColorModelKind::kLocal;
      LocalColorModel model(local, mesh->diameter());
      model.Update(images[c], silhouette);
      const Eigen::Isometry3d rig_from_objcentre = loaded->RigFromObjcentre(frame);
      StatusOr<CorrespondenceLines> region =
          BuildCorrespondenceLines(caster, camera, cam_from_rig, rig_from_objcentre, images[c],
                                   model, silhouette, options->tracker.frame.lines);
      EdgeLineOptions edge_lines = options->tracker.frame.edge.lines;
      if (!edge_lines.response.IsResolved()) edge_lines.response = ImageResponse();  // synth: γ 2.2
      edge_lines.crease_contours = false;  // the rims' evidence: the silhouette's lines
      StatusOr<CorrespondenceLines> edge = BuildEdgeLines(
          caster, camera, cam_from_rig, rig_from_objcentre, images[c], silhouette, edge_lines);
      if (!region.ok() || !edge.ok()) return Fail(region.ok() ? edge.status() : region.status());
      auto shading = [&](const CorrespondenceLine& line) {
        Eigen::Vector3d in;
        ContourPoint p;
        p.pixel = line.centre;
        p.normal = line.normal;
        return BandMean(images[c], p, -3, -1, &in) ? in.mean() / 255.0 : 0.0;
      };
      // Offsets relative to the model point's true projection (the contour itself).
      for (const CorrespondenceLine& line : region->lines) {
        region_bins[c].Add(line.normal,
                           line.mean_px - line.normal.dot(line.projection0 - line.centre),
                           shading(line));
      }
      for (const CorrespondenceLine& line : edge->lines) {
        edge_bins[c].Add(line.normal,
                         line.mean_px - line.normal.dot(line.projection0 - line.centre),
                         shading(line));
      }
    }
  }

  // Tracking.
  std::vector<TrackedView> views;
  for (int c = 0; c < num_views; ++c) {
    views.push_back({sequence->rig[c].camera, sequence->rig[c].cam_from_rig, 1.0});
  }
  StatusOr<std::unique_ptr<MultiViewTracker>> tracker =
      MultiViewTracker::Create(caster, views, options->tracker);
  if (!tracker.ok()) return Fail(tracker.status());
  std::vector<CameraStats> stats(num_views);
  int lost = 0, timed = 0;
  double cpu_ms = 0.0;
  Eigen::Isometry3d rig_from_objcentre = loaded->RigFromObjcentre(0);
  if (!(*tracker)->Reset(load_images(0), rig_from_objcentre).ok()) return 1;
  // The temporal window of the annotate config, when it is on, refines the per-frame poses
  // like `bcot annotate` does (frame 0 and lost frames held at the truth they were reset to).
  std::unique_ptr<WindowSmoother> window;
  if (options->window.enabled) window = std::make_unique<WindowSmoother>(options->window);
  std::vector<Eigen::Isometry3d> poses = {rig_from_objcentre};
  std::vector<bool> counted = {false};
  if (window) window->Push(rig_from_objcentre, {});
  for (int frame = 1; frame < sequence->num_frames; ++frame) {
    const std::vector<cv::Mat3b> images = load_images(frame);
    const std::clock_t start = std::clock();
    std::vector<ViewLinearisation> linearisations;
    StatusOr<FrameSummary> summary = (*tracker)->Track(
        images, &rig_from_objcentre, window != nullptr ? &linearisations : nullptr);
    cpu_ms += 1000.0 * static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    ++timed;
    if (!summary.ok()) return Fail(summary.status());
    const Eigen::Isometry3d expected_rig = loaded->RigFromObjcentre(frame);
    bool is_lost = false;
    for (int c = 0; c < num_views; ++c) {
      const Eigen::Isometry3d estimate = sequence->rig[c].cam_from_rig * rig_from_objcentre;
      const Eigen::Isometry3d expected = sequence->rig[c].cam_from_rig * expected_rig;
      const double rotation = RotationDistanceDeg(estimate.linear(), expected.linear());
      const Eigen::Vector3d t = estimate.translation() - expected.translation();
      if (rotation > 5.0 || t.norm() > 50.0) is_lost = true;
    }
    if (is_lost) {
      ++lost;
      rig_from_objcentre = expected_rig;
      if (!(*tracker)->Reset(images, rig_from_objcentre).ok()) return 1;
      linearisations.clear();
    }
    poses.push_back(rig_from_objcentre);
    counted.push_back(!is_lost);
    if (window) {
      const std::clock_t window_start = std::clock();
      window->Push(rig_from_objcentre, std::move(linearisations));
      cpu_ms += 1000.0 * static_cast<double>(std::clock() - window_start) / CLOCKS_PER_SEC;
    }
  }
  if (window) {
    const std::clock_t window_start = std::clock();
    window->Finish();
    cpu_ms += 1000.0 * static_cast<double>(std::clock() - window_start) / CLOCKS_PER_SEC;
    poses = window->rig_from_objcentre();
  }
  for (int frame = 1; frame < sequence->num_frames; ++frame) {
    if (!counted[frame]) continue;
    const Eigen::Isometry3d expected_rig = loaded->RigFromObjcentre(frame);
    for (int c = 0; c < num_views; ++c) {
      const Eigen::Isometry3d estimate = sequence->rig[c].cam_from_rig * poses[frame];
      const Eigen::Isometry3d expected = sequence->rig[c].cam_from_rig * expected_rig;
      const Eigen::Vector3d t = estimate.translation() - expected.translation();
      CameraStats& s = stats[c];
      s.rotation += RotationDistanceDeg(estimate.linear(), expected.linear());
      s.abs_sum += t.cwiseAbs();
      s.sum += t;
      s.square_sum += t.cwiseProduct(t);
      ++s.frames;
    }
  }

  if (header) {
    std::printf(
        "| run | cam | contrast | r (°) | abs x / y / z (mm) | bias x (mm) | bias y (mm) | bias z "
        "(mm) | lost | CPU ms/frame |\n|---|---|---:|---:|---|---|---|---|---:|---:|\n");
  }
  for (int c = 0; c < num_views; ++c) {
    const CameraStats& s = stats[c];
    const int n = std::max(1, s.frames);
    const Eigen::Vector3d mean = s.sum / n;
    const Eigen::Vector3d sd =
        (s.square_sum / n - mean.cwiseProduct(mean)).cwiseMax(0.0).cwiseSqrt();
    std::printf(
        "| %s | %s | %.1f | %.3f | %.3f / %.3f / %.3f | %+.3f ± %.3f | %+.3f ± %.3f | %+.3f ± "
        "%.3f | %d | %.0f |\n",
        label.c_str(), sequence->rig[c].camera.name.c_str(),
        contrast_den[c] > 0 ? contrast_num[c] / contrast_den[c] : 0.0, s.rotation / n,
        s.abs_sum.x() / n, s.abs_sum.y() / n, s.abs_sum.z() / n, mean.x(), sd.x(), mean.y(), sd.y(),
        mean.z(), sd.z(), lost, cpu_ms / std::max(1, timed));
  }
  if (evidence) {
    for (int c = 0; c < num_views; ++c) {
      std::printf(
          "| %s | %s | offset at truth (px, + outward) and luminance inside: lower rim | upper "
          "rim | sides |\n| | region μ |%s\n| | edge μ |%s\n",
          label.c_str(), sequence->rig[c].camera.name.c_str(), region_bins[c].Format().c_str(),
          edge_bins[c].Format().c_str());
    }
  }
  std::fflush(stdout);
  return 0;
}

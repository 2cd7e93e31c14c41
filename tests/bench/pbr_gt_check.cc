// Ground-truth check of the physically based render path (issue 12), and the boundary
// contrast of its images.
//
// For every camera and frame of a sequence written by scripts/pbr_synth.sh, bcot's own Embree
// contour of the ground-truth pose (gt/<camera>/pose.txt, sub-pixel silhouette points with
// outward normals) is compared with Blender's coverage of the object alone
// (gt/mask/<camera>/NNNNNN.png, 16-bit, box-filtered over each pixel's square). Along each
// contour normal, the coverage bilinearly interpolated between pixel centres (at integer
// coordinates) is searched for its 0.5 crossing, in Blender's mask and in bcot's own coverage
// of the same pose (Embree, 16×16 rays per pixel averaged over the pixel's square, i.e. the
// same box filter); the boundary distance d is the signed distance between the two crossings
// (positive = Blender's boundary lies outside bcot's). Using one estimator on both cancels its
// own error (interpolation across diagonal edges, curvature), so d is what the two renderers
// disagree on (plus Blender's sampling noise). A half-pixel, principal-point, axis or unit slip
// moves it by ≥ 0.5 px; agreement within a few hundredths of a pixel proves the conventions.
// Also printed: "vs contour", the mean signed distance from Embree's bisected contour point to
// Blender's crossing (includes the estimator's own error).
//
// Boundary contrast (per camera, on the rendered frames): along the same normals, the mean
// colour of a band just inside the true contour (1–3 px) and of two outside bands (1–3 px,
// 3–5 px); contrast = mean ‖inside − outside₁‖ / mean ‖outside₁ − outside₂‖ (RGB 0–255).
//
//   build/tests/bench/pbr_gt_check SEQ [--max-mean-px 0.05] [--frames N] [--contrast-only]
// Prints one line per camera and a total; exit 1 when --max-mean-px is given and the mean
// |distance| of any camera exceeds it (or no contour point was compared), 2 on bad input.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "ground_truth_sequence.h"

namespace {

// Bilinear sample with pixel centres at integer coordinates; nullopt outside the image.
template <typename T, int C>
bool Sample(const cv::Mat& image, const Eigen::Vector2d& p, double out[C]) {
  const double x = p.x(), y = p.y();
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= image.cols || y0 + 1 >= image.rows) return false;
  const double ax = x - x0, ay = y - y0;
  for (int c = 0; c < C; ++c) {
    auto at = [&](int r, int col) { return static_cast<double>(image.ptr<T>(r)[col * C + c]); };
    out[c] = (1 - ay) * ((1 - ax) * at(y0, x0) + ax * at(y0, x0 + 1)) +
             ay * ((1 - ax) * at(y0 + 1, x0) + ax * at(y0 + 1, x0 + 1));
  }
  return true;
}

struct Stats {
  int points = 0, missed = 0;
  double sum_abs = 0, sum_signed = 0, max_abs = 0, sum_raw = 0;
  double contrast_num = 0, contrast_den = 0;
  int contrast_points = 0;
  void Add(const Stats& o) {
    points += o.points;
    missed += o.missed;
    sum_abs += o.sum_abs;
    sum_signed += o.sum_signed;
    sum_raw += o.sum_raw;
    max_abs = std::max(max_abs, o.max_abs);
    contrast_num += o.contrast_num;
    contrast_den += o.contrast_den;
    contrast_points += o.contrast_points;
  }
  std::string Line(const std::string& name) const {
    const double n = std::max(points, 1);
    return fmt::format(
        "{:<6} points {:6d} (no crossing {:4d})  mean |d| {:.4f} px  max |d| {:.4f} px  "
        "mean signed d {:+.4f} px  (vs contour {:+.4f} px)  contrast {:.1f}",
        name, points, missed, sum_abs / n, max_abs, sum_signed / n, sum_raw / n,
        contrast_den > 0 ? contrast_num / contrast_den : 0.0);
  }
};

// 0.5 crossing (inside → outside) of a coverage image along p + s·n nearest to s = 0, within
// ±range px; NaN when there is none.
template <typename T>
double Crossing(const cv::Mat& coverage, double scale, const Eigen::Vector2d& p,
                const Eigen::Vector2d& n) {
  constexpr double kStep = 0.01, kRange = 2.0;
  double best = NAN;
  double prev_s = -kRange, prev_c = -1;
  for (int i = 0; i <= static_cast<int>(2 * kRange / kStep + 0.5); ++i) {
    const double s = -kRange + i * kStep;
    double c;
    if (!Sample<T, 1>(coverage, p + s * n, &c)) {
      prev_c = -1;
      continue;
    }
    c *= scale;
    if (prev_c >= 0.5 && c < 0.5) {
      const double crossing = prev_s + (prev_c - 0.5) / (prev_c - c) * (s - prev_s);
      if (std::isnan(best) || std::abs(crossing) < std::abs(best)) best = crossing;
    }
    prev_s = s;
    prev_c = c;
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Blender mask vs bcot's Embree contour of the ground truth; boundary contrast"};
  std::string dir;
  double max_mean_px = -1;
  int max_frames = 0;
  bool contrast_only = false;
  app.add_option("sequence", dir, "sequence directory (scripts/pbr_synth.sh)")->required();
  app.add_option("--max-mean-px", max_mean_px, "fail when a camera's mean |distance| exceeds it");
  app.add_option("--frames", max_frames, "only the first N frames (0 = all)");
  app.add_flag("--contrast-only", contrast_only, "boundary contrast only (no gt/mask needed)");
  CLI11_PARSE(app, argc, argv);

  auto seq = bcot::LoadSequence(dir, /*require_init_pose=*/false);
  if (!seq.ok()) {
    std::fprintf(stderr, "%s\n", seq.status().message().c_str());
    return 2;
  }
  auto mesh = bcot::Mesh::Load(seq->object.mesh_path, seq->object.unit_to_mm);
  if (!mesh.ok()) {
    std::fprintf(stderr, "%s\n", mesh.status().message().c_str());
    return 2;
  }
  const bcot::RayCaster caster(*mesh);
  bcot::ContourOptions contour_options;
  contour_options.precision_px = 1.0 / 512.0;
  contour_options.sample_spacing_px = 1.0;

  Stats total;
  bool fail = false;
  const int frames = max_frames > 0 ? std::min(max_frames, seq->num_frames) : seq->num_frames;
  for (int view = 0; view < seq->rig.size(); ++view) {
    const bcot::Camera& camera = seq->rig[view].camera;
    auto poses = bcot::ReadPoseFile(dir + "/gt/" + camera.name + "/pose.txt");
    if (!poses.ok()) {
      std::fprintf(stderr, "%s\n", poses.status().message().c_str());
      return 2;
    }
    Stats stats;
    for (int frame = 0; frame < frames; ++frame) {
      const auto contour = caster.ExtractContour(camera, poses->at(frame), contour_options);
      const cv::Mat image = cv::imread(seq->image_paths[view][frame], cv::IMREAD_COLOR);
      if (image.empty()) {
        std::fprintf(stderr, "%s: unreadable\n", seq->image_paths[view][frame].c_str());
        return 2;
      }
      cv::Mat mask;
      if (!contrast_only) {
        bcot::StatusOr<cv::Mat> read = bcot::bench::ReadCoverageMask(dir, camera.name, frame);
        if (!read.ok()) {
          std::fprintf(stderr, "%s\n", read.status().message().c_str());
          return 2;
        }
        mask = *std::move(read);
      }
      // bcot's coverage of the same pose: 16×16 rays per pixel, averaged over the pixel.
      cv::Mat1f coverage(camera.height, camera.width, 0.0f);
      if (!contrast_only) {
        bcot::RenderOptions render_options;
        render_options.samples_per_axis = 16;
        render_options.margin_px = 4;
        render_options.depth = render_options.normal_in_cam = false;
        render_options.point_in_object = render_options.triangle_id = false;
        const bcot::RenderedView view = caster.Render(camera, poses->at(frame), render_options);
        if (!view.roi.empty()) {
          cv::Mat1f fine;
          view.mask.convertTo(fine, CV_32F, 1.0 / 255.0);
          cv::Mat1f coarse;
          cv::resize(fine, coarse, view.roi.size(), 0, 0, cv::INTER_AREA);
          coarse.copyTo(coverage(view.roi));
        }
      }
      for (const bcot::ContourPoint& point : contour) {
        if (point.is_hole) continue;
        // Contrast bands along the normal.
        double in[3] = {0, 0, 0}, out1[3] = {0, 0, 0}, out2[3] = {0, 0, 0};
        bool ok = true;
        for (double s = 1.0; s <= 3.0 + 1e-9 && ok; s += 0.5) {
          double a[3], b[3], c[3];
          ok = Sample<uchar, 3>(image, point.pixel - s * point.normal, a) &&
               Sample<uchar, 3>(image, point.pixel + s * point.normal, b) &&
               Sample<uchar, 3>(image, point.pixel + (s + 2.0) * point.normal, c);
          for (int k = 0; k < 3 && ok; ++k) {
            in[k] += a[k] / 5;
            out1[k] += b[k] / 5;
            out2[k] += c[k] / 5;
          }
        }
        if (ok) {
          stats.contrast_num +=
              std::sqrt(std::pow(in[0] - out1[0], 2) + std::pow(in[1] - out1[1], 2) +
                        std::pow(in[2] - out1[2], 2));
          stats.contrast_den +=
              std::sqrt(std::pow(out2[0] - out1[0], 2) + std::pow(out2[1] - out1[1], 2) +
                        std::pow(out2[2] - out1[2], 2));
          ++stats.contrast_points;
        }
        if (contrast_only) continue;
        const double blender = Crossing<uint16_t>(mask, 1.0 / 65535.0, point.pixel, point.normal);
        const double embree = Crossing<float>(coverage, 1.0, point.pixel, point.normal);
        if (std::isnan(blender) || std::isnan(embree)) {
          ++stats.missed;
          continue;
        }
        const double best = blender - embree;
        stats.sum_raw += blender;
        ++stats.points;
        stats.sum_abs += std::abs(best);
        stats.sum_signed += best;
        stats.max_abs = std::max(stats.max_abs, std::abs(best));
      }
    }
    std::printf("%s\n", stats.Line(camera.name).c_str());
    if (max_mean_px >= 0 && !contrast_only &&
        (stats.points == 0 || stats.sum_abs / stats.points > max_mean_px)) {
      fail = true;
    }
    total.Add(stats);
  }
  std::printf("%s\n", total.Line("all").c_str());
  if (fail) {
    std::printf("FAIL: mean |d| above %.3f px\n", max_mean_px);
    return 1;
  }
  return 0;
}

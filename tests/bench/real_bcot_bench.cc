// Real-data check of the region tracker on BCOT frames (release layout: models/<Object>.obj,
// <scene>/K.txt, <scene>/<Object>/%04d.png and pose.txt), run by scripts/bench_real_bcot.sh;
// not a test. Monocular, the BCOT protocol: start from the ground truth of frame 0, track
// frames 1..N−1, reset to the ground truth only after a 5° / 5 cm failure. Prints the error of
// every frame against BCOT's own annotation and the 5°5cm / 2°2cm success rates.
//
// --from-truth instead solves every frame f starting from its own annotation (colour model
// from frame f, no motion): where the region energy's optimum on the image lies relative to
// BCOT's annotation. A frame that is "lost" in this mode is not a tracking failure but a
// disagreement between the image silhouette's best fit and the annotation. --overlay-dir
// writes the annotation's (green) and the solution's (red) silhouette contours per frame.
// --edge-offsets instead prints, per frame, the image edges measured along the contour normals
// of BCOT's annotation (the edge stage's measurement, bcot/optim/edge_lines.h): how many lines
// found an edge and the mean and median signed offset (px, + = the image edge lies outside the
// annotation's contour), i.e. how the edge stage would move that pose, and the share of the
// contour whose boundary shows only in saturated channels (the quality check's CountClippedPoints).
//
// Usage: real_bcot_bench --scene DIR --object NAME --model FILE --config FILE [--set k=v]...
//        [--from-truth] [--overlay-dir DIR] [--edge-offsets] [--threads N]
// TBB (rendering, contours) is limited to --threads (default 1) while timing.
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <string>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "bcot/optim/edge_lines.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/optim/silhouette.h"
#include "bcot/quality/boundary_search.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"

namespace {

int Fail(const std::string& message) {
  std::fprintf(stderr, "real_bcot_bench: %s\n", message.c_str());
  return 1;
}

// The nine numbers of K.txt (`Matx33f K = Matx33f(fx, 0, cx, 0, fy, cy, 0, 0, 1);` or plain).
bool ReadK(const std::string& text, std::vector<double>* k) {
  const std::regex number(R"([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)");
  std::string body = text;
  const size_t open = text.rfind('(');
  if (open != std::string::npos) body = text.substr(open + 1);
  for (auto it = std::sregex_iterator(body.begin(), body.end(), number);
       it != std::sregex_iterator(); ++it) {
    k->push_back(std::stod(it->str()));
  }
  return k->size() == 9;
}

// Draws the outer silhouette contours of the mesh at `cam_from_object` into `image`.
void DrawSilhouette(const bcot::RayCaster& caster, const bcot::Camera& camera,
                    const Eigen::Isometry3d& cam_from_object, const cv::Scalar& colour,
                    cv::Mat* image) {
  const bcot::RenderedView view = caster.Render(camera, cam_from_object, bcot::RenderOptions{});
  if (view.mask.empty()) return;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(view.mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  cv::drawContours(*image, contours, -1, colour, 1, cv::LINE_8, cv::noArray(), INT_MAX,
                   view.roi.tl());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bcot;
  CLI::App app{"Monocular region tracking on real BCOT frames vs BCOT's annotation"};
  std::string scene;
  std::string object;
  std::string model;
  std::string config_path;
  std::vector<std::string> overrides;
  app.add_option("--scene", scene, "Scene folder holding K.txt and <object>/")->required();
  app.add_option("--object", object, "Object folder name")->required();
  app.add_option("--model", model, "Mesh file (mm)")->required();
  app.add_option("--config", config_path, "annotate config")->required();
  app.add_option("--set", overrides, "Override of the config (repeatable)");
  bool from_truth = false;
  std::string overlay_dir;
  app.add_flag("--from-truth", from_truth,
               "Solve every frame from its own annotation (where the image optimum lies)");
  app.add_option("--overlay-dir", overlay_dir,
                 "Write <frame>.png with the annotation (green) and solution (red) contours");
  bool edge_offsets = false;
  app.add_flag("--edge-offsets", edge_offsets,
               "Print the image edges' offsets along the annotation's contour normals");
  int threads = 1;
  app.add_option("--threads", threads, "TBB threads (rendering, contours) while timing")
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);

  StatusOr<AnnotateOptions> options = ReadAnnotateOptions(config_path, overrides);
  if (!options.ok()) return Fail(options.status().message());
  StatusOr<std::string> k_text = ReadTextFile(scene + "/K.txt");
  if (!k_text.ok()) return Fail(k_text.status().message());
  std::vector<double> k;
  if (!ReadK(*k_text, &k)) return Fail(scene + "/K.txt: expected 9 numbers");
  StatusOr<std::vector<Eigen::Isometry3d>> truth = ReadPoseFile(scene + "/" + object + "/pose.txt");
  if (!truth.ok()) return Fail(truth.status().message());
  StatusOr<Mesh> mesh = Mesh::Load(model, 1.0);
  if (!mesh.ok()) return Fail(mesh.status().message());
  const RayCaster caster(*mesh);

  if (!overlay_dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(overlay_dir, error);
    if (error) return Fail(overlay_dir + ": " + error.message());
  }
  auto image_path = [&](size_t frame) {
    return fmt::format("{}/{}/{:04d}.png", scene, object, frame);
  };
  const cv::Mat first = cv::imread(image_path(0), cv::IMREAD_COLOR);
  if (first.empty()) return Fail(image_path(0) + ": cannot read");
  const Camera camera("camera", first.cols, first.rows, k[0], k[4], k[2], k[5]);
  StatusOr<std::unique_ptr<MultiViewTracker>> tracker = MultiViewTracker::Create(
      caster, {{camera, Eigen::Isometry3d::Identity(), 1.0}}, options->tracker);
  if (!tracker.ok()) return Fail(tracker.status().message());

  const Eigen::Isometry3d objcentre_from_template = mesh->objcentre_from_template();
  const Eigen::Isometry3d template_from_objcentre = objcentre_from_template.inverse();
  Eigen::Isometry3d cam_from_objcentre = (*truth)[0] * template_from_objcentre;
  if (!(*tracker)->Reset({cv::Mat3b(first)}, cam_from_objcentre).ok()) return 1;
  std::printf("image response: %s%s\n", (*tracker)->image_response().Name().c_str(),
              (*tracker)->response_estimate().has_value() ? " (estimated from frame 0)" : "");

  // The edge lines decoded as the tracker does (its estimate when edge.response is auto).
  EdgeLineOptions edge_lines = options->tracker.frame.edge.lines;
  edge_lines.response = (*tracker)->image_response();
  edge_lines.crease_contours = false;  // the contour's own lines (header)
  if (edge_offsets) {
    std::printf(
        "| frame | lines | found | mean offset (px) | median offset (px) | contour saturated |\n"
        "|---:|---:|---:|---:|---:|---:|\n");
    const LinearTable linear(edge_lines.response);
    double sum_of_means = 0.0;
    for (size_t frame = 0; frame < truth->size(); ++frame) {
      const cv::Mat image = cv::imread(image_path(frame), cv::IMREAD_COLOR);
      if (image.empty()) return Fail(image_path(frame) + ": cannot read");
      const Eigen::Isometry3d pose = (*truth)[frame] * template_from_objcentre;
      const Silhouette silhouette =
          RenderSilhouette(caster, camera, pose * objcentre_from_template, ContourOptions{});
      StatusOr<CorrespondenceLines> lines =
          BuildEdgeLines(caster, camera, Eigen::Isometry3d::Identity(), pose, cv::Mat3b(image),
                         silhouette, edge_lines);
      if (!lines.ok()) return Fail(lines.status().message());
      std::vector<double> offsets;
      for (const CorrespondenceLine& line : lines->lines) offsets.push_back(line.mean_px);
      double mean = 0.0;
      for (double offset : offsets) mean += offset / std::max<size_t>(1, offsets.size());
      std::sort(offsets.begin(), offsets.end());
      const double median = offsets.empty() ? 0.0 : offsets[offsets.size() / 2];
      // The quality check's count of contour points shown only in saturated channels.
      const int clipped =
          CountClippedPoints(silhouette.contour, cv::Mat3b(image), linear, QualityOptions());
      std::printf("| %zu | %d | %zu | %+.3f | %+.3f | %.1f %% |\n", frame, lines->candidates,
                  offsets.size(), mean, median,
                  100.0 * clipped / std::max<size_t>(1, silhouette.contour.size()));
      sum_of_means += mean;
    }
    std::printf("\nmean over frames of the mean signed offset: %+.3f px\n",
                sum_of_means / truth->size());
    return 0;
  }
  std::printf(
      "| frame | rotation error (°) | translation error (mm) | ms |\n|---:|---:|---:|---:|\n");
  int scored = 0;
  int within_5_5 = 0;
  int within_2_2 = 0;
  int resets = 0;
  double rotation_sum = 0.0;
  double translation_sum = 0.0;
  double milliseconds = 0.0;
  for (size_t frame = 1; frame < truth->size(); ++frame) {
    const cv::Mat image = cv::imread(image_path(frame), cv::IMREAD_COLOR);
    if (image.empty()) return Fail(image_path(frame) + ": cannot read");
    if (from_truth) {
      cam_from_objcentre = (*truth)[frame] * template_from_objcentre;
      if (!(*tracker)->Reset({cv::Mat3b(image)}, cam_from_objcentre).ok()) return 1;
    }
    const auto start = std::chrono::steady_clock::now();
    StatusOr<FrameSummary> summary = (*tracker)->Track({cv::Mat3b(image)}, &cam_from_objcentre);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!summary.ok()) return Fail(summary.status().message());
    milliseconds += ms;
    const Eigen::Isometry3d estimate = cam_from_objcentre * objcentre_from_template;
    const double rotation = RotationDistanceDeg(estimate.linear(), (*truth)[frame].linear());
    const double translation = (estimate.translation() - (*truth)[frame].translation()).norm();
    std::printf("| %zu | %.2f | %.2f | %.1f |\n", frame, rotation, translation, ms);
    if (!overlay_dir.empty()) {
      cv::Mat overlay = image.clone();
      DrawSilhouette(caster, camera, (*truth)[frame], cv::Scalar(0, 255, 0), &overlay);
      DrawSilhouette(caster, camera, estimate, cv::Scalar(0, 0, 255), &overlay);
      const std::string path = fmt::format("{}/{:04d}.png", overlay_dir, frame);
      if (!cv::imwrite(path, overlay)) return Fail(path + ": cannot write");
    }
    ++scored;
    rotation_sum += rotation;
    translation_sum += translation;
    if (rotation <= 5.0 && translation <= 50.0) ++within_5_5;
    if (rotation <= 2.0 && translation <= 20.0) ++within_2_2;
    if (!from_truth && (rotation > 5.0 || translation > 50.0)) {
      ++resets;
      cam_from_objcentre = (*truth)[frame] * template_from_objcentre;
      if (!(*tracker)->Reset({cv::Mat3b(image)}, cam_from_objcentre).ok()) return 1;
    }
  }
  std::printf(
      "\n| frames | 5°5cm (%%) | 2°2cm (%%) | mean rotation (°) | mean translation (mm) | resets "
      "| ms/frame |\n|---:|---:|---:|---:|---:|---:|---:|\n");
  std::printf("| %d | %.1f | %.1f | %.2f | %.2f | %d | %.1f |\n", scored,
              100.0 * within_5_5 / scored, 100.0 * within_2_2 / scored, rotation_sum / scored,
              translation_sum / scored, resets, milliseconds / scored);
  return 0;
}

// Per-frame PoseScorer scores (annotate/pose_scorer.h) of annotations of one sequence: the
// region energy with colour models learned at each pose, lower is better. It tells a frame whose
// contour left the object (a lost track) from one that follows it, without ground truth.
//   build/tests/bench/pose_scores SEQ ANNOTATION_DIR [ANNOTATION_DIR ...] [--frames N]
// One line per frame: the frame index, then each annotation's score (a sequence's gt/ counts as
// an annotation too).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "bcot/annotate/pose_scorer.h"
#include "bcot/core/image_io.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"

int main(int argc, char** argv) {
  CLI::App app{"Per-frame PoseScorer scores of annotations"};
  std::string sequence_dir;
  std::vector<std::string> annotations;
  int max_frames = 0;
  app.add_option("sequence", sequence_dir)->required();
  app.add_option("annotations", annotations)->required();
  app.add_option("--frames", max_frames, "Only the first N frames (0 = all)");
  CLI11_PARSE(app, argc, argv);
  const auto fail = [](const std::string& message) {
    std::fprintf(stderr, "pose_scores: %s\n", message.c_str());
    return 2;
  };
  auto sequence = bcot::LoadSequence(sequence_dir, /*require_init_pose=*/false);
  if (!sequence.ok()) return fail(sequence.status().message());
  auto mesh = bcot::Mesh::Load(sequence->object.mesh_path, sequence->object.unit_to_mm);
  if (!mesh.ok()) return fail(mesh.status().message());
  std::vector<std::vector<Eigen::Isometry3d>> poses;
  for (const std::string& dir : annotations) {
    auto read = bcot::ReadPoseFile(dir + "/rig_from_object.txt");
    if (!read.ok()) return fail(read.status().message());
    if (static_cast<int>(read->size()) != sequence->num_frames) {
      return fail(
          fmt::format("{}: {} poses for {} frames", dir, read->size(), sequence->num_frames));
    }
    poses.push_back(std::move(read).value());
  }
  const bcot::RayCaster caster(*mesh);
  const Eigen::Isometry3d template_from_objcentre = mesh->objcentre_from_template().inverse();
  const int frames =
      max_frames > 0 ? std::min(max_frames, sequence->num_frames) : sequence->num_frames;
  for (int frame = 0; frame < frames; ++frame) {
    std::vector<cv::Mat3b> images;
    for (int view = 0; view < sequence->rig.size(); ++view) {
      auto image =
          bcot::ReadCameraImage(sequence->image_paths[view][frame], sequence->rig[view].camera);
      if (!image.ok()) return fail(image.status().message());
      images.push_back(std::move(image).value());
    }
    const bcot::PoseScorer scorer(caster, sequence->rig, images, bcot::PoseScorerOptions());
    std::printf("%d", frame);
    for (const auto& annotation : poses) {
      std::printf(" %.4f", scorer.Score(annotation[frame] * template_from_objcentre));
    }
    std::printf("\n");
  }
  return 0;
}

// A sequence with ground truth (the layout `bcot synth` and scripts/pbr_synth.sh write:
// gt/rig_from_object.txt beside the input contract), loaded once for the accuracy benchmarks.
#pragma once

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"

namespace bcot::bench {

struct GroundTruthSequence {
  Sequence sequence;
  std::vector<Eigen::Isometry3d> truth;  // rig_from_object per frame (gt/rig_from_object.txt)
  Mesh mesh;                             // the object's mesh in mm

  // The truth of `frame` as rig_from_objcentre, the pose the tracker estimates.
  Eigen::Isometry3d RigFromObjcentre(int frame) const {
    return truth[frame] * mesh.objcentre_from_template().inverse();
  }
};

// The images of `frame` seen by the rig's cameras `cameras`, in that order.
inline std::vector<cv::Mat3b> ReadFrameImages(const Sequence& sequence,
                                              const std::vector<int>& cameras, int frame) {
  std::vector<cv::Mat3b> images;
  for (int c : cameras) images.emplace_back(cv::imread(sequence.image_paths[c][frame]));
  return images;
}

inline std::string TruthPath(const std::string& dir) { return dir + "/gt/rig_from_object.txt"; }

// gt/mask/<camera>/NNNNNN.png of a scripts/pbr_synth.sh sequence: the renderer's anti-aliased
// coverage of the object (CV_16UC1, 65535 = covered). kIoError naming the file otherwise.
inline StatusOr<cv::Mat> ReadCoverageMask(const std::string& dir, const std::string& camera,
                                          int frame) {
  const std::string path = dir + "/gt/mask/" + camera + "/" + cv::format("%06d.png", frame);
  cv::Mat mask = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (mask.empty() || mask.type() != CV_16UC1) {
    return Status::IoError(path + ": missing or not 16-bit grey");
  }
  return mask;
}

// Loads the sequence in `dir` (init_pose.txt not required), its ground truth and its mesh.
inline StatusOr<GroundTruthSequence> LoadGroundTruthSequence(const std::string& dir) {
  StatusOr<Sequence> sequence = LoadSequence(dir, /*require_init_pose=*/false);
  if (!sequence.ok()) return sequence.status();
  StatusOr<std::vector<Eigen::Isometry3d>> truth = ReadPoseFile(TruthPath(dir));
  if (!truth.ok()) return truth.status();
  StatusOr<Mesh> mesh = Mesh::Load(sequence->object.mesh_path, sequence->object.unit_to_mm);
  if (!mesh.ok()) return mesh.status();
  return GroundTruthSequence{std::move(sequence).value(), std::move(truth).value(),
                             std::move(mesh).value()};
}

// Runs `synthesize(dir)` unless `dir` already holds a ground truth (a finished synthesis is
// reused across runs; an unfinished one is removed and made again), then loads it.
template <typename SynthesizeFn>
StatusOr<GroundTruthSequence> SynthesizeOrLoad(const std::string& dir, const std::string& label,
                                               SynthesizeFn&& synthesize) {
  if (!std::filesystem::exists(TruthPath(dir))) {
    std::fprintf(stderr, "synthesizing %s (%s) ...\n", dir.c_str(), label.c_str());
    std::filesystem::remove_all(dir);
    const Status status = synthesize(dir);
    if (!status.ok()) return status;
  }
  return LoadGroundTruthSequence(dir);
}

}  // namespace bcot::bench

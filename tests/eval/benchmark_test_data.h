// Benchmark test data: scored frames for the metrics and report tests, and tiny benchmark trees
// on disk for the layout, evaluator and eval-command tests.
#pragma once

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/core/status.h"
#include "bcot/eval/metrics.h"
#include "test_util.h"

namespace bcot::test {

// A frame of an object with d = 100 mm and the given rotation (deg), translation (mm) and ADD
// (mm) errors, lost when it fails the 5°/5 cm reset test; `time_ms` NaN = no tracker time.
inline ScoredFrame MakeScoredFrame(double deg, double mm, double add_mm,
                                   double time_ms = std::numeric_limits<double>::quiet_NaN()) {
  ScoredFrame frame;
  frame.errors = {deg, mm, add_mm};
  frame.diameter_mm = 100.0;
  frame.time_ms = time_ms;
  frame.lost = deg > 5.0 || mm > 50.0;
  return frame;
}

// A 100 mm cube (d = 100) as OBJ text, template frame = its centre.
inline std::string CubeObj() {
  std::string text = "# cube, mm\n";
  for (int i = 0; i < 8; ++i) {
    text += fmt::format("v {} {} {}\n", (i & 1) ? 50 : -50, (i & 2) ? 50 : -50, (i & 4) ? 50 : -50);
  }
  const int faces[12][3] = {{1, 3, 2}, {2, 3, 4}, {5, 6, 7}, {6, 8, 7}, {1, 2, 5}, {2, 6, 5},
                            {3, 7, 4}, {4, 7, 8}, {1, 5, 3}, {3, 5, 7}, {2, 4, 6}, {4, 8, 6}};
  for (const auto& f : faces) text += fmt::format("f {} {} {}\n", f[0], f[1], f[2]);
  return text;
}

// Smooth GT trajectory cam_from_object: 3° and 4 mm per frame.
inline std::vector<Eigen::Isometry3d> MakeTrajectory(int num_frames) {
  std::vector<Eigen::Isometry3d> poses;
  for (int f = 0; f < num_frames; ++f) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = ExpSO3(Eigen::Vector3d(0.3, 1.0, 0.2).normalized() * (3.0 * f * M_PI / 180));
    pose.translation() = Eigen::Vector3d(4.0 * f, -2.0 * f, 600.0);
    poses.push_back(pose);
  }
  return poses;
}

// A BCOT pose file as the release writes it: 6 digits, tabs, trailing tab, CRLF.
inline std::string BcotPoseText(const std::vector<Eigen::Isometry3d>& poses) {
  std::string text;
  for (const Eigen::Isometry3d& p : poses) {
    const Eigen::Matrix3d& r = p.linear();
    const Eigen::Vector3d& t = p.translation();
    text += fmt::format(
        "{:.6f}\t{:.6f}\t{:.6f}\t{:.6f}\t{:.6f}\t{:.6f}\t{:.6f}\t{:.6f}\t{:.6f}\t"
        "{:.3f}\t{:.3f}\t{:.3f}\t\r\n",
        r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2), t.x(),
        t.y(), t.z());
  }
  return text;
}

// 8×6 frame whose pixels all hold `frame` (so a fake tracker can tell which frame it sees).
inline void WriteFrameImage(const std::string& path, int frame) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  cv::Mat3b image(6, 8, cv::Vec3b(frame, frame, frame));
  BCOT_CHECK(cv::imwrite(path, image));
}

// <root>/models/<object>.obj, <root>/<scene>/K.txt, <root>/<scene>/<object>/0000.png..., pose.txt.
inline void WriteBcotSequence(const std::string& root, const std::string& scene,
                              const std::string& object, const std::vector<Eigen::Isometry3d>& gt) {
  WriteText(root + "/models/" + object + ".obj", CubeObj());
  WriteText(root + "/" + scene + "/K.txt",
            "Matx33f K = Matx33f(500.5, 0.0, 319.5, 0.0, 501.0, 255.5, 0.0, 0.0, 1.0);\n");
  WriteText(root + "/" + scene + "/" + object + "/pose.txt", BcotPoseText(gt));
  for (size_t f = 0; f < gt.size(); ++f) {
    WriteFrameImage(fmt::format("{}/{}/{}/{:04d}.png", root, scene, object, f),
                    static_cast<int>(f));
  }
}

}  // namespace bcot::test

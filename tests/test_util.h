// Shared test helpers: temporary directories, data paths, pose matchers.
#pragma once

#include <gmock/gmock.h>

#include <Eigen/Geometry>
#include <initializer_list>
#include <random>
#include <string>

#include "bcot/core/se3.h"
#include "bcot/core/status.h"

namespace bcot::test {

using ::bcot::kPi;

// A fresh directory under the system temp dir, removed (recursively) on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string File(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

// Project source root (for bundled data/ and configs/).
std::string SourcePath(const std::string& relative);
// Path inside ../shared/data, or "" when that folder is absent (tests then GTEST_SKIP).
std::string SharedDataPath(const std::string& relative);
// Path of the built `bcot` binary.
std::string BcotBinary();

// Copies the directory `source` recursively to `target` (which must not exist); returns target.
std::string CopyTree(const std::string& source, const std::string& target);

// Writes `content` to `path` (creating parent directories); CHECK-fails on error.
void WriteText(const std::string& path, const std::string& content);

// Runs a shell command, returns its exit code; stdout+stderr go to `output` when non-null.
int RunCommand(const std::string& command, std::string* output = nullptr);

// Lines (newline characters) in a command's output: a one-line error has exactly one.
int CountLines(const std::string& text);

// `bcot synth --quiet --config configs/synth/<config> --out <sequence_dir> <settings>`
// (settings: "--set key=value ..."); CHECK-fails, printing the command's output, when it fails.
void Synthesize(const std::string& sequence_dir, const std::string& settings,
                const std::string& config = "demo.yaml");

// `bcot synth` of the demo scene at 160×128 with `num_frames` frames into `sequence_dir`, then,
// when `annotation_dir` is not empty, `bcot annotate` of it with configs/track.yaml and the
// `annotate_overrides` ("--set key=value ..."; accepted or rejected both do). CHECK-fails when
// a command fails.
void MakeTinyAnnotatedSequence(const std::string& sequence_dir, int num_frames,
                               const std::string& annotation_dir,
                               const std::string& annotate_overrides = "");

// A unit vector in a uniformly random direction (normalised standard normal draws).
inline Eigen::Vector3d RandomUnitVector(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

// EXPECTs `status` to have `code` and a message that contains each of `parts` (a missing part
// is reported with the whole message).
void ExpectErrorNaming(const Status& status, StatusCode code,
                       std::initializer_list<std::string> parts);

// Rotation (deg) and translation (mm) distance between two poses.
double RotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);
double TranslationErrorMm(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

MATCHER_P3(PoseNear, expected, max_deg, max_mm,
           "pose within " + ::testing::PrintToString(max_deg) + " deg and " +
               ::testing::PrintToString(max_mm) + " mm") {
  const double deg = RotationErrorDeg(arg, expected);
  const double mm = TranslationErrorMm(arg, expected);
  *result_listener << "rotation error " << deg << " deg, translation error " << mm << " mm";
  return deg <= max_deg && mm <= max_mm;
}

}  // namespace bcot::test

#include "test_util.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "bcot/core/se3.h"
#include "bcot/core/status.h"

namespace bcot::test {

TempDir::TempDir() {
  std::random_device device;
  const auto base = std::filesystem::temp_directory_path();
  for (int attempt = 0; attempt < 100; ++attempt) {
    const auto candidate = base / ("bcot_test_" + std::to_string(device()));
    if (std::filesystem::create_directory(candidate)) {
      path_ = candidate.string();
      return;
    }
  }
  BCOT_CHECK(false && "could not create a temporary directory");
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string SourcePath(const std::string& relative) {
  return std::string(BCOT_SOURCE_DIR) + "/" + relative;
}

std::string SharedDataPath(const std::string& relative) {
  const std::string root = BCOT_SHARED_DATA;
  if (root.empty() || !std::filesystem::exists(root + "/" + relative)) return "";
  return root + "/" + relative;
}

std::string BcotBinary() { return BCOT_BINARY; }

void WriteText(const std::string& path, const std::string& content) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  std::ofstream out(path, std::ios::binary);
  out << content;
  BCOT_CHECK(out.good());
}

int RunCommand(const std::string& command, std::string* output) {
  const std::string full = command + " 2>&1";
  FILE* pipe = popen(full.c_str(), "r");
  BCOT_CHECK(pipe != nullptr);
  std::array<char, 4096> buffer;
  std::string text;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) text.append(buffer.data(), n);
  const int status = pclose(pipe);
  if (output != nullptr) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string CopyTree(const std::string& source, const std::string& target) {
  std::filesystem::copy(source, target, std::filesystem::copy_options::recursive);
  return target;
}

int CountLines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

void Synthesize(const std::string& sequence_dir, const std::string& settings,
                const std::string& config) {
  std::string output;
  const int code =
      RunCommand(BcotBinary() + " synth --quiet --config " + SourcePath("configs/synth/" + config) +
                     " --out " + sequence_dir + " " + settings,
                 &output);
  if (code != 0) std::fprintf(stderr, "%s\n", output.c_str());
  BCOT_CHECK(code == 0 && "bcot synth failed");
}

void MakeTinyAnnotatedSequence(const std::string& sequence_dir, int num_frames,
                               const std::string& annotation_dir,
                               const std::string& annotate_overrides) {
  Synthesize(sequence_dir,
             "--set cameras.width=160 --set cameras.height=128 --set distractors.count=1"
             " --set render.object_samples_per_axis=2 --set motion.num_frames=" +
                 std::to_string(num_frames));
  if (annotation_dir.empty()) return;
  std::string output;
  const int annotate =
      RunCommand(BcotBinary() + " annotate --quiet " + sequence_dir + " --out " + annotation_dir +
                     " --config " + SourcePath("configs/track.yaml") + " " + annotate_overrides,
                 &output);
  BCOT_CHECK((annotate == 0 || annotate == kExitRejected) && "bcot annotate failed");
}

void ExpectErrorNaming(const Status& status, StatusCode code,
                       std::initializer_list<std::string> parts) {
  EXPECT_EQ(status.code(), code) << status.message();
  for (const std::string& part : parts) {
    EXPECT_NE(status.message().find(part), std::string::npos)
        << "missing '" << part << "' in: " << status.message();
  }
}

double RotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return RotationDistanceDeg(a.linear(), b.linear());
}

double TranslationErrorMm(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

}  // namespace bcot::test

// The review workbench's frame switch (scripts/bench_review.sh runs this and tabulates it).
//
// What the page asks for when the user moves to another frame: one /api/frame/N/view/CAM.jpg per
// view, i.e. ReviewSession::ViewJpeg (read the frame image, cast the silhouette of the
// annotated pose with Embree, draw its contour, encode JPEG). Scene: `bcot synth`'s demo
// (configs/synth/demo.yaml) at 960×768, two cameras, 8 frames, with its ground truth written as
// the annotation (rig_from_object.txt; the pose only changes what is drawn). Each iteration
// serves the next frame, cycling: both views one after the other (the server answers them on
// two threads, so this is the single-core cost), or one view. Target (issue 16): a frame
// switch of two 960×768 views within 150 ms. Benchmarks time; tests never check wall time.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bcot/core/annotation_poses.h"
#include "bcot/core/pose_io.h"
#include "bcot/review/review_options.h"
#include "bcot/review/review_session.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"

namespace bcot {
namespace {

constexpr int kNumFrames = 8;
const int kJpegQuality = ReviewOptions().jpeg_quality;  // what `bcot review` serves

template <typename T>
T OrDie(StatusOr<T> value) {
  if (!value.ok()) {
    std::fprintf(stderr, "bench_review: %s\n", value.status().message().c_str());
    std::exit(1);
  }
  return std::move(value).value();
}

void CheckOk(const Status& status) {
  if (status.ok()) return;
  std::fprintf(stderr, "bench_review: %s\n", status.message().c_str());
  std::exit(1);
}

// The synthesized sequence with its ground truth as annotation, and the loaded session.
struct Fixture {
  std::filesystem::path dir;
  std::unique_ptr<ReviewSession> session;

  Fixture() {
    dir = std::filesystem::temp_directory_path() /
          ("bcot_bench_review_" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::remove_all(dir);
    const std::string source = BCOT_SOURCE_DIR;
    const std::string sequence_dir = (dir / "seq").string();
    const std::string annotation_dir = (dir / "ann").string();
    const SynthOptions synth = OrDie(ReadSynthOptions(
        source + "/configs/synth/demo.yaml", {"cameras.width=960", "cameras.height=768",
                                              "motion.num_frames=" + std::to_string(kNumFrames)}));
    CheckOk(Synthesize(synth, sequence_dir));
    const Sequence sequence = OrDie(LoadSequence(sequence_dir, /*require_init_pose=*/false));
    CheckOk(WriteAnnotationPoses(annotation_dir, sequence.rig,
                                 OrDie(ReadPoseFile(sequence_dir + "/gt/rig_from_object.txt"))));
    session = OrDie(ReviewSession::Load(sequence_dir, annotation_dir));
  }
  ~Fixture() { std::filesystem::remove_all(dir); }
};

const Fixture& TheFixture() {
  static const Fixture fixture;  // benchmark fixture data, built on first use
  return fixture;
}

void BM_FrameSwitch(benchmark::State& state) {
  const ReviewSession& session = *TheFixture().session;
  const int num_views = static_cast<int>(state.range(0));
  const Rig& rig = session.sequence().rig;
  int frame = 0;
  size_t bytes = 0;
  for (auto _ : state) {
    for (int view = 0; view < num_views; ++view) {
      const ReviewTarget target =
          OrDie(session.Resolve(std::to_string(frame), rig[view].camera.name));
      const std::vector<unsigned char> jpeg = OrDie(session.ViewJpeg(target, kJpegQuality));
      bytes += jpeg.size();
      benchmark::DoNotOptimize(jpeg.data());
    }
    frame = (frame + 1) % kNumFrames;
  }
  state.counters["views"] = num_views;
  state.counters["width"] = rig[0].camera.width;
  state.counters["height"] = rig[0].camera.height;
  state.counters["jpeg_kb_per_view"] =
      static_cast<double>(bytes) / 1024.0 / (static_cast<double>(state.iterations()) * num_views);
}
BENCHMARK(BM_FrameSwitch)->Arg(2)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace bcot

BENCHMARK_MAIN();

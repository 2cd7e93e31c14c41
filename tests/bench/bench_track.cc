// MultiViewTracker::Track throughput (scripts/bench_track.sh runs this and tabulates it).
//
// Scene: a short binocular sequence of the precision protocol, synthesized once into a
// temporary directory: configs/synth/arc_and_cone.yaml with C-0 and the 90° arc camera only
// (cam0, cam1), 640×480, the bunny, 16 frames. Each benchmark iteration tracks the next frame
// (images decoded beforehand); after the last frame the tracker is reset to the ground truth of
// frame 0 outside the timed region. Settings: configs/track.yaml (1 round) and
// configs/annotate.yaml (2 rounds and the edge stage; the temporal window is not part of Track).
// TBB is limited to one thread: the single-core figure. Benchmarks time; tests never check wall
// time.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/optim/multi_view_tracker.h"
#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/render/sparse_viewpoint_model.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"

namespace bcot {
namespace {

constexpr int kNumFrames = 16;

template <typename T>
T OrDie(StatusOr<T> value) {
  if (!value.ok()) {
    std::fprintf(stderr, "bench_track: %s\n", value.status().message().c_str());
    std::exit(1);
  }
  return std::move(value).value();
}

// The synthesized sequence, its decoded images, ground truth and mesh (built once).
struct Fixture {
  Sequence sequence;
  std::vector<std::vector<cv::Mat3b>> images;  // [frame][view]
  std::vector<Eigen::Isometry3d> rig_from_objcentre;
  std::unique_ptr<Mesh> mesh;
  std::unique_ptr<RayCaster> caster;
  std::filesystem::path dir;

  Fixture() {
    dir = std::filesystem::temp_directory_path() /
          ("bcot_bench_track_" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::remove_all(dir);
    const std::string source = BCOT_SOURCE_DIR;
    const SynthOptions synth = OrDie(
        ReadSynthOptions(source + "/configs/synth/arc_and_cone.yaml",
                         {"object.mesh=" + source + "/data/meshes/bunny.obj", "object.name=bunny",
                          "cameras.arc_angles_deg=[90]", "cameras.cone_angles_deg=[]",
                          "motion.num_frames=" + std::to_string(kNumFrames), "seed=11"}));
    const Status status = Synthesize(synth, dir.string());
    if (!status.ok()) {
      std::fprintf(stderr, "bench_track: %s\n", status.message().c_str());
      std::exit(1);
    }
    sequence = OrDie(LoadSequence(dir.string()));
    mesh = std::make_unique<Mesh>(
        OrDie(Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm)));
    caster = std::make_unique<RayCaster>(*mesh);
    const std::vector<Eigen::Isometry3d> truth =
        OrDie(ReadPoseFile(dir.string() + "/gt/rig_from_object.txt"));
    const Eigen::Isometry3d template_from_objcentre = mesh->objcentre_from_template().inverse();
    for (int frame = 0; frame < sequence.num_frames; ++frame) {
      rig_from_objcentre.push_back(truth[frame] * template_from_objcentre);
      std::vector<cv::Mat3b> views;
      for (int c = 0; c < 2; ++c) views.emplace_back(cv::imread(sequence.image_paths[c][frame]));
      images.push_back(std::move(views));
    }
  }
  ~Fixture() { std::filesystem::remove_all(dir); }
};

const Fixture& TheFixture() {
  static const Fixture fixture;  // benchmark fixture data, built on first use
  return fixture;
}

// The fixture mesh's sparse viewpoint model (default options), built on first use.
std::shared_ptr<const SparseViewpointModel> TheViewpointModel() {
  static const std::shared_ptr<const SparseViewpointModel> model =
      std::make_shared<const SparseViewpointModel>(
          SparseViewpointModel::Build(*TheFixture().caster, SparseViewpointModelOptions()));
  return model;
}

// `overrides`: --set style settings on top of the config (the region energy variants).
void BM_Track(benchmark::State& state, const std::string& config,
              const std::vector<std::string>& overrides) {
  const Fixture& fixture = TheFixture();
  const AnnotateOptions options =
      OrDie(ReadAnnotateOptions(std::string(BCOT_SOURCE_DIR) + "/configs/" + config, overrides));
  const std::shared_ptr<const SparseViewpointModel> viewpoint_model =
      options.tracker.frame.lines_from_viewpoint_model ||
              options.tracker.viewpoint_model_for_two_views
          ? TheViewpointModel()
          : nullptr;
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 1);
  std::vector<TrackedView> views;
  for (int c = 0; c < 2; ++c) {
    views.push_back({fixture.sequence.rig[c].camera, fixture.sequence.rig[c].cam_from_rig, 1.0});
  }
  std::unique_ptr<MultiViewTracker> tracker = OrDie(MultiViewTracker::Create(
      *fixture.caster, views, options.tracker, std::nullopt, viewpoint_model));
  Eigen::Isometry3d rig_from_objcentre;
  int frame = kNumFrames;  // reset on the first iteration
  for (auto _ : state) {
    if (frame >= fixture.sequence.num_frames) {
      state.PauseTiming();
      frame = 1;
      rig_from_objcentre = fixture.rig_from_objcentre[0];
      if (!tracker->Reset(fixture.images[0], rig_from_objcentre).ok()) std::exit(1);
      state.ResumeTiming();
    }
    const StatusOr<FrameSummary> summary =
        tracker->Track(fixture.images[frame], &rig_from_objcentre);
    benchmark::DoNotOptimize(summary);
    ++frame;
  }
  state.counters["frames"] = static_cast<double>(state.iterations());
}

}  // namespace
}  // namespace bcot

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  // The configs as they are, then with the sparse region energy, rendered or from the sparse
  // viewpoint model (sparse_viewpoint_model.h), the colour models learned from the rendered
  // silhouette or along the model's contour; last, the model on the frames two views see (all
  // of this benchmark's: the energy and colours of the one before it, frame 0 as configured).
  const std::vector<std::pair<std::string, std::vector<std::string>>> variants = {
      {"", {}},
      {"/sparse", {"cost.energy=sparse"}},
      {"/sparse_viewpoints", {"cost.energy=sparse", "lines.viewpoint_model=true"}},
      {"/sparse_viewpoints_colors",
       {"cost.energy=sparse", "lines.viewpoint_model=true", "color.samples=viewpoint_model"}},
      {"/viewpoint_model_two_views", {"lines.viewpoint_model_two_views=true"}}};
  for (const std::string config : {"track.yaml", "annotate.yaml"}) {
    for (const auto& [suffix, overrides] : variants) {
      benchmark::RegisterBenchmark(
          ("Track/2views/640x480/" + config + suffix + "/threads:1").c_str(), bcot::BM_Track,
          config, overrides)
          ->Unit(benchmark::kMillisecond)
          ->MinTime(2.0);
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

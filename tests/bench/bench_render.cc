// Render and ExtractContour throughput (scripts/bench_render.sh runs this and tabulates it).
//
// Scene: a mesh whose image is 40 % of the image height, 640×512 (f = 1000 px) and the same
// physical camera at 1280×1024 (Camera::Scaled(2)). Meshes: a 10,000-triangle torus (tilted so
// the silhouette has a hole) and the bundled spool CAD part (1,294 triangles). Each benchmark
// runs with TBB limited to `threads` (1 = the single-core figure; 2 = scaling on this 2-core
// machine). Real time is reported, since rendering runs on TBB workers.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bcot/render/mesh.h"
#include "bcot/render/ray_caster.h"
#include "bcot/render/sparse_viewpoint_model.h"
#include "test_meshes.h"

namespace bcot {
namespace {

constexpr double kImageFractionOfHeight = 0.4;

using test::MakeTorus;

struct Scene {
  Mesh mesh;
  Camera camera;
  Eigen::Isometry3d cam_from_object = Eigen::Isometry3d::Identity();
};

// `mesh` is centred; the camera looks at it from the distance where its longest bbox side
// spans 40 % of the image height, rotated by `rotation`.
Scene MakeScene(Mesh mesh, int image_height, const Eigen::AngleAxisd& rotation) {
  Scene scene{std::move(mesh), Camera("bench", 640, 512, 1000.0, 1000.0, 319.5, 255.5), {}};
  scene.mesh = scene.mesh.Transformed(scene.mesh.objcentre_from_template());
  if (image_height == 1024) scene.camera = scene.camera.Scaled(2.0);
  const double distance_mm =
      scene.mesh.diameter() * scene.camera.fy / (kImageFractionOfHeight * scene.camera.height);
  scene.cam_from_object.linear() = rotation.toRotationMatrix();
  scene.cam_from_object.translation() = Eigen::Vector3d(0.0, 0.0, distance_mm);
  return scene;
}

Scene SceneFor(const std::string& mesh_name, int image_height) {
  if (mesh_name == "torus10k") {
    return MakeScene(MakeTorus(60.0, 20.0, 100, 50), image_height,
                     Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX()));
  }
  StatusOr<Mesh> spool = Mesh::Load(std::string(BCOT_SOURCE_DIR) + "/data/meshes/spool.off");
  if (!spool.ok()) {
    std::fprintf(stderr, "%s\n", spool.status().message().c_str());
    std::abort();
  }
  const Mesh scaled = spool->Transformed(Eigen::Isometry3d::Identity(), 150.0 / spool->diameter());
  return MakeScene(scaled, image_height,
                   Eigen::AngleAxisd(0.9, Eigen::Vector3d(1.0, 0.5, 0.2).normalized()));
}

// `reuse`: render into the same RenderedView every frame (the tracking-loop overload) instead
// of allocating fresh images.
void BM_Render(benchmark::State& state, const std::string& mesh_name, int image_height,
               bool full_image, bool reuse, int threads) {
  const Scene scene = SceneFor(mesh_name, image_height);
  const RayCaster caster(scene.mesh);
  RenderOptions options;
  if (full_image) options.roi = cv::Rect(0, 0, scene.camera.width, scene.camera.height);
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);
  double rays = 0.0;
  RenderedView reused;
  for (auto _ : state) {
    RenderedView fresh;
    RenderedView& view = reuse ? reused : fresh;
    caster.Render(scene.camera, scene.cam_from_object, options, &view);
    benchmark::DoNotOptimize(view.depth.data);
    rays = static_cast<double>(view.mask.total());
  }
  const double hits =
      cv::countNonZero(caster.Render(scene.camera, scene.cam_from_object, options).mask);
  state.counters["rays"] = rays;
  state.counters["hit_fraction"] = hits / rays;
  state.counters["rays_per_second"] =
      benchmark::Counter(rays * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["tbb_threads"] = threads;
  state.counters["triangles"] = static_cast<double>(scene.mesh.triangles().size());
}

void BM_ExtractContour(benchmark::State& state, const std::string& mesh_name, int image_height,
                       int threads) {
  const Scene scene = SceneFor(mesh_name, image_height);
  const RayCaster caster(scene.mesh);
  const ContourOptions options;
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);
  double points = 0.0;
  for (auto _ : state) {
    const std::vector<ContourPoint> contour =
        caster.ExtractContour(scene.camera, scene.cam_from_object, options);
    benchmark::DoNotOptimize(contour.data());
    points = static_cast<double>(contour.size());
  }
  state.counters["points"] = points;
  state.counters["points_per_second"] =
      benchmark::Counter(points * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["tbb_threads"] = threads;
  state.counters["triangles"] = static_cast<double>(scene.mesh.triangles().size());
}

// The default-options viewpoint model of `mesh_name`'s scene mesh, built once per mesh.
const SparseViewpointModel& ViewpointModelFor(const std::string& mesh_name,
                                              const RayCaster& caster) {
  static std::map<std::string, std::unique_ptr<SparseViewpointModel>> models;
  std::unique_ptr<SparseViewpointModel>& model = models[mesh_name];
  if (model == nullptr) {
    model = std::make_unique<SparseViewpointModel>(SparseViewpointModel::Build(caster, {}));
  }
  return *model;
}

// The sparse viewpoint model's replacement of ExtractContour in the region rounds: the nearest
// viewpoint and its points projected (sparse_viewpoint_model.h).
void BM_ViewpointContour(benchmark::State& state, const std::string& mesh_name, int image_height) {
  const Scene scene = SceneFor(mesh_name, image_height);
  const RayCaster caster(scene.mesh);
  const SparseViewpointModel& model = ViewpointModelFor(mesh_name, caster);
  double points = 0.0;
  for (auto _ : state) {
    const std::vector<ProjectedContourPoint> contour =
        model.Project(model.Nearest(scene.cam_from_object), scene.camera, scene.cam_from_object);
    benchmark::DoNotOptimize(contour.data());
    points = static_cast<double>(contour.size());
  }
  state.counters["points"] = points;
  state.counters["tbb_threads"] = 1;
}

// Building the default model (2,562 viewpoints), once.
void BM_BuildViewpointModel(benchmark::State& state, const std::string& mesh_name, int threads) {
  const Scene scene = SceneFor(mesh_name, 512);
  const RayCaster caster(scene.mesh);
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);
  double points = 0.0;
  for (auto _ : state) {
    const SparseViewpointModel model = SparseViewpointModel::Build(caster, {});
    points = 0.0;
    for (int i = 0; i < model.size(); ++i) points += model.viewpoint(i).points.size();
  }
  state.counters["points"] = points;
  state.counters["tbb_threads"] = threads;
}

void RegisterAll() {
  for (const std::string mesh : {"torus10k", "spool"}) {
    for (const int height : {512, 1024}) {
      const std::string size = height == 512 ? "640x512" : "1280x1024";
      for (const int threads : {1, 2}) {
        const std::string suffix = "/threads:" + std::to_string(threads);
        for (const bool full_image : {false, true}) {
          for (const bool reuse : {false, true}) {
            const std::string name = "Render/" + mesh + "/" + size +
                                     (full_image ? "/image" : "/bbox") + (reuse ? "/reuse" : "") +
                                     suffix;
            benchmark::RegisterBenchmark(name.c_str(), BM_Render, mesh, height, full_image, reuse,
                                         threads)
                ->UseRealTime()
                ->Unit(benchmark::kMillisecond);
          }
        }
        benchmark::RegisterBenchmark(("ExtractContour/" + mesh + "/" + size + suffix).c_str(),
                                     BM_ExtractContour, mesh, height, threads)
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
      }
      benchmark::RegisterBenchmark(("ViewpointContour/" + mesh + "/" + size + "/threads:1").c_str(),
                                   BM_ViewpointContour, mesh, height)
          ->Unit(benchmark::kMillisecond);
    }
    for (const int threads : {1, 2}) {
      benchmark::RegisterBenchmark(
          ("BuildViewpointModel/" + mesh + "/threads:" + std::to_string(threads)).c_str(),
          BM_BuildViewpointModel, mesh, threads)
          ->UseRealTime()
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
  }
}

}  // namespace
}  // namespace bcot

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  bcot::RegisterAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

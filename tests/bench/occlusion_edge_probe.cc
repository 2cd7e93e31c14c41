// The edge stage's lines across the occlusion contours inside the silhouette
// (`edge.occlusion_contours`, occlusion_contour.h), measured at the true pose of a sequence
// with ground truth (`bcot synth` or scripts/pbr_synth.sh output): how many there are beside
// the silhouette's own lines, and where they find the image step (μ, px, + = towards the far
// surface; 0 at the true pose for an unbiased measurement).
//
// Usage: occlusion_edge_probe --sequence DIR [--config FILE] [--set key=value]... [--frames N]
// Prints per camera: the silhouette's lines and the occlusion contours' lines measured, and the
// median, interquartile range and 10/90 % quantiles of μ of either kind.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/image_io.h"
#include "bcot/optim/edge_lines.h"
#include "bcot/optim/silhouette.h"
#include "bcot/render/ray_caster.h"
#include "ground_truth_sequence.h"

namespace {

int Fail(const std::string& message) {
  std::fprintf(stderr, "occlusion_edge_probe: %s\n", message.c_str());
  return 1;
}

// "n, median, IQR, p10, p90" of `offsets` (px).
std::string Quantiles(std::vector<double> offsets) {
  if (offsets.empty()) return "0 lines";
  std::sort(offsets.begin(), offsets.end());
  auto at = [&](double q) { return offsets[static_cast<size_t>(q * (offsets.size() - 1))]; };
  char text[160];
  std::snprintf(text, sizeof(text), "%6zu lines, median %+.3f, IQR %.3f, p10 %+.2f, p90 %+.2f",
                offsets.size(), at(0.5), at(0.75) - at(0.25), at(0.1), at(0.9));
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bcot;
  CLI::App app{"Edge lines across occlusion contours at the true pose"};
  std::string sequence_dir, config_path = std::string(BCOT_SOURCE_DIR) + "/configs/annotate.yaml";
  std::vector<std::string> overrides;
  int max_frames = 20;
  app.add_option("--sequence", sequence_dir, "Sequence with gt/")->required();
  app.add_option("--config", config_path, "Annotate config (edge.* options)");
  app.add_option("--set", overrides, "key=value override of the config (repeatable)");
  app.add_option("--frames", max_frames, "Frames measured from the first (0 = all)");
  CLI11_PARSE(app, argc, argv);

  const StatusOr<AnnotateOptions> options = ReadAnnotateOptions(config_path, overrides);
  if (!options.ok()) return Fail(options.status().message());
  const StatusOr<bench::GroundTruthSequence> loaded = bench::LoadGroundTruthSequence(sequence_dir);
  if (!loaded.ok()) return Fail(loaded.status().message());
  const Sequence& sequence = loaded->sequence;
  const RayCaster caster(loaded->mesh);
  // As edge_bias_probe: the lines decoded as sRGB unless the config names a response.
  EdgeLineOptions silhouette_only = options->tracker.frame.edge.lines;
  if (!silhouette_only.response.IsResolved()) silhouette_only.response = ImageResponse();
  silhouette_only.occlusion_contours = false;
  silhouette_only.crease_contours = false;
  EdgeLineOptions with_occlusion = silhouette_only;
  with_occlusion.occlusion_contours = true;
  const int frames =
      max_frames > 0 ? std::min(max_frames, sequence.num_frames) : sequence.num_frames;
  for (int v = 0; v < sequence.rig.size(); ++v) {
    const RigCamera& camera = sequence.rig[v];
    std::vector<double> silhouette_offsets, occlusion_offsets;
    for (int f = 0; f < frames; ++f) {
      const StatusOr<cv::Mat3b> image = ReadCameraImage(sequence.image_paths[v][f], camera.camera);
      if (!image.ok()) return Fail(image.status().message());
      const Eigen::Isometry3d rig_from_objcentre = loaded->RigFromObjcentre(f);
      const Silhouette silhouette = RenderSilhouette(
          caster, camera.camera, camera.cam_from_rig * loaded->truth[f], ContourOptions{});
      const StatusOr<CorrespondenceLines> outer =
          BuildEdgeLines(caster, camera.camera, camera.cam_from_rig, rig_from_objcentre, *image,
                         silhouette, silhouette_only);
      const StatusOr<CorrespondenceLines> both =
          BuildEdgeLines(caster, camera.camera, camera.cam_from_rig, rig_from_objcentre, *image,
                         silhouette, with_occlusion);
      if (!outer.ok()) return Fail(outer.status().message());
      if (!both.ok()) return Fail(both.status().message());
      // BuildEdgeLines puts the silhouette's lines first, the occlusion contours' after them.
      for (size_t i = 0; i < both->lines.size(); ++i) {
        (i < outer->lines.size() ? silhouette_offsets : occlusion_offsets)
            .push_back(both->lines[i].mean_px);
      }
    }
    std::printf("%-6s silhouette %s\n", camera.camera.name.c_str(),
                Quantiles(silhouette_offsets).c_str());
    std::printf("%-6s occlusion  %s\n", camera.camera.name.c_str(),
                Quantiles(occlusion_offsets).c_str());
  }
  return 0;
}

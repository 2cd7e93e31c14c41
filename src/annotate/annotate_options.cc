#include "bcot/annotate/annotate_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bcot {
namespace {

template <typename Value>
using Choices = std::vector<std::pair<std::string, Value>>;

const Choices<ColorModelKind> kColorKinds = {{"global", ColorModelKind::kGlobal},
                                             {"local", ColorModelKind::kLocal}};
const Choices<MotionModel> kMotionModels = {{"velocity", MotionModel::kConstantVelocity},
                                            {"acceleration", MotionModel::kConstantAcceleration}};

void DeclareFrame(OptionSchema<AnnotateOptions>* s) {
  s->Add(
       "frame.rounds", [](auto& o) -> auto& { return o.tracker.frame.rounds; }, "",
       "full-resolution rounds per frame, each re-renders the templates")
      .Range(AtLeast(1));
  s->Add(
       "frame.iterations", [](auto& o) -> auto& { return o.tracker.frame.iterations; }, "",
       "Ceres iterations per round (and per coarse level)")
      .Range(AtLeast(1));
  s->Add(
       "frame.pyramid_levels", [](auto& o) -> auto& { return o.tracker.frame.pyramid_levels; }, "",
       "image pyramid levels; the coarse ones run once before the rounds")
      .Range(Closed(1, 6));
  s->Add(
       "frame.coarse_rounds", [](auto& o) -> auto& { return o.tracker.frame.coarse_rounds; }, "",
       "re-rendered solves per coarse level")
      .Range(AtLeast(1));
  s->Add(
      "frame.coarse_check", [](auto& o) -> auto& { return o.tracker.frame.coarse_check; }, "",
      "keep the coarse levels' pose only if the full-resolution energy is lower there than at "
      "the start");
  s->Add(
       "frame.coarse_check_min_shift_px",
       [](auto& o) -> auto& { return o.tracker.frame.coarse_check_min_shift_px; }, "px",
       "run the coarse check only when the coarse levels moved the object's box this far")
      .Range(NonNegative());
  s->Add(
       "frame.damping_translation_mm",
       [](auto& o) -> auto& { return o.tracker.frame.damping_translation_mm; }, "mm",
       "per-solve damping towards the template's pose (0 = off)")
      .Range(NonNegative());
  s->Add(
       "frame.damping_rotation_deg",
       [](auto& o) -> auto& { return o.tracker.frame.damping_rotation_deg; }, "deg",
       "per-solve rotation damping (0 = off)")
      .Range(NonNegative());
  s->Add(
       "frame.round_tolerance_deg",
       [](auto& o) -> auto& { return o.tracker.frame.round_tolerance_deg; }, "deg",
       "rounds stop once one moves the pose less than this ...")
      .Range(NonNegative());
  s->Add(
       "frame.round_tolerance_mm",
       [](auto& o) -> auto& { return o.tracker.frame.round_tolerance_mm; }, "mm", "... and this")
      .Range(NonNegative());
  s->Add(
       "frame.num_threads", [](auto& o) -> auto& { return o.tracker.frame.num_threads; }, "",
       "Ceres threads per frame")
      .Range(AtLeast(1));
}

void DeclareRegionAndCost(OptionSchema<AnnotateOptions>* s) {
  s->Add(
       "region.band_px", [](auto& o) -> auto& { return o.tracker.frame.region.band_px; }, "px",
       "half-width of the band around the projected contour")
      .Range(Positive());
  s->Add(
       "region.stride_px", [](auto& o) -> auto& { return o.tracker.frame.region.stride_px; }, "px",
       "every n-th band pixel in x and y")
      .Range(AtLeast(1));
  s->Add(
       "region.contour_sample_spacing_px",
       [](auto& o) -> auto& { return o.tracker.frame.region.contour.sample_spacing_px; }, "px",
       "spacing of the template's contour samples")
      .Range(Closed(0.05, 1000));
  s->Add(
       "region.contour_precision_px",
       [](auto& o) -> auto& { return o.tracker.frame.region.contour.precision_px; }, "px",
       "sub-pixel precision of the contour bisection")
      .Range(Closed(1e-6, 0.5));
  s->Add(
       "region.contour_coarse_step_px",
       [](auto& o) -> auto& { return o.tracker.frame.region.contour.coarse_step_px; }, "px",
       "grid step of the coarse mask contours are traced on")
      .Range(AtLeast(1));
  s->AddChoice(
      "cost.form", [](auto& o) -> auto& { return o.tracker.frame.cost.form; },
      Choices<RegionResidualForm>{{"sqrt_energy", RegionResidualForm::kSqrtEnergy},
                                  {"irls", RegionResidualForm::kIrls}},
      "residual form of the region energy");
  s->Add(
       "cost.heaviside_slope",
       [](auto& o) -> auto& { return o.tracker.frame.cost.heaviside_slope; }, "px",
       "slope of the smoothed Heaviside of the signed distance")
      .Range(Positive());
  s->Add(
       "cost.probability_floor",
       [](auto& o) -> auto& { return o.tracker.frame.cost.probability_floor; }, "",
       "lower bound of the pixel likelihood")
      .Range(Open(0, 0.5));
  s->AddChoice(
      "cost.energy", [](auto& o) -> auto& { return o.tracker.frame.energy; },
      Choices<RegionEnergy>{{"dense", RegionEnergy::kDense},
                            {"sparse", RegionEnergy::kSparse},
                            {"combined", RegionEnergy::kCombined}},
      "dense (eq. 6 band), sparse (correspondence lines) or both");
}

void DeclareLines(OptionSchema<AnnotateOptions>* s) {
  s->Add(
       "lines.num_lines", [](auto& o) -> auto& { return o.tracker.frame.lines.num_lines; }, "",
       "correspondence lines per view, evenly spaced along the contour")
      .Range(AtLeast(1));
  s->Add(
       "lines.scale_px", [](auto& o) -> auto& { return o.tracker.frame.lines.scale_px; }, "px",
       "sample spacing along a line (level 0; x2^l coarser)")
      .Range(Positive());
  s->Add(
       "lines.half_length_px",
       [](auto& o) -> auto& { return o.tracker.frame.lines.half_length_px; }, "px",
       "extent on each side of the contour point")
      .Check([](const AnnotateOptions& o) {
        return o.tracker.frame.lines.half_length_px > o.tracker.frame.lines.scale_px
                   ? ""
                   : "must be > scale_px";
      });
  s->Add(
       "lines.min_side_px", [](auto& o) -> auto& { return o.tracker.frame.lines.min_side_px; },
       "px", "shorter sides reject the line")
      .Range(NonNegative());
  s->Add(
       "lines.slope_px", [](auto& o) -> auto& { return o.tracker.frame.lines.slope_px; }, "px",
       "slope of the smoothed step h_f")
      .Range(Positive());
  s->Add(
       "lines.amplitude", [](auto& o) -> auto& { return o.tracker.frame.lines.amplitude; }, "",
       "amplitude of the smoothed step h_f")
      .Range(Open(0, 0.5));
  s->Add(
       "lines.hypothesis_subdivisions",
       [](auto& o) -> auto& { return o.tracker.frame.lines.hypothesis_subdivisions; }, "",
       "contour hypotheses per sample spacing")
      .Range(AtLeast(1));
  s->Add(
       "lines.min_sigma_px", [](auto& o) -> auto& { return o.tracker.frame.lines.min_sigma_px; },
       "px", "floor of a line's standard deviation")
      .Range(Positive());
  s->Add(
       "lines.max_sigma_px", [](auto& o) -> auto& { return o.tracker.frame.lines.max_sigma_px; },
       "px", "wider distributions are ambiguous: rejected")
      .Check([](const AnnotateOptions& o) {
        return o.tracker.frame.lines.max_sigma_px > o.tracker.frame.lines.min_sigma_px
                   ? ""
                   : "must be > min_sigma_px";
      });
  s->Add(
       "lines.weight", [](auto& o) -> auto& { return o.tracker.frame.lines.weight; }, "",
       "sparse energy weight (relative to dense when combined)")
      .Range(NonNegative())
      .Check([](const AnnotateOptions& o) {
        return o.tracker.frame.energy != RegionEnergy::kDense && o.tracker.frame.lines.weight == 0
                   ? "must be > 0 when the sparse energy is used"
                   : "";
      });
  s->Add(
       "lines.viewpoint_model",
       [](auto& o) -> auto& { return o.tracker.frame.lines_from_viewpoint_model; }, "",
       "region rounds' lines along a sparse viewpoint model (each viewpoint rendered once, when "
       "first used), without a render per round (cost.energy sparse only; "
       "docs/sparse_viewpoint_model.md)")
      .Check([](const AnnotateOptions& o) {
        return o.tracker.frame.lines_from_viewpoint_model &&
                       o.tracker.frame.energy != RegionEnergy::kSparse
                   ? "must be false unless cost.energy is sparse"
                   : "";
      });
  s->Add(
       "lines.viewpoint_model_two_views",
       [](auto& o) -> auto& { return o.tracker.viewpoint_model_for_two_views; }, "",
       "tracked frames that two or more cameras see: region rounds with the sparse energy along "
       "the sparse viewpoint model and colours learned along its contour, no render; frames one "
       "camera sees keep cost.energy and color.samples (docs/sparse_viewpoint_model.md)")
      .Check([](const AnnotateOptions& o) {
        return o.tracker.viewpoint_model_for_two_views && o.tracker.frame.lines_from_viewpoint_model
                   ? "must be false when lines.viewpoint_model is true (the model on every frame)"
                   : "";
      });
}

void DeclareEdge(OptionSchema<AnnotateOptions>* s) {
  s->Add(
      "edge.enabled", [](auto& o) -> auto& { return o.tracker.frame.edge.enabled; }, "",
      "final edge-alignment stage on the image's own blurred step along the contour normals");
  s->Add(
       "edge.rounds", [](auto& o) -> auto& { return o.tracker.frame.edge.rounds; }, "",
       "re-rendered edge solves")
      .Range(AtLeast(1));
  s->Add(
       "edge.iterations", [](auto& o) -> auto& { return o.tracker.frame.edge.iterations; }, "",
       "Ceres iterations per edge solve")
      .Range(AtLeast(1));
  s->AddChoice(
      "edge.robust_loss", [](auto& o) -> auto& { return o.tracker.frame.edge.robust_loss; },
      Choices<EdgeRobustLoss>{{"huber", EdgeRobustLoss::kHuber},
                              {"cauchy", EdgeRobustLoss::kCauchy},
                              {"tukey", EdgeRobustLoss::kTukey}},
      "robust loss of each edge line's residual");
  s->Add(
       "edge.robust_scale", [](auto& o) -> auto& { return o.tracker.frame.edge.robust_scale; },
       "sigma", "threshold of the edge residuals' robust loss")
      .Range(Positive());
  s->Add(
       "edge.redescending_rounds",
       [](auto& o) -> auto& { return o.tracker.frame.edge.redescending_rounds; }, "",
       "re-rendered edge solves after edge.rounds, with Tukey's loss on each line")
      .Range(AtLeast(0));
  s->Add(
       "edge.redescending_scale",
       [](auto& o) -> auto& { return o.tracker.frame.edge.redescending_scale; }, "sigma",
       "threshold of the redescending rounds' Tukey loss")
      .Range(Positive());
  s->Add(
       "edge.line_spacing_px",
       [](auto& o) -> auto& { return o.tracker.frame.edge.lines.line_spacing_px; }, "px",
       "one edge line per this length of contour, evenly spaced along it")
      .Range(Positive());
  s->Add(
       "edge.num_lines", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.num_lines; }, "",
       "at most this many edge lines per view")
      .Range(AtLeast(1));
  s->Add(
      "edge.occlusion_contours",
      [](auto& o) -> auto& { return o.tracker.frame.edge.lines.occlusion_contours; }, "",
      "also measure edges along the occlusion contours inside the silhouette");
  s->Add(
      "edge.crease_contours",
      [](auto& o) -> auto& { return o.tracker.frame.edge.lines.crease_contours; }, "",
      "also measure edges along the mesh's creases inside the silhouette");
  s->Add(
       "edge.crease_min_angle_deg",
       [](auto& o) -> auto& { return o.tracker.frame.edge.lines.crease_min_angle_deg; }, "deg",
       "a mesh edge is a crease when its two faces' normals differ by more than this")
      .Range(Open(0.0, 180.0));
  s->Add(
       "edge.search_px", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.search_px; },
       "px", "the edge is looked for within this distance of the contour")
      .Range(Positive());
  s->Add(
       "edge.min_sigma_px",
       [](auto& o) -> auto& { return o.tracker.frame.edge.lines.min_sigma_px; }, "px",
       "floor of an edge line's standard deviation")
      .Range(Positive());
  s->Add(
       "edge.window_px", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.window_px; },
       "px", "half-length of the profile sampled along each line")
      .Range(Closed(2, 50));
  s->Add(
       "edge.step_px", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.step_px; }, "px",
       "sample spacing of the profile along each line")
      .Range(Positive());
  s->Add(
       "edge.fit_half_px", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.fit_half_px; },
       "px", "half-width of the blurred-step fit around the steepest point")
      .Check([](const AnnotateOptions& o) {
        // FitEdgeProfile needs at least 8 samples in its window.
        const EdgeLineOptions& lines = o.tracker.frame.edge.lines;
        return lines.fit_half_px >= 3.5 * lines.step_px && lines.fit_half_px <= lines.window_px
                   ? ""
                   : "must be in [3.5 × edge.step_px, edge.window_px] (the fit needs 8 samples)";
      });
  s->Add(
       "edge.min_snr", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.min_snr; }, "",
       "smallest step in units of the profile fit's residual standard deviation")
      .Range(NonNegative());
  s->Add(
       "edge.clip_level", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.clip_level; },
       "",
       "linear level (1 = full scale) from which a colour sample counts as clipped by the "
       "sensor and is left out of that line's contrast (> 1 = never)")
      .Range(Closed(0.5, 2));
  s->Add(
      "edge.saturated_level_fit",
      [](auto& o) -> auto& { return o.tracker.frame.edge.lines.saturated_level_fit; }, "",
      "with subsampled chroma, fit how far above full scale a channel clipped on the object's "
      "side is, for the codec's simulation (false: drawn at full scale)");
  s->AddChoice(
       "edge.response", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.response.kind; },
       Choices<ImageResponse::Kind>{{"srgb", ImageResponse::Kind::kSrgb},
                                    {"gamma", ImageResponse::Kind::kGamma},
                                    {"log", ImageResponse::Kind::kLog},
                                    {"table", ImageResponse::Kind::kTable},
                                    {"auto", ImageResponse::Kind::kAuto}},
       "the cameras' response, how 8-bit codes map to linear light (edge stage and quality "
       "check): srgb, gamma with edge.gamma (1 = a linear machine-vision camera), log with "
       "edge.log_stops (log-encoding cameras, film-like views), table (edge.response_file), or "
       "auto (estimated from the first frame: image_response.yaml)")
      .Check([](const AnnotateOptions& o) -> std::string {
        const ImageResponse& response = o.tracker.frame.edge.lines.response;
        return response.kind == ImageResponse::Kind::kTable && response.table.empty()
                   ? "table needs edge.response_file"
                   : "";
      });
  s->AddChoice(
      "edge.chroma_sampling", [](auto& o) -> auto& { return o.chroma_sampling; },
      Choices<ChromaSamplingSetting>{{"auto", ChromaSamplingSetting::kAuto},
                                     {"4:4:4", ChromaSamplingSetting::kFull},
                                     {"4:2:0", ChromaSamplingSetting::kJpeg420},
                                     {"4:2:2", ChromaSamplingSetting::kJpeg422}},
      "how the frames store colour; JPEG's subsampled chroma (4:2:0, 4:2:2) moves edges and the "
      "edge stage takes the move off: auto (each camera's first frame: a JPEG's header, else "
      "4:4:4), or set (frames converted from 4:2:0 JPEG to PNG keep its damage)");
  s->Add(
      "edge.chroma_restoration",
      [](auto& o) -> auto& { return o.tracker.frame.edge.chroma_restoration.enabled; }, "",
      "the edge stage's last round measures frames with subsampled chroma on a copy whose chroma "
      "is brought back to full resolution from the luma around the object, as 4:4:4; false = "
      "the decoded frames and a per-line correction (the region stage reads them either way)");
  s->Add(
       "edge.chroma_restoration_radius_px",
       [](auto& o) -> auto& { return o.tracker.frame.edge.chroma_restoration.radius_px; }, "px",
       "window radius of the chroma restoration's local fits")
      .Range(Closed(1, 16));
  s->Add(
       "edge.chroma_restoration_degree",
       [](auto& o) -> auto& { return o.tracker.frame.edge.chroma_restoration.degree; }, "",
       "degree of the chroma restoration's polynomial in luma")
      .Range(Closed(1, 4));
  s->Add(
       "edge.chroma_restoration_ridge",
       [](auto& o) -> auto& { return o.tracker.frame.edge.chroma_restoration.ridge_luma_codes2; },
       "codes^2",
       "ridge on the chroma restoration's polynomial coefficients, in luma codes squared (a "
       "window whose luma varies by less keeps its mean chroma)")
      .Range(Positive());
  s->Add(
       "edge.chroma_restoration_isophote_sigma_px",
       [](auto& o) -> auto& { return o.tracker.frame.edge.chroma_restoration.isophote_sigma_px; },
       "px",
       "the chroma restoration reads the luma averaged along its isophotes by a Gaussian of this "
       "sigma (0 = each pixel's own luma)")
      .Range(Closed(0.0, 4.0));
  s->Add(
       "edge.chroma_restoration_hue_slope",
       [](auto& o) -> auto& { return o.tracker.frame.edge.chroma_restoration.hue_slope_codes; },
       "codes/code",
       "where chroma changes more than this per unit of luma the decoded chroma is kept "
       "(weight s0^2 / (s0^2 + slope^2) of the restored one; 0 = restored everywhere)")
      .Range(AtLeast(0.0));
  s->Add(
       "edge.gamma", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.response.gamma; }, "",
       "exponent of edge.response: gamma, linear = (code / 255)^gamma")
      .Range(Closed(ImageResponse::kMinGamma, ImageResponse::kMaxGamma));
  s->Add(
       "edge.log_stops",
       [](auto& o) -> auto& { return o.tracker.frame.edge.lines.response.log_stops; }, "stops",
       "stops below white the codes 1..255 span with edge.response: log, linear = "
       "2^(log_stops·(code / 255 − 1))")
      .Range(Closed(ImageResponse::kMinLogStops, ImageResponse::kMaxLogStops));
  s->AddCustom(
      "edge.response_file", [](auto& o) -> auto& { return o.tracker.frame.edge.lines.response; },
      [](YamlMap& map, const std::string& base_dir, ImageResponse* response) -> Status {
        std::string file;
        BCOT_RETURN_IF_ERROR(map.Get("response_file", &file));
        if (file.empty()) {  // none (what the resolved config writes without a table)
          response->table_file.clear();
          response->table.clear();
          return Status::Ok();
        }
        file = option_internal::ResolvePath(base_dir, file);
        StatusOr<std::vector<float>> table = ReadResponseTable(file);
        if (!table.ok()) return map.Error("response_file", table.status().message());
        response->table_file = file;
        response->table = std::move(table).value();
        return Status::Ok();
      },
      [](YAML::Emitter& out, const ImageResponse& response) { out << response.table_file; },
      [](const ImageResponse& response) { return response.table_file; },
      "file of the measured response of edge.response: table: the linear value of codes 0..255 "
      "(docs/camera_response.md)");
}

void DeclareColorAndTracker(OptionSchema<AnnotateOptions>* s) {
  s->AddChoice(
      "color.kind", [](auto& o) -> auto& { return o.tracker.color.kind; }, kColorKinds,
      "colour model of the coarse levels and of capture (local: RBOT histograms)");
  s->AddChoice(
      "color.refine_kind", [](auto& o) -> auto& { return o.tracker.color.refine_kind; },
      Choices<std::optional<ColorModelKind>>{{"same", std::nullopt},
                                             {"global", ColorModelKind::kGlobal},
                                             {"local", ColorModelKind::kLocal}},
      "colour model of the full-resolution rounds (same = kind)");
  s->Add(
       "color.bins_per_channel", [](auto& o) -> auto& { return o.tracker.color.bins_per_channel; },
       "", "histogram bins per colour channel")
      .Check([](const AnnotateOptions& o) {
        const int bins = o.tracker.color.bins_per_channel;
        return bins >= 1 && bins <= 256 && 256 % bins == 0 ? "" : "must divide 256";
      });
  s->Add(
       "color.learning_rate_foreground",
       [](auto& o) -> auto& { return o.tracker.color.learning_rate_foreground; }, "",
       "weight of a new foreground histogram")
      .Range(LeftOpen(0, 1));
  s->Add(
       "color.learning_rate_background",
       [](auto& o) -> auto& { return o.tracker.color.learning_rate_background; }, "",
       "weight of a new background histogram")
      .Range(LeftOpen(0, 1));
  s->Add(
       "color.background_band_px",
       [](auto& o) -> auto& { return o.tracker.color.background_band_px; }, "px",
       "background pixels are sampled within this distance of the silhouette")
      .Range(Positive());
  s->Add(
       "color.sample_margin_px", [](auto& o) -> auto& { return o.tracker.color.sample_margin_px; },
       "px", "no pixel this close to the contour teaches the histograms")
      .Range(NonNegative());
  s->Add(
       "color.local_region_radius_px",
       [](auto& o) -> auto& { return o.tracker.color.local_region_radius_px; }, "px",
       "radius of a local histogram region")
      .Range(Positive());
  s->Add(
       "color.local_region_spacing_px",
       [](auto& o) -> auto& { return o.tracker.color.local_region_spacing_px; }, "px",
       "spacing of the local regions along the contour")
      .Range(Positive());
  s->Add(
       "color.local_anchor_fraction",
       [](auto& o) -> auto& { return o.tracker.color.local_anchor_fraction; }, "",
       "a contour point reuses the local region anchored within this share of the object's "
       "diameter")
      .Range(LeftOpen(0, 1));
  s->AddChoice(
      "color.local_background_memory",
      [](auto& o) -> auto& { return o.tracker.color.local_background_memory; },
      Choices<LocalBackgroundMemory>{{"image", LocalBackgroundMemory::kImage},
                                     {"object", LocalBackgroundMemory::kObject}},
      "what a local region's background histogram keeps when the region moves in the image "
      "(image: only where its old and new discs overlap; object: all of it, as RBOT)");
  s->AddChoice(
       "color.samples", [](auto& o) -> auto& { return o.tracker.color_samples; },
       Choices<ColorSampleSource>{{"silhouette", ColorSampleSource::kSilhouette},
                                  {"viewpoint_model", ColorSampleSource::kViewpointModel}},
       "where the colour models learn after each frame: the silhouette rendered at the pose, or "
       "along the sparse viewpoint model's contour without a render (lines.viewpoint_model only)")
      .Check([](const AnnotateOptions& o) {
        return o.tracker.color_samples == ColorSampleSource::kViewpointModel &&
                       !o.tracker.frame.lines_from_viewpoint_model
                   ? "must be silhouette unless lines.viewpoint_model is true"
                   : "";
      });
  s->Add(
       "tracker.velocity_prediction",
       [](auto& o) -> auto& { return o.tracker.velocity_prediction; }, "",
       "start each frame at the last pose + this fraction of the last motion")
      .Range(Closed(0, 1));
  s->Add(
       "tracker.bootstrap_passes", [](auto& o) -> auto& { return o.tracker.bootstrap_passes; }, "",
       "frame 0: at most this many {learn colours, solve} passes")
      .Range(AtLeast(1));
  s->Add(
       "tracker.bootstrap_rounds", [](auto& o) -> auto& { return o.tracker.bootstrap_rounds; }, "",
       "full-resolution rounds of each bootstrap solve of frame 0 (0 = frame.rounds)")
      .Range(NonNegative());
  s->Add(
       "tracker.bootstrap_converged_deg",
       [](auto& o) -> auto& { return o.tracker.bootstrap_converged_deg; }, "deg",
       "... stopping once a pass moved the pose less than this")
      .Range(Positive());
  s->Add(
       "tracker.bootstrap_converged_mm",
       [](auto& o) -> auto& { return o.tracker.bootstrap_converged_mm; }, "mm",
       "... and this (object centre)")
      .Range(Positive());
}

void DeclareViewsAndWindow(OptionSchema<AnnotateOptions>* s) {
  s->Add(
       "views.cameras", [](auto& o) -> auto& { return o.views.cameras; }, "",
       "rig cameras to use, in this order ([] = all)")
      .Check([](const AnnotateOptions& o) -> std::string {
        const std::vector<std::string>& cameras = o.views.cameras;
        for (size_t i = 0; i < cameras.size(); ++i) {
          for (size_t j = 0; j < i; ++j) {
            if (cameras[i] == cameras[j]) {
              return fmt::format("must not list camera '{}' twice", cameras[i]);
            }
          }
        }
        return "";
      });
  s->Add(
       "views.weights", [](auto& o) -> auto& { return o.views.weights; }, "",
       "one weight per selected camera (eq. 8; [] = all 1)")
      .Range(NonNegative())
      .Check([](const AnnotateOptions& o) -> std::string {
        const ViewSelection& v = o.views;
        if (!v.weights.empty() &&
            std::none_of(v.weights.begin(), v.weights.end(), [](double w) { return w > 0; })) {
          return "must hold at least one weight > 0 (all views would be ignored)";
        }
        if (v.weights.empty() || v.cameras.empty() || v.weights.size() == v.cameras.size()) {
          return "";
        }
        return fmt::format(
            "must list one weight per camera (weights has {} entries for {} cameras)",
            v.weights.size(), v.cameras.size());
      });
  s->Add(
      "symmetry.detect", [](auto& o) -> auto& { return o.symmetry.detect; }, "",
      "find whether the mesh is a body of revolution; if so, the angle about its axis (which no "
      "image observes) is kept where tracking starts");
  s->Add(
       "symmetry.tolerance", [](auto& o) -> auto& { return o.symmetry.detection.tolerance; }, "",
       "largest mean silhouette change under a turn about the axis, as a fraction of the "
       "object's diameter, that still counts as symmetric")
      .Range(Open(0, 0.1));
  s->Add(
      "window.enabled", [](auto& o) -> auto& { return o.window.enabled; }, "",
      "refine the per-frame poses in sliding temporal windows");
  s->Add(
       "window.size", [](auto& o) -> auto& { return o.window.size; }, "frames",
       "frames per window (0 = the whole sequence)")
      .Check([](const AnnotateOptions& o) {
        return o.window.size == 0 || o.window.size >= 3 ? "" : "must be 0 (whole sequence) or >= 3";
      });
  s->Add(
       "window.overlap", [](auto& o) -> auto& { return o.window.overlap; }, "frames",
       "frames shared by consecutive windows")
      .Range(NonNegative())
      .Check([](const AnnotateOptions& o) -> std::string {
        const WindowProblemOptions& w = o.window;
        if (w.size == 0 || w.overlap <= w.size - 1) return "";
        return fmt::format("must be in [0, size − 1 = {}]", std::max(w.size - 1, 0));
      });
  s->Add(
       "window.iterations", [](auto& o) -> auto& { return o.window.iterations; }, "",
       "Ceres iterations per window")
      .Range(AtLeast(1));
  s->AddChoice(
      "window.prior", [](auto& o) -> auto& { return o.window.prior; },
      Choices<MotionPriorForm>{{"se3", MotionPriorForm::kSe3},
                               {"decoupled", MotionPriorForm::kDecoupled}},
      "motion prior over SE(3) or decoupled translation and rotation");
  s->AddChoice(
      "window.translation_model", [](auto& o) -> auto& { return o.window.translation_model; },
      kMotionModels, "constant velocity or acceleration of the object centre");
  s->AddChoice(
      "window.rotation_model", [](auto& o) -> auto& { return o.window.rotation_model; },
      kMotionModels, "constant body angular velocity or acceleration");
  s->Add(
       "window.rotation_sigma_deg", [](auto& o) -> auto& { return o.window.rotation_sigma_deg; },
       "deg", "sigma of the rotation prior per axis [x, y, z]")
      .Range(Positive())
      .Elements({"x", "y", "z"});
  s->Add(
       "window.translation_sigma_mm",
       [](auto& o) -> auto& { return o.window.translation_sigma_mm; }, "mm",
       "sigma of the translation prior per axis [x, y, z]")
      .Range(Positive())
      .Elements({"x", "y", "z"});
  s->Add(
       "window.robust_translation_mm",
       [](auto& o) -> auto& { return o.window.robust_translation_mm; }, "mm",
       "Cauchy threshold of the translation prior: larger changes of motion are followed")
      .Range(NonNegative());
  s->Add(
       "window.robust_rotation_deg", [](auto& o) -> auto& { return o.window.robust_rotation_deg; },
       "deg", "Cauchy threshold of the rotation prior")
      .Range(NonNegative());
  s->Add(
      "window.adaptive_prior", [](auto& o) -> auto& { return o.window.adaptive_prior; }, "",
      "raise each window's prior sigmas to the motion's own change per frame, estimated from the "
      "per-frame poses (the sigmas above are then the floor)");
  s->Add(
      "window.edge_posterior", [](auto& o) -> auto& { return o.window.edge_posterior; }, "",
      "a frame refined by the edge stage enters the window as its edge pose posterior "
      "(false: its region terms)");
  s->Add(
       "window.keyframe_sigma_translation_mm",
       [](auto& o) -> auto& { return o.window.keyframe_sigma_translation_mm; }, "mm",
       "sigma of a keyframe's prior toward its hand-set pose, translation (keyframes.md)")
      .Range(Positive());
  s->Add(
       "window.keyframe_sigma_rotation_deg",
       [](auto& o) -> auto& { return o.window.keyframe_sigma_rotation_deg; }, "deg",
       "sigma of a keyframe's prior toward its hand-set pose, rotation")
      .Range(Positive());
  s->Add(
       "window.num_threads", [](auto& o) -> auto& { return o.window.num_threads; }, "",
       "Ceres threads per window")
      .Range(AtLeast(1));
}

OptionSchema<AnnotateOptions>* BuildAnnotateOptionSchema() {
  auto* s = new OptionSchema<AnnotateOptions>();
  DeclareFrame(s);
  DeclareRegionAndCost(s);
  DeclareLines(s);
  DeclareEdge(s);
  DeclareColorAndTracker(s);
  DeclareViewsAndWindow(s);
  s->Include(
      QualityOptionSchema(), [](auto& o) -> auto& { return o.quality; });
  return s;
}

// The optim layer's own checks, after the declared rules (which name locations): a rule added
// there but not declared here still stops a bad config, naming `source_name`.
Status LayerChecks(const AnnotateOptions& options, const std::string& source_name) {
  for (const Status& status : {options.tracker.Validate(), options.window.Validate(),
                               options.symmetry.detection.Validate()}) {
    if (!status.ok()) return Status::InvalidConfig(source_name + ": " + status.message());
  }
  return Status::Ok();
}

}  // namespace

AnnotateOptions::AnnotateOptions() {
  tracker.frame.rounds = 2;
  tracker.bootstrap_rounds = 5;
  tracker.frame.edge.lines.response = ImageResponse::Auto();
}

const OptionSchema<AnnotateOptions>& AnnotateOptionSchema() {
  static const OptionSchema<AnnotateOptions>* const schema = BuildAnnotateOptionSchema();
  return *schema;
}

Status AnnotateOptions::Validate() const {
  BCOT_RETURN_IF_ERROR(AnnotateOptionSchema().Validate(*this, nullptr));
  return LayerChecks(*this, "annotate options");
}

StatusOr<AnnotateOptions> ParseAnnotateOptions(const YAML::Node& root,
                                               const std::string& source_name) {
  AnnotateOptions options;
  OptionSources sources;
  const OptionSchema<AnnotateOptions>& schema = AnnotateOptionSchema();
  BCOT_RETURN_IF_ERROR(schema.Parse(root, source_name, "", &options, &sources));
  BCOT_RETURN_IF_ERROR(schema.Validate(options, &sources));
  BCOT_RETURN_IF_ERROR(LayerChecks(options, source_name));
  return options;
}

StatusOr<AnnotateOptions> ReadAnnotateOptions(const std::string& path,
                                              const std::vector<std::string>& overrides) {
  BCOT_ASSIGN_OR_RETURN(AnnotateOptions options, AnnotateOptionSchema().Read(path, overrides));
  BCOT_RETURN_IF_ERROR(LayerChecks(options, path.empty() ? kCommandLineSource : path));
  return options;
}

std::string FormatAnnotateOptions(const AnnotateOptions& options) {
  return AnnotateOptionSchema().Emit(options);
}

}  // namespace bcot

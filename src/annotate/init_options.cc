// InitializerOptions, the `bcot init` option schema, --click parsing and the request checks
// (declared in bcot/annotate/initializer.h).
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "bcot/annotate/initializer.h"
#include "bcot/core/file_util.h"

namespace bcot {
namespace {

void DeclareSearch(OptionSchema<InitOptions>* s) {
  s->Add(
       "init.grid_rotations", [](auto& o) -> auto& { return o.search.grid_rotations; }, "",
       "rotations of the super-Fibonacci orientation grid")
      .Range(AtLeast(100));
  s->Add(
       "init.search_width_px", [](auto& o) -> auto& { return o.search.search_width_px; }, "px",
       "views are resized to this width for the grid search")
      .Range(AtLeast(16));
  s->Add(
       "init.rank_width_px", [](auto& o) -> auto& { return o.search.rank_width_px; }, "px",
       "views are resized to this width to rank refined candidates")
      .Range(AtLeast(16));
  s->Add(
       "init.band_px", [](auto& o) -> auto& { return o.search.band_px; }, "px",
       "half-width of the energy's band at the scoring scale")
      .Range(Positive());
  s->Add(
       "init.bins_per_channel", [](auto& o) -> auto& { return o.search.bins_per_channel; }, "",
       "histogram bins per channel of the per-candidate colour models")
      .Check([](const InitOptions& o) {
        const int bins = o.search.bins_per_channel;
        return bins >= 1 && bins <= 256 && 256 % bins == 0 ? "" : "must divide 256";
      });
  s->Add(
       "init.background_band_px", [](auto& o) -> auto& { return o.search.background_band_px; },
       "px", "background colour samples within this distance of the silhouette")
      .Range(AtLeast(1));
  s->Add(
       "init.refine_candidates", [](auto& o) -> auto& { return o.search.refine_candidates; }, "",
       "best grid poses refined by the frame solver")
      .Range(AtLeast(1));
  s->Add(
       "init.distinct_deg", [](auto& o) -> auto& { return o.search.distinct_deg; }, "deg",
       "refined grid poses are at least this far apart")
      .Range(NonNegative());
  s->Add(
       "init.same_iou", [](auto& o) -> auto& { return o.search.same_iou; }, "",
       "refined poses whose silhouettes overlap more than this in every view are one answer")
      .Range(LeftOpen(0, 1));
  s->Add(
       "init.depth_steps", [](auto& o) -> auto& { return o.search.depth_steps; }, "",
       "one click, no --distance-mm: depths searched along the ray")
      .Range(AtLeast(2));
  s->Add(
       "init.depth_grid_rotations", [](auto& o) -> auto& { return o.search.depth_grid_rotations; },
       "", "... with this many rotations each")
      .Range(AtLeast(1));
  s->Add(
       "init.min_extent_fraction", [](auto& o) -> auto& { return o.search.min_extent_fraction; },
       "", "... over projected object sizes (of the shorter image side) from this ...")
      .Range(LeftOpen(0, 2));
  s->Add(
       "init.max_extent_fraction", [](auto& o) -> auto& { return o.search.max_extent_fraction; },
       "", "... to this")
      .Range(LeftOpen(0, 2))
      .Check([](const InitOptions& o) {
        return o.search.max_extent_fraction > o.search.min_extent_fraction
                   ? ""
                   : "must be > init.min_extent_fraction";
      });
  s->Add(
       "init.motion_frames", [](auto& o) -> auto& { return o.search.motion.frames; }, "",
       "no --click: frames sampled over the sequence for the background of the moving object")
      .Range(AtLeast(3));
  s->Add(
       "init.motion_width_px", [](auto& o) -> auto& { return o.search.motion.work_width_px; }, "px",
       "... views resized to this width")
      .Range(AtLeast(32));
  s->Add(
       "init.motion_threshold_sigmas",
       [](auto& o) -> auto& { return o.search.motion.threshold_sigmas; }, "",
       "... a pixel changed beyond this many robust sigmas of the change ...")
      .Range(Positive());
  s->Add(
       "init.motion_min_change", [](auto& o) -> auto& { return o.search.motion.min_change; }, "",
       "... and beyond this many grey levels")
      .Range(NonNegative());
  s->Add(
       "init.motion_min_area_fraction",
       [](auto& o) -> auto& { return o.search.motion.min_area_fraction; }, "",
       "... smallest changed region taken for the object (fraction of the image)")
      .Range(Open(0, 1));
}

OptionSchema<InitOptions>* BuildInitOptionSchema() {
  auto* s = new OptionSchema<InitOptions>();
  s->Include(
      AnnotateOptionSchema(), [](auto& o) -> auto& { return o.annotate; });
  DeclareSearch(s);
  return s;
}

std::string CameraNames(const Rig& rig) {
  std::string names;
  for (const RigCamera& camera : rig.cameras()) {
    names += (names.empty() ? "" : ", ") + camera.camera.name;
  }
  return names;
}

std::string ClickText(const ImageClick& click) {
  return fmt::format("--click {}:{},{}", click.camera, click.pixel.x(), click.pixel.y());
}

}  // namespace

Status InitializerOptions::Validate() const {
  InitOptions options;
  options.search = *this;
  return InitOptionSchema().Validate(options, nullptr);
}

Status InitOptions::Validate() const {
  BCOT_RETURN_IF_ERROR(InitOptionSchema().Validate(*this, nullptr));
  return annotate.Validate();
}

const OptionSchema<InitOptions>& InitOptionSchema() {
  static const OptionSchema<InitOptions>* const schema = BuildInitOptionSchema();
  return *schema;
}

StatusOr<InitOptions> ReadInitOptions(const std::string& path,
                                      const std::vector<std::string>& overrides) {
  BCOT_ASSIGN_OR_RETURN(InitOptions options, InitOptionSchema().Read(path, overrides));
  const Status layer = options.annotate.Validate();
  if (!layer.ok()) {
    return Status::InvalidConfig((path.empty() ? kCommandLineSource : path) + std::string(": ") +
                                 layer.message());
  }
  return options;
}

StatusOr<ImageClick> ParseImageClick(const std::string& text) {
  const Status malformed = Status::InvalidConfig(
      fmt::format("--click '{}': expected CAM:X,Y (camera name, then the pixel column and row "
                  "of the object's centre, e.g. cam0:320.5,241)",
                  text));
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) return malformed;
  const std::string pixel = text.substr(colon + 1);
  const size_t comma = pixel.find(',');
  if (comma == std::string::npos || pixel.find(',', comma + 1) != std::string::npos) {
    return malformed;
  }
  ImageClick click;
  click.camera = text.substr(0, colon);
  if (!ParseDouble(TrimWhitespace(pixel.substr(0, comma)), &click.pixel.x()) ||
      !ParseDouble(TrimWhitespace(pixel.substr(comma + 1)), &click.pixel.y()) ||
      !click.pixel.allFinite()) {
    return malformed;
  }
  return click;
}

Status CheckInitRequest(const Sequence& sequence, const InitRequest& request) {
  if (request.frame < 0 || request.frame >= sequence.num_frames) {
    return Status::InvalidConfig(fmt::format("--frame {}: the sequence has frames 0..{}",
                                             request.frame, sequence.num_frames - 1));
  }
  if (request.clicks.empty()) {
    return Status::InvalidConfig(
        "give --click CAM:X,Y (the object's centre) in at least one view, better two (without "
        "any, bcot init looks for the moving object)");
  }
  for (size_t i = 0; i < request.clicks.size(); ++i) {
    const ImageClick& click = request.clicks[i];
    const int index = sequence.rig.Find(click.camera);
    if (index < 0) {
      return Status::InvalidConfig(fmt::format("{}: no camera '{}' in the rig (cameras: {})",
                                               ClickText(click), click.camera,
                                               CameraNames(sequence.rig)));
    }
    for (size_t j = 0; j < i; ++j) {
      if (request.clicks[j].camera == click.camera) {
        return Status::InvalidConfig(
            fmt::format("{}: camera '{}' is clicked twice", ClickText(click), click.camera));
      }
    }
    const Camera& camera = sequence.rig[index].camera;
    if (!camera.InImage(click.pixel)) {
      return Status::InvalidConfig(
          fmt::format("{}: ({}, {}) is outside {}'s {}x{} image (columns -0.5..{}, rows -0.5..{})",
                      ClickText(click), click.pixel.x(), click.pixel.y(), camera.name, camera.width,
                      camera.height, camera.width - 0.5, camera.height - 0.5));
    }
  }
  if (request.distance_mm.has_value()) {
    if (!(*request.distance_mm > 0.0) || !std::isfinite(*request.distance_mm)) {
      return Status::InvalidConfig(
          fmt::format("--distance-mm {}: must be a finite distance > 0", *request.distance_mm));
    }
    if (request.clicks.size() > 1) {
      return Status::InvalidConfig(
          "--distance-mm applies to a single --click; with two or more clicks the centre is "
          "triangulated");
    }
  }
  return Status::Ok();
}

}  // namespace bcot

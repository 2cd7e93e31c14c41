// Options of `bcot capture` (configs/capture.yaml documents every key): which cameras, how
// they are set up and triggered, and how the recording runs.
//
// Sections: `aravis`, `trigger`, `cameras` (a list, one mapping per camera), `recording`
// (RecorderOptions). YAML keys are spelled as the fields; unknown keys are errors naming
// file:line:key. Camera settings that are absent are left as the camera has them. Every option
// is declared once, in CaptureOptionSchema (core/option_schema.h): parsing, --set, validation,
// the resolved file and `bcot capture --help` derive from it.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "bcot/capture/recorder.h"
#include "bcot/core/option_schema.h"
#include "bcot/core/status.h"

namespace bcot {

struct CaptureOptions {
  struct Aravis {
    // Also list Aravis' in-process fake camera ("Fake_1"): for tests and demos.
    bool enable_fake_interface = false;
    // Stream buffers per camera, [2, 256]: frames the host can hold while the recorder is
    // busy writing.
    int num_buffers = 16;
  } aravis;

  struct Trigger {
    // "software": the recorder triggers every camera once per frame set (TriggerSoftware);
    // "hardware": every camera waits for an edge on `source`, wired to one common signal
    //   (function generator, or one camera's strobe output);
    // "free_run": cameras stream at their frame rate, frames are paired by host timestamp.
    std::string mode = "software";
    // Trigger input line of hardware mode ("Line0", "Line1", ...); must be offered by every
    // camera.
    std::string source = "Line1";
  } trigger;

  struct Camera {
    // Folder and rig.yaml name; unique, usable as a folder name.
    std::string name;
    // Aravis device id (`arv-tool-0.8` lists them: "Vendor-Model-Serial", an IP address, or
    // "Fake_1").
    std::string device_id;
    // GenICam PixelFormat ("Mono8", "Mono16", "RGB8", "BGR8", "BayerRG8", ...); empty = keep.
    std::string pixel_format;
    // Exposure time (µs, > 0; auto exposure is switched off), gain (camera units, usually dB,
    // ≥ 0; auto gain off), acquisition frame rate (Hz, > 0). Absent = keep.
    std::optional<double> exposure_us;
    std::optional<double> gain;
    std::optional<double> frame_rate_hz;
    // Region of interest [x, y, width, height] (px); absent = keep.
    std::optional<std::array<int, 4>> region;
  };
  std::vector<Camera> cameras;

  RecorderOptions recording;

  // Every violation, kInvalidConfig.
  Status Validate() const;
};

const OptionSchema<CaptureOptions>& CaptureOptionSchema();

// Reads a config file strictly, applies `overrides` ("section.key=value"; the `cameras` list
// can only be set whole, e.g. `--set 'cameras=[{name: c0, device_id: Fake_1}]'`), resolves
// recording.rig_yaml against the config file's directory and validates.
StatusOr<CaptureOptions> ReadCaptureOptions(const std::string& path,
                                            const std::vector<std::string>& overrides = {});
StatusOr<CaptureOptions> ParseCaptureOptions(const YAML::Node& root, const std::string& source_name,
                                             const std::string& base_dir);

// Every option as YAML (absent camera settings stay absent); reads back the same.
std::string FormatCaptureOptions(const CaptureOptions& options);

}  // namespace bcot

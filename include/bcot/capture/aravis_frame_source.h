// Aravis cameras (GigE Vision, USB3 Vision, Aravis' fake cameras) as FrameSources.
//
// Compiled in when CMake finds aravis-0.8 (BCOT_HAVE_ARAVIS); otherwise every function
// reports that bcot was built without Aravis, so the rest of bcot builds and runs without a
// camera stack.
//
// Setup order per camera: pixel format, region, frame rate, exposure (auto off), gain (auto
// off), then the trigger (frame rate first: some cameras switch triggers off when the frame
// rate is set). Images are converted to CV_8UC1 (Mono8), CV_16UC1 (Mono10/12/14/16, unpacked)
// or CV_8UC3 BGR (RGB8, BGR8, 8-bit Bayer demosaiced).
//
// A source is used by one thread. Aravis' device list is process-wide: opening cameras from
// several threads at once is not supported.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bcot/capture/capture_options.h"
#include "bcot/capture/frame_source.h"
#include "bcot/core/status.h"

namespace bcot {

// True when bcot was built with Aravis.
bool AravisAvailable();

// Device ids Aravis finds now (network discovery takes up to about a second).
StatusOr<std::vector<std::string>> ListAravisDevices(bool enable_fake_interface);

// Opens and configures every camera of `options`, in order. NotFound names a device id that
// does not exist and lists the ones found; InvalidConfig names the camera and setting a camera
// rejects (unknown pixel format, trigger line it does not have, value out of its range);
// Internal when bcot was built without Aravis.
StatusOr<std::vector<std::unique_ptr<FrameSource>>> OpenAravisCameras(
    const CaptureOptions& options);

}  // namespace bcot

#include "bcot/capture/aravis_frame_source.h"

// CMake links Aravis (and its include path) only when it found aravis-0.8; without a
// definition from the build, the header's presence decides.
#ifndef BCOT_HAVE_ARAVIS
#if __has_include(<arv.h>)
#define BCOT_HAVE_ARAVIS 1
#else
#define BCOT_HAVE_ARAVIS 0
#endif
#endif

#include <fmt/format.h>

#if BCOT_HAVE_ARAVIS
#include <arv.h>

#include <atomic>
#include <opencv2/imgproc.hpp>
#endif

namespace bcot {

#if BCOT_HAVE_ARAVIS
namespace {

// Takes ownership of `*error` (clears it) and returns its message.
std::string TakeMessage(GError** error) {
  std::string message = (*error != nullptr && (*error)->message != nullptr)
                            ? std::string((*error)->message)
                            : std::string("unknown error");
  g_clear_error(error);
  return message;
}

// Comma-separated strings of an Aravis `dup_*` list (freed here).
std::string JoinAndFree(const char** strings, guint count) {
  std::string joined;
  for (guint i = 0; i < count; ++i) joined += (i == 0 ? "" : ", ") + std::string(strings[i]);
  g_free(strings);
  return joined.empty() ? "none" : joined;
}

std::vector<std::string> CurrentDeviceIds(bool enable_fake_interface) {
  if (enable_fake_interface) arv_enable_interface("Fake");
  arv_update_device_list();
  std::vector<std::string> ids;
  const unsigned int count = arv_get_n_devices();
  for (unsigned int i = 0; i < count; ++i) {
    const char* id = arv_get_device_id(i);
    if (id != nullptr) ids.emplace_back(id);
  }
  return ids;
}

bool IsSupportedFormat(ArvPixelFormat format) {
  switch (format) {
    case ARV_PIXEL_FORMAT_MONO_8:
    case ARV_PIXEL_FORMAT_MONO_10:
    case ARV_PIXEL_FORMAT_MONO_12:
    case ARV_PIXEL_FORMAT_MONO_14:
    case ARV_PIXEL_FORMAT_MONO_16:
    case ARV_PIXEL_FORMAT_RGB_8_PACKED:
    case ARV_PIXEL_FORMAT_BGR_8_PACKED:
    case ARV_PIXEL_FORMAT_BAYER_GR_8:
    case ARV_PIXEL_FORMAT_BAYER_RG_8:
    case ARV_PIXEL_FORMAT_BAYER_GB_8:
    case ARV_PIXEL_FORMAT_BAYER_BG_8:
      return true;
    default:
      return false;
  }
}

// The buffer's image as an owned cv::Mat (see the header for the conversions); empty when
// the buffer is shorter than its declared size.
cv::Mat ToMat(ArvBuffer* buffer) {
  size_t size = 0;
  const void* data = arv_buffer_get_image_data(buffer, &size);
  const int width = arv_buffer_get_image_width(buffer);
  const int height = arv_buffer_get_image_height(buffer);
  const ArvPixelFormat format = arv_buffer_get_image_pixel_format(buffer);
  const int bits = static_cast<int>(ARV_PIXEL_FORMAT_BIT_PER_PIXEL(format));
  const int type = bits == 24 ? CV_8UC3 : (bits == 16 ? CV_16UC1 : CV_8UC1);
  if (data == nullptr || width <= 0 || height <= 0 || !IsSupportedFormat(format) ||
      size < static_cast<size_t>(width) * height * (bits / 8)) {
    return cv::Mat();
  }
  // OpenCV's Bayer codes name the pattern shifted by one pixel relative to GenICam's.
  const cv::Mat raw(height, width, type, const_cast<void*>(data));
  cv::Mat image;
  switch (format) {
    case ARV_PIXEL_FORMAT_RGB_8_PACKED:
      cv::cvtColor(raw, image, cv::COLOR_RGB2BGR);
      break;
    case ARV_PIXEL_FORMAT_BAYER_RG_8:
      cv::cvtColor(raw, image, cv::COLOR_BayerBG2BGR);
      break;
    case ARV_PIXEL_FORMAT_BAYER_GR_8:
      cv::cvtColor(raw, image, cv::COLOR_BayerGB2BGR);
      break;
    case ARV_PIXEL_FORMAT_BAYER_BG_8:
      cv::cvtColor(raw, image, cv::COLOR_BayerRG2BGR);
      break;
    case ARV_PIXEL_FORMAT_BAYER_GB_8:
      cv::cvtColor(raw, image, cv::COLOR_BayerGR2BGR);
      break;
    default:
      image = raw.clone();
      break;
  }
  return image;
}

class AravisFrameSource final : public FrameSource {
 public:
  AravisFrameSource(std::string name, std::string device_id, ArvCamera* camera,
                    bool software_trigger, int num_buffers)
      : name_(std::move(name)),
        device_id_(std::move(device_id)),
        camera_(camera),
        software_trigger_(software_trigger),
        num_buffers_(num_buffers) {
    // Emitted from Aravis' heartbeat thread when the device stops answering.
    control_lost_handler_ = g_signal_connect(arv_camera_get_device(camera_), "control-lost",
                                             G_CALLBACK(+[](ArvDevice*, gpointer flag) {
                                               static_cast<std::atomic<bool>*>(flag)->store(true);
                                             }),
                                             &control_lost_);
  }

  ~AravisFrameSource() override {
    Stop();
    g_signal_handler_disconnect(arv_camera_get_device(camera_), control_lost_handler_);
    g_clear_object(&stream_);
    g_clear_object(&camera_);
  }

  const std::string& name() const override { return name_; }
  std::string description() const override { return fmt::format("Aravis device '{}'", device_id_); }

  Status Start() override {
    GError* error = nullptr;
    if (stream_ == nullptr) {
      stream_ = arv_camera_create_stream(camera_, nullptr, nullptr, &error);
      if (stream_ == nullptr) return Fail("cannot create the stream", &error);
      const guint payload = arv_camera_get_payload(camera_, &error);
      if (error != nullptr) return Fail("cannot read the payload size", &error);
      for (int i = 0; i < num_buffers_; ++i) {
        arv_stream_push_buffer(stream_, arv_buffer_new_allocate(payload));
      }
    }
    arv_camera_start_acquisition(camera_, &error);
    if (error != nullptr) return Fail("cannot start acquisition", &error);
    acquiring_ = true;
    return Status::Ok();
  }

  Status Trigger() override {
    if (!software_trigger_) return Status::Ok();
    if (control_lost_.load()) return Status::IoError("control of the device was lost");
    GError* error = nullptr;
    arv_camera_software_trigger(camera_, &error);
    if (error != nullptr) {
      control_lost_.store(true);  // a command that fails means the device is not answering
      return Status::IoError(TakeMessage(&error));
    }
    return Status::Ok();
  }

  GrabResult Grab(int timeout_ms) override {
    GrabResult result;
    if (control_lost_.load()) {
      result.status = GrabStatus::kLost;
      result.message = "control of the device was lost";
      return result;
    }
    ArvBuffer* buffer =
        arv_stream_timeout_pop_buffer(stream_, static_cast<guint64>(timeout_ms) * 1000);
    if (buffer == nullptr) {
      result.status = control_lost_.load() ? GrabStatus::kLost : GrabStatus::kMissed;
      result.message = fmt::format("no frame within {} ms", timeout_ms);
      return result;
    }
    const ArvBufferStatus status = arv_buffer_get_status(buffer);
    if (status == ARV_BUFFER_STATUS_SUCCESS) {
      result.frame.image = ToMat(buffer);
      result.frame.device_timestamp_ns = static_cast<int64_t>(arv_buffer_get_timestamp(buffer));
      result.frame.host_timestamp_ns =
          static_cast<int64_t>(arv_buffer_get_system_timestamp(buffer));
      result.frame.frame_id = arv_buffer_get_frame_id(buffer);
      if (!result.frame.image.empty()) {
        result.status = GrabStatus::kFrame;
      } else {
        result.message = "frame with a short or unsupported payload";
      }
    } else {
      result.message =
          fmt::format("incomplete frame (Aravis buffer status {})", static_cast<int>(status));
    }
    arv_stream_push_buffer(stream_, buffer);
    return result;
  }

  void Stop() override {
    // A lost device would only make the command time out.
    if (!acquiring_ || control_lost_.load()) return;
    acquiring_ = false;
    GError* error = nullptr;
    arv_camera_stop_acquisition(camera_, &error);
    g_clear_error(&error);
  }

 private:
  Status Fail(const std::string& what, GError** error) const {
    return Status::IoError(
        fmt::format("camera '{}' ({}): {}: {}", name_, description(), what, TakeMessage(error)));
  }

  std::string name_;
  std::string device_id_;
  ArvCamera* camera_ = nullptr;
  ArvStream* stream_ = nullptr;
  bool software_trigger_ = true;
  int num_buffers_ = 16;
  bool acquiring_ = false;
  std::atomic<bool> control_lost_{false};
  gulong control_lost_handler_ = 0;
};

// Applies the camera's settings and trigger mode; InvalidConfig naming what was rejected.
Status Configure(ArvCamera* camera, const CaptureOptions::Camera& options,
                 const CaptureOptions::Trigger& trigger) {
  const std::string who =
      fmt::format("camera '{}' (Aravis device '{}')", options.name, options.device_id);
  GError* error = nullptr;
  const auto rejected = [&](const std::string& setting, const std::string& extra) {
    const std::string message = TakeMessage(&error);
    return Status::InvalidConfig(fmt::format("{}: {} rejected: {}{}", who, setting, message,
                                             extra.empty() ? "" : " (" + extra + ")"));
  };

  if (!options.pixel_format.empty()) {
    arv_camera_set_pixel_format_from_string(camera, options.pixel_format.c_str(), &error);
    if (error != nullptr) {
      GError* list_error = nullptr;
      guint count = 0;
      const char** formats =
          arv_camera_dup_available_pixel_formats_as_strings(camera, &count, &list_error);
      g_clear_error(&list_error);
      return rejected("pixel_format '" + options.pixel_format + "'",
                      "available: " + JoinAndFree(formats, count));
    }
  }
  const ArvPixelFormat format = arv_camera_get_pixel_format(camera, &error);
  if (error != nullptr) return rejected("reading PixelFormat", "");
  if (!IsSupportedFormat(format)) {
    const char* name = arv_camera_get_pixel_format_as_string(camera, nullptr);
    return Status::InvalidConfig(fmt::format(
        "{}: pixel format {} is not supported (use Mono8, Mono10/12/14/16, RGB8, BGR8 or an 8-bit "
        "Bayer format)",
        who, name != nullptr ? name : "(unknown)"));
  }
  if (options.region) {
    const std::array<int, 4>& r = *options.region;
    arv_camera_set_region(camera, r[0], r[1], r[2], r[3], &error);
    if (error != nullptr) {
      return rejected(fmt::format("region [{}, {}, {}, {}]", r[0], r[1], r[2], r[3]), "");
    }
  }
  if (options.frame_rate_hz) {
    arv_camera_set_frame_rate(camera, *options.frame_rate_hz, &error);
    if (error != nullptr) {
      double lo = 0.0, hi = 0.0;
      arv_camera_get_frame_rate_bounds(camera, &lo, &hi, nullptr);
      return rejected(fmt::format("frame_rate_hz {}", *options.frame_rate_hz),
                      fmt::format("range [{}, {}]", lo, hi));
    }
  }
  if (options.exposure_us) {
    if (arv_camera_is_exposure_auto_available(camera, nullptr)) {
      arv_camera_set_exposure_time_auto(camera, ARV_AUTO_OFF, nullptr);
    }
    arv_camera_set_exposure_time(camera, *options.exposure_us, &error);
    if (error != nullptr) {
      double lo = 0.0, hi = 0.0;
      arv_camera_get_exposure_time_bounds(camera, &lo, &hi, nullptr);
      return rejected(fmt::format("exposure_us {}", *options.exposure_us),
                      fmt::format("range [{}, {}]", lo, hi));
    }
  }
  if (options.gain) {
    if (arv_camera_is_gain_auto_available(camera, nullptr)) {
      arv_camera_set_gain_auto(camera, ARV_AUTO_OFF, nullptr);
    }
    arv_camera_set_gain(camera, *options.gain, &error);
    if (error != nullptr) {
      double lo = 0.0, hi = 0.0;
      arv_camera_get_gain_bounds(camera, &lo, &hi, nullptr);
      return rejected(fmt::format("gain {}", *options.gain), fmt::format("range [{}, {}]", lo, hi));
    }
  }

  arv_camera_set_acquisition_mode(camera, ARV_ACQUISITION_MODE_CONTINUOUS, &error);
  if (error != nullptr) return rejected("AcquisitionMode Continuous", "");
  if (trigger.mode == "free_run") {
    arv_camera_clear_triggers(camera, &error);
    if (error != nullptr) return rejected("switching triggers off", "");
    return Status::Ok();
  }
  const std::string source = trigger.mode == "software" ? "Software" : trigger.source;
  guint count = 0;
  const char** sources = arv_camera_dup_available_trigger_sources(camera, &count, &error);
  if (error != nullptr) return rejected("listing trigger sources", "");
  bool offered = false;
  for (guint i = 0; i < count; ++i) offered = offered || source == sources[i];
  const std::string available = JoinAndFree(sources, count);
  if (!offered) {
    return Status::InvalidConfig(
        fmt::format("{}: trigger source '{}' not offered (trigger.mode {}; available: {})", who,
                    source, trigger.mode, available));
  }
  arv_camera_set_trigger(camera, source.c_str(), &error);
  if (error != nullptr) return rejected("trigger source '" + source + "'", "");
  return Status::Ok();
}

}  // namespace

bool AravisAvailable() { return true; }

StatusOr<std::vector<std::string>> ListAravisDevices(bool enable_fake_interface) {
  return CurrentDeviceIds(enable_fake_interface);
}

StatusOr<std::vector<std::unique_ptr<FrameSource>>> OpenAravisCameras(
    const CaptureOptions& options) {
  BCOT_RETURN_IF_ERROR(options.Validate());
  // Discovery first: a GigE Vision camera opened without it may stream to the wrong host
  // interface (seen with the loopback fake camera: no frame ever arrives).
  const std::vector<std::string> found = CurrentDeviceIds(options.aravis.enable_fake_interface);
  std::vector<std::unique_ptr<FrameSource>> sources;
  for (const CaptureOptions::Camera& camera_options : options.cameras) {
    GError* error = nullptr;
    ArvCamera* camera = arv_camera_new(camera_options.device_id.c_str(), &error);
    if (camera == nullptr) {
      const std::string message = TakeMessage(&error);
      return Status::NotFound(fmt::format(
          "camera '{}': cannot open Aravis device '{}': {} (devices found: {}; list them with "
          "`bcot capture --list-devices`)",
          camera_options.name, camera_options.device_id, message,
          found.empty() ? std::string("none") : fmt::format("{}", fmt::join(found, ", "))));
    }
    const Status configured = Configure(camera, camera_options, options.trigger);
    if (!configured.ok()) {
      g_object_unref(camera);
      return configured;
    }
    sources.push_back(std::make_unique<AravisFrameSource>(
        camera_options.name, camera_options.device_id, camera, options.trigger.mode == "software",
        options.aravis.num_buffers));
  }
  return sources;
}

#else  // !BCOT_HAVE_ARAVIS

namespace {
Status NotBuiltWithAravis() {
  return Status::Internal(
      "bcot was built without Aravis (aravis-0.8 was not found by CMake): install libaravis-dev "
      "and libusb-1.0-0-dev (scripts/setup.sh) and rebuild to capture from cameras");
}
}  // namespace

bool AravisAvailable() { return false; }

StatusOr<std::vector<std::string>> ListAravisDevices(bool) { return NotBuiltWithAravis(); }

StatusOr<std::vector<std::unique_ptr<FrameSource>>> OpenAravisCameras(const CaptureOptions&) {
  return NotBuiltWithAravis();
}

#endif  // BCOT_HAVE_ARAVIS

}  // namespace bcot

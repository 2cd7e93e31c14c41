#include "bcot/review/review_server.h"

#include <fmt/format.h>
#include <httplib.h>

#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "bcot/core/file_util.h"
#include "bcot/review/review_assets.h"

namespace bcot {
namespace {

int HttpStatusOf(const Status& status) {
  switch (status.code()) {
    case StatusCode::kInvalidInput:
    case StatusCode::kInvalidConfig:
      return 400;
    case StatusCode::kNotFound:
      return 404;
    default:
      return 500;
  }
}

void SetError(const Status& status, httplib::Response& response) {
  response.status = HttpStatusOf(status);
  response.set_content(status.message() + "\n", "text/plain; charset=utf-8");
}

void SetJson(const std::string& json, httplib::Response& response) {
  response.set_header("Cache-Control", "no-store");
  response.set_content(json, "application/json");
}

void Respond(const StatusOr<std::string>& json, httplib::Response& response) {
  if (!json.ok()) return SetError(json.status(), response);
  SetJson(*json, response);
}

// The nudge of a request's parameters dx, dy (px), dz (mm), rx, ry, rz (deg); absent = 0.
StatusOr<PoseNudge> ParseNudge(const httplib::Request& request) {
  PoseNudge nudge;
  const std::pair<const char*, double*> fields[] = {{"dx", &nudge.dx_px},
                                                    {"dy", &nudge.dy_px},
                                                    {"dz", &nudge.dz_mm},
                                                    {"rx", &nudge.rotation_deg.x()},
                                                    {"ry", &nudge.rotation_deg.y()},
                                                    {"rz", &nudge.rotation_deg.z()}};
  for (const auto& [name, value] : fields) {
    if (!request.has_param(name)) continue;
    const std::string text = request.get_param_value(name);
    if (!ParseDouble(text, value) || !std::isfinite(*value) || std::abs(*value) > 1e4) {
      return Status::InvalidInput(
          fmt::format("nudge {}='{}': expected a number of magnitude at most 10000", name, text));
    }
  }
  return nudge;
}

// An integer of at most 6 digits (a candidate index).
bool ParseCount(const std::string& text, int* value) {
  int64_t parsed = 0;
  if (!ParseInt64(text, &parsed) || parsed < -1 || parsed > 999999) return false;
  *value = static_cast<int>(parsed);
  return true;
}

// The initial-pose search of a request: frame (default 0) and click=CAM:X,Y (repeated).
StatusOr<InitRequest> ParseInitRequest(const httplib::Request& request, int num_frames) {
  InitRequest init;
  if (request.has_param("frame")) {
    BCOT_ASSIGN_OR_RETURN(init.frame,
                          ParseFrameIndex(request.get_param_value("frame"), num_frames));
  }
  for (size_t k = 0; k < request.get_param_value_count("click"); ++k) {
    BCOT_ASSIGN_OR_RETURN(init.clicks.emplace_back(),
                          ParseImageClick(request.get_param_value("click", k)));
  }
  return init;
}

// Serves the embedded asset `name`, or 404.
void ServeAsset(const std::string& name, httplib::Response& response) {
  const ReviewAsset* asset = FindReviewAsset(name);
  if (asset == nullptr) {
    SetError(Status::NotFound("no such page file"), response);
    return;
  }
  response.set_content(asset->content.data(), asset->content.size(),
                       ReviewAssetContentType(asset->name));
}

}  // namespace

struct ReviewServer::Impl {
  Impl(ReviewSession& session_in, const ReviewOptions& options_in)
      : session(session_in), options(options_in) {}

  void AddRoutes();

  ReviewSession& session;
  const ReviewOptions options;
  httplib::Server server;
  int port = -1;
  // Listen/Stop handshake: a Stop() before, during or after Listen() always ends it.
  std::mutex mutex;
  bool listening = false;
  bool stop_requested = false;
  std::atomic<bool> done{false};
  std::thread thread;  // of Start()
};

void ReviewServer::Impl::AddRoutes() {
  if (options.LoopbackOnly()) {
    server.set_pre_routing_handler(
        [](const httplib::Request& request, httplib::Response& response) {
          if (IsLoopbackAddress(request.remote_addr))
            return httplib::Server::HandlerResponse::Unhandled;
          response.status = 403;
          response.set_content("bcot review answers loopback clients only (see --host)\n",
                               "text/plain; charset=utf-8");
          return httplib::Server::HandlerResponse::Handled;
        });
  }
  server.Get("/", [](const httplib::Request&, httplib::Response& response) {
    ServeAsset("index.html", response);
  });
  server.Get(R"(/(review\.js|review\.css|dygraph\.min\.js|dygraph\.min\.css))",
             [](const httplib::Request& request, httplib::Response& response) {
               ServeAsset(request.matches[1], response);
             });
  server.Get("/api/sequence", [this](const httplib::Request&, httplib::Response& response) {
    SetJson(session.SequenceJson(), response);
  });
  server.Get("/api/quality", [this](const httplib::Request&, httplib::Response& response) {
    SetJson(session.QualityJson(), response);
  });
  // Edits: a frame's pose, nudges in one view, undo, the pose as a keyframe (review_edits.h).
  server.Get(R"(/api/frame/([^/]+)/pose)", [this](const httplib::Request& request,
                                                  httplib::Response& response) {
    const StatusOr<int> frame = ParseFrameIndex(request.matches[1], session.sequence().num_frames);
    if (!frame.ok()) return SetError(frame.status(), response);
    Respond(session.PoseJson(*frame), response);
  });
  server.Post(R"(/api/frame/([^/]+)/nudge)",
              [this](const httplib::Request& request, httplib::Response& response) {
                const StatusOr<ReviewTarget> target =
                    session.Resolve(request.matches[1], request.get_param_value("camera"));
                if (!target.ok()) return SetError(target.status(), response);
                const StatusOr<PoseNudge> nudge = ParseNudge(request);
                if (!nudge.ok()) return SetError(nudge.status(), response);
                Respond(session.Nudge(*target, *nudge), response);
              });
  server.Post(R"(/api/frame/([^/]+)/(undo|keyframe|refine))",
              [this](const httplib::Request& request, httplib::Response& response) {
                const StatusOr<int> frame =
                    ParseFrameIndex(request.matches[1], session.sequence().num_frames);
                if (!frame.ok()) return SetError(frame.status(), response);
                const std::string action = request.matches[2];
                Respond(action == "undo"       ? session.Undo(*frame)
                        : action == "keyframe" ? session.SetKeyframeJson(*frame)
                                               : session.Refine(*frame),
                        response);
              });
  // Long tasks (review_job.h): re-annotating frames, searching an initial pose.
  server.Get("/api/job", [this](const httplib::Request&, httplib::Response& response) {
    SetJson(session.JobJson(), response);
  });
  server.Post(
      "/api/reannotate", [this](const httplib::Request& request, httplib::Response& response) {
        const int num_frames = session.sequence().num_frames;
        const StatusOr<int> first = ParseFrameIndex(request.get_param_value("first"), num_frames);
        if (!first.ok()) return SetError(first.status(), response);
        const StatusOr<int> last = ParseFrameIndex(request.get_param_value("last"), num_frames);
        if (!last.ok()) return SetError(last.status(), response);
        Respond(session.StartReannotate(*first, *last), response);
      });
  server.Post("/api/annotate", [this](const httplib::Request&, httplib::Response& response) {
    Respond(session.StartAnnotate(), response);
  });
  server.Get("/api/init", [this](const httplib::Request&, httplib::Response& response) {
    SetJson(session.InitJson(), response);
  });
  server.Post("/api/init", [this](const httplib::Request& request, httplib::Response& response) {
    const StatusOr<InitRequest> init = ParseInitRequest(request, session.sequence().num_frames);
    if (!init.ok()) return SetError(init.status(), response);
    Respond(session.StartInit(*init), response);
  });
  server.Post("/api/init/save", [this](const httplib::Request& request,
                                       httplib::Response& response) {
    int candidate = 0;
    const std::string text = request.get_param_value("candidate");
    if (!ParseCount(text, &candidate)) {
      return SetError(Status::InvalidInput("candidate='" + text + "': expected an integer"),
                      response);
    }
    Respond(session.SaveInitPose(candidate, request.get_param_value("overwrite") == "1"), response);
  });
  server.Get("/api/trajectory", [this](const httplib::Request&, httplib::Response& response) {
    SetJson(session.TrajectoryJson(), response);
  });
  server.Get(R"(/api/frame/([^/]+)/diagnostics)", [this](const httplib::Request& request,
                                                         httplib::Response& response) {
    const StatusOr<int> frame = ParseFrameIndex(request.matches[1], session.sequence().num_frames);
    if (!frame.ok()) return SetError(frame.status(), response);
    SetJson(session.DiagnosticsJson(*frame), response);
  });
  server.Get(R"(/api/frame/([^/]+)/view/([^/]+)\.jpg)", [this](const httplib::Request& request,
                                                               httplib::Response& response) {
    const StatusOr<ReviewTarget> target = session.Resolve(request.matches[1], request.matches[2]);
    if (!target.ok()) return SetError(target.status(), response);
    int candidate = -1;
    if (request.has_param("candidate") &&
        !ParseCount(request.get_param_value("candidate"), &candidate)) {
      return SetError(Status::InvalidInput("candidate: expected an integer"), response);
    }
    const StatusOr<std::vector<unsigned char>> jpeg = session.ViewJpeg(
        *target, options.jpeg_quality, request.get_param_value("mask") == "1", candidate);
    if (!jpeg.ok()) return SetError(jpeg.status(), response);
    response.set_header("Cache-Control", "no-store");
    response.set_content(reinterpret_cast<const char*>(jpeg->data()), jpeg->size(), "image/jpeg");
  });
}

ReviewServer::ReviewServer(ReviewSession& session, const ReviewOptions& options)
    : impl_(std::make_unique<Impl>(session, options)) {
  BCOT_CHECK(options.Validate().ok());
  impl_->AddRoutes();
}

ReviewServer::~ReviewServer() { Stop(); }

StatusOr<int> ReviewServer::Bind() {
  const ReviewOptions& options = impl_->options;
  if (options.port == 0) {
    impl_->port = impl_->server.bind_to_any_port(options.host);
  } else if (impl_->server.bind_to_port(options.host, options.port)) {
    impl_->port = options.port;
  }
  if (impl_->port <= 0) {
    impl_->port = -1;
    return Status::IoError(fmt::format("cannot listen on {}:{} (address in use or not local?)",
                                       options.host, options.port));
  }
  return impl_->port;
}

std::string ReviewServer::Url() const {
  const std::string& host = impl_->options.host;
  const bool ipv6 = host.find(':') != std::string::npos;
  return fmt::format("http://{}:{}/", ipv6 ? "[" + host + "]" : host, impl_->port);
}

void ReviewServer::Listen() {
  BCOT_CHECK(impl_->port > 0);
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    if (impl_->stop_requested) return;
    impl_->listening = true;
  }
  impl_->server.listen_after_bind();
  impl_->done = true;
}

void ReviewServer::Start() {
  BCOT_CHECK(!impl_->thread.joinable());
  impl_->thread = std::thread([this] { Listen(); });
}

void ReviewServer::Stop() {
  bool listening = false;
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->stop_requested = true;
    listening = impl_->listening;
  }
  if (listening) {
    // Listen() has been entered: wait until httplib runs (or has ended), then stop it.
    while (!impl_->server.is_running() && !impl_->done) std::this_thread::yield();
    impl_->server.stop();
  }
  if (impl_->thread.joinable()) impl_->thread.join();
}

}  // namespace bcot

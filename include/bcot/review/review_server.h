// The HTTP server of `bcot review` (cpp-httplib): the embedded page and the JSON and image
// endpoints of one ReviewSession (docs/review.md lists them). Request text is never used as a
// path: assets are looked up by exact name in the embedded table, frames and cameras are
// validated by ReviewSession::Resolve. With a loopback `host`, clients not on loopback get 403.
//
// Threading: httplib answers on its own worker threads; the session must outlive the server.
// Stop() may be called from any thread but Start()'s and makes Listen() return.
#pragma once

#include <memory>
#include <string>

#include "bcot/core/status.h"
#include "bcot/review/review_options.h"
#include "bcot/review/review_session.h"

namespace bcot {

class ReviewServer {
 public:
  // `options` must be valid (CHECKed).
  ReviewServer(ReviewSession& session, const ReviewOptions& options);
  ~ReviewServer();
  ReviewServer(const ReviewServer&) = delete;
  ReviewServer& operator=(const ReviewServer&) = delete;

  // Binds options.host:options.port (port 0: a free port). Returns the bound port; IoError
  // naming the address when it cannot bind.
  StatusOr<int> Bind();
  // The page's address after Bind(), e.g. "http://127.0.0.1:8765/".
  std::string Url() const;
  // Answers requests until Stop(). Bind() must have succeeded (CHECKed).
  void Listen();
  // Listen() on a thread of the server's own (tests, embedding); Stop() joins it.
  void Start();
  // Ends Listen() (at once or when it starts); joins the thread of Start(). Idempotent.
  void Stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bcot

// Status and StatusOr: how bcot reports anything a user, a file or a device can cause.
//
// Broken invariants are bugs and use BCOT_CHECK; bad input is a Status whose message names
// the file, line and key (`rig.yaml:12: cameras[1].K: expected 4 numbers, got 3`). No
// exception crosses the public API.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

namespace bcot {

enum class StatusCode {
  kOk = 0,
  kInvalidConfig,  // bad option, YAML key or command-line value: the user must fix the config
  kInvalidInput,   // a data file (rig, object, pose, image, mesh) is malformed or inconsistent
  kNotFound,       // a file or directory that must exist does not
  kIoError,        // reading or writing failed (disk full, permissions)
  kInternal,       // a library call failed for reasons the user cannot fix
};

// Exit code of `bcot annotate`, `batch` and `report` when every annotation was written but the
// quality check rejected one (0 accepted, 1 failure, 2 usage or configuration error).
inline constexpr int kExitRejected = 3;

class [[nodiscard]] Status {
 public:
  Status() = default;  // OK
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status Ok() { return Status(); }
  static Status InvalidConfig(std::string m) { return {StatusCode::kInvalidConfig, std::move(m)}; }
  static Status InvalidInput(std::string m) { return {StatusCode::kInvalidInput, std::move(m)}; }
  static Status NotFound(std::string m) { return {StatusCode::kNotFound, std::move(m)}; }
  static Status IoError(std::string m) { return {StatusCode::kIoError, std::move(m)}; }
  static Status Internal(std::string m) { return {StatusCode::kInternal, std::move(m)}; }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }

  // Process exit code for a tool: 0 success, 2 usage/config error, 1 any other failure
  // (kExitRejected below is the fourth code, for a finished but rejected annotation).
  int ExitCode() const {
    if (ok()) return 0;
    return code_ == StatusCode::kInvalidConfig ? 2 : 1;
  }

  // Returns a copy whose message is prefixed with `context: `.
  Status WithContext(const std::string& context) const {
    if (ok()) return *this;
    return Status(code_, context + ": " + message_);
  }

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

// Holds either a value or a non-OK Status.
template <typename T>
class [[nodiscard]] StatusOr {
 public:
  StatusOr(T value) : value_(std::move(value)) {}         // NOLINT(runtime/explicit)
  StatusOr(Status status) : status_(std::move(status)) {  // NOLINT(runtime/explicit)
    if (status_.ok()) status_ = Status::Internal("StatusOr constructed from an OK status");
  }

  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }

  const T& value() const& { return *value_; }
  T& value() & { return *value_; }
  T&& value() && { return std::move(*value_); }
  const T& operator*() const& { return *value_; }
  T& operator*() & { return *value_; }
  const T* operator->() const { return &*value_; }
  T* operator->() { return &*value_; }

 private:
  Status status_;
  std::optional<T> value_;
};

}  // namespace bcot

// Invariant check: a failure is a bug in bcot, never the user's input.
#define BCOT_CHECK(condition)                                                            \
  do {                                                                                   \
    if (!(condition)) {                                                                  \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                      \
    }                                                                                    \
  } while (false)

// Propagates a non-OK Status from an expression returning Status.
#define BCOT_RETURN_IF_ERROR(expr)               \
  do {                                           \
    ::bcot::Status bcot_status_ = (expr);        \
    if (!bcot_status_.ok()) return bcot_status_; \
  } while (false)

#define BCOT_CONCAT_INNER(a, b) a##b
#define BCOT_CONCAT(a, b) BCOT_CONCAT_INNER(a, b)
// BCOT_ASSIGN_OR_RETURN(auto x, ReadThing()); moves the value out or returns the Status.
#define BCOT_ASSIGN_OR_RETURN(lhs, expr)                   \
  auto BCOT_CONCAT(bcot_statusor_, __LINE__) = (expr);     \
  if (!BCOT_CONCAT(bcot_statusor_, __LINE__).ok())         \
    return BCOT_CONCAT(bcot_statusor_, __LINE__).status(); \
  lhs = std::move(BCOT_CONCAT(bcot_statusor_, __LINE__)).value()

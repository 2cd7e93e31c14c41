#include "bcot/core/file_util.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <system_error>

namespace bcot {
namespace {

namespace fs = std::filesystem;

std::string ErrnoText(int error) { return std::strerror(error); }

// write() may write less than asked (signals, pipes); loop until everything is out.
bool WriteAll(int fd, const std::string& content, int* error) {
  const char* data = content.data();
  size_t remaining = content.size();
  while (remaining > 0) {
    const ssize_t written = ::write(fd, data, remaining);
    if (written < 0) {
      if (errno == EINTR) continue;
      *error = errno;
      return false;
    }
    data += written;
    remaining -= static_cast<size_t>(written);
  }
  return true;
}

// Makes the rename itself durable. Best effort: some file systems refuse fsync on a directory.
void SyncDirectory(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

StatusOr<std::string> ReadFileContents(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) return Status::NotFound("file not found");
  if (fs::is_directory(status)) return Status::IoError("is a directory, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::IoError(fmt::format("cannot open for reading: {}", ErrnoText(errno)));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return Status::IoError("read failed");
  return buffer.str();
}

StatusOr<std::string> ReadTextFile(const std::string& path) {
  StatusOr<std::string> contents = ReadFileContents(path);
  if (!contents.ok()) return contents.status().WithContext(path);
  return contents;
}

Status CreateDirectories(const std::string& path) {
  if (path.empty()) return Status::Ok();
  std::error_code error;
  fs::create_directories(path, error);
  if (error) {
    return Status::IoError(fmt::format("{}: cannot create directory: {}", path, error.message()));
  }
  // create_directories reports success when `path` exists as a regular file on some versions.
  if (!fs::is_directory(path, error)) {
    return Status::IoError(fmt::format("{}: exists but is not a directory", path));
  }
  return Status::Ok();
}

Status CheckWritableDirectory(const std::string& dir) {
  BCOT_RETURN_IF_ERROR(CreateDirectories(dir));
  const std::string probe = (fs::path(dir) / ".bcot_write_probe").string();
  const Status written = WriteFileAtomic(probe, "");
  if (!written.ok()) {
    return Status::IoError(fmt::format("{}: not writable ({})", dir, written.message()));
  }
  std::error_code error;
  fs::remove(probe, error);
  if (error) return Status::IoError(fmt::format("{}: cannot remove: {}", probe, error.message()));
  return Status::Ok();
}

Status WriteFileAtomic(const std::string& path, const std::string& content) {
  const fs::path target(path);
  if (target.filename().empty()) {
    return Status::IoError(fmt::format("{}: not a file path", path));
  }
  const fs::path parent = target.parent_path();
  BCOT_RETURN_IF_ERROR(CreateDirectories(parent.string()));

  // The temporary file lives in the target's directory so that rename() is atomic (same file
  // system). O_EXCL with a random suffix instead of mkstemp keeps the usual 0666 & ~umask
  // permissions without touching the process-wide umask.
  std::random_device random;
  std::string temp_path;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temp_path =
        (parent / fmt::format(".{}.tmp.{:08x}", target.filename().string(), random())).string();
    fd = ::open(temp_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) {
      return Status::IoError(
          fmt::format("{}: cannot create temporary file: {}", temp_path, ErrnoText(errno)));
    }
  }
  if (fd < 0) {
    return Status::IoError(fmt::format("{}: cannot find a free temporary file name", path));
  }

  int error = 0;
  bool ok = WriteAll(fd, content, &error);
  if (ok && ::fsync(fd) != 0) {
    error = errno;
    ok = false;
  }
  if (::close(fd) != 0 && ok) {
    error = errno;
    ok = false;
  }
  if (ok && ::rename(temp_path.c_str(), path.c_str()) != 0) {
    error = errno;
    ok = false;
  }
  if (!ok) {
    ::unlink(temp_path.c_str());
    return Status::IoError(fmt::format("{}: write failed: {}", path, ErrnoText(error)));
  }
  SyncDirectory(parent.empty() ? "." : parent.string());
  return Status::Ok();
}

std::string ResolveRelativeTo(const std::string& file, const std::string& relative) {
  const fs::path relative_path(relative);
  if (relative.empty() || relative_path.is_absolute()) return relative;
  const fs::path dir = fs::path(file).parent_path();
  if (dir.empty()) return relative;
  return (dir / relative_path).string();
}

std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
  size_t start = std::string_view(text).substr(0, 3) == kUtf8Bom ? 3 : 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    size_t length = end - start;
    if (length > 0 && text[start + length - 1] == '\r') --length;
    lines.push_back(text.substr(start, length));
    start = end + 1;
  }
  return lines;
}

std::vector<std::string> SplitTokens(std::string_view text, std::string_view separators) {
  std::vector<std::string> tokens;
  size_t start = text.find_first_not_of(separators);
  while (start != std::string_view::npos) {
    const size_t end = text.find_first_of(separators, start);
    tokens.emplace_back(text.substr(start, end == std::string_view::npos ? end : end - start));
    start = text.find_first_not_of(separators, end);
  }
  return tokens;
}

std::string_view TrimWhitespace(std::string_view text) {
  constexpr std::string_view kWhitespace = " \t\r";
  const size_t first = text.find_first_not_of(kWhitespace);
  if (first == std::string_view::npos) return {};
  const size_t last = text.find_last_not_of(kWhitespace);
  return text.substr(first, last - first + 1);
}

namespace {

// std::from_chars rejects a leading '+', which people (and some tools) write.
std::string_view StripPlus(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') {
    return text.substr(1);
  }
  return text;
}

}  // namespace

bool ParseDouble(std::string_view text, double* value) {
  text = StripPlus(text);
  if (text.empty()) return false;
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (error != std::errc() || end != text.data() + text.size()) return false;
  *value = parsed;
  return true;
}

bool ParseInt64(std::string_view text, int64_t* value) {
  text = StripPlus(text);
  if (text.empty()) return false;
  int64_t parsed = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (error != std::errc() || end != text.data() + text.size()) return false;
  *value = parsed;
  return true;
}

}  // namespace bcot

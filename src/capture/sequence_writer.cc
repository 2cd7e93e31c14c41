#include "bcot/capture/sequence_writer.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "bcot/core/file_util.h"
#include "bcot/core/rig_io.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

// Writes all of `size` bytes to `fd`; false with errno set on failure.
bool WriteFully(int fd, const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  for (size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      return false;
    }
    done += static_cast<size_t>(n);
  }
  return true;
}

// Writes `bytes` to a new file at `path`; on failure the file is removed.
Status WriteNewFile(const std::string& path, const std::vector<uchar>& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0)
    return Status::IoError(fmt::format("{}: cannot create: {}", path, std::strerror(errno)));
  bool ok = WriteFully(fd, bytes.data(), bytes.size());
  int saved_errno = ok ? 0 : errno;
  if (::close(fd) != 0 && ok) {
    ok = false;
    saved_errno = errno;
  }
  if (!ok) {
    ::unlink(path.c_str());
    return Status::IoError(fmt::format("{}: write failed: {}", path, std::strerror(saved_errno)));
  }
  return Status::Ok();
}

std::string FrameFileName(int frame) { return fmt::format("{:06d}.png", frame); }

}  // namespace

// An append-only CSV whose last line is either complete or absent.
struct SequenceWriter::CsvFile {
  std::string path;
  int fd = -1;
  off_t committed = 0;

  ~CsvFile() {
    if (fd >= 0) ::close(fd);
  }

  Status Open(const std::string& file_path, const std::string& header) {
    path = file_path;
    fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0)
      return Status::IoError(fmt::format("{}: cannot create: {}", path, std::strerror(errno)));
    return Append(header);
  }

  Status Append(const std::string& line) {
    if (!WriteFully(fd, line.data(), line.size())) {
      const int saved_errno = errno;
      Rollback();
      return Status::IoError(fmt::format("{}: write failed: {}", path, std::strerror(saved_errno)));
    }
    committed += static_cast<off_t>(line.size());
    return Status::Ok();
  }

  // Drops everything after the last committed line (a partial line, or a whole line whose
  // frame set was not committed).
  void Rollback() {
    if (::ftruncate(fd, committed) == 0) ::lseek(fd, committed, SEEK_SET);
  }
  void Uncommit(size_t line_size) {
    committed -= static_cast<off_t>(line_size);
    Rollback();
  }
};

StatusOr<std::unique_ptr<SequenceWriter>> SequenceWriter::Create(
    const std::string& dir, const std::vector<std::string>& camera_names,
    const std::string& rig_yaml_path, int png_compression) {
  BCOT_CHECK(!camera_names.empty());
  BCOT_CHECK(png_compression >= 0 && png_compression <= 9);
  std::error_code error;
  if (fs::exists(dir, error) && !(fs::is_directory(dir, error) && fs::is_empty(dir, error))) {
    return Status::InvalidConfig(
        fmt::format("{}: output exists and is not an empty folder (choose a new --out)", dir));
  }
  std::unique_ptr<SequenceWriter> writer(new SequenceWriter());
  writer->dir_ = dir;
  writer->camera_names_ = camera_names;
  writer->png_params_ = {cv::IMWRITE_PNG_COMPRESSION, png_compression};

  std::string rig_text;
  if (!rig_yaml_path.empty()) {
    BCOT_ASSIGN_OR_RETURN(rig_text, ReadTextFile(rig_yaml_path));
    StatusOr<Rig> rig = ParseRigYaml(rig_text, rig_yaml_path);
    if (!rig.ok()) return Status::InvalidConfig(rig.status().message());
    std::vector<std::string> rig_names;
    for (const RigCamera& camera : rig->cameras()) {
      rig_names.push_back(camera.camera.name);
      writer->rig_sizes_.emplace_back(camera.camera.width, camera.camera.height);
    }
    if (rig_names != camera_names) {
      return Status::InvalidConfig(fmt::format(
          "{}: rig cameras [{}] differ from the capture cameras [{}] (same names, same order)",
          rig_yaml_path, fmt::join(rig_names, ", "), fmt::join(camera_names, ", ")));
    }
  }

  for (const std::string& name : camera_names) {
    BCOT_RETURN_IF_ERROR(CreateDirectories((fs::path(dir) / name).string()));
  }
  const std::string header = fmt::format("frame,{}\n", fmt::join(camera_names, ","));
  writer->host_csv_ = std::make_unique<CsvFile>();
  BCOT_RETURN_IF_ERROR(
      writer->host_csv_->Open((fs::path(dir) / "timestamps.csv").string(), header));
  writer->device_csv_ = std::make_unique<CsvFile>();
  BCOT_RETURN_IF_ERROR(
      writer->device_csv_->Open((fs::path(dir) / "device_timestamps.csv").string(), header));
  if (!rig_text.empty()) {
    BCOT_RETURN_IF_ERROR(WriteFileAtomic((fs::path(dir) / "rig.yaml").string(), rig_text));
  }
  return writer;
}

SequenceWriter::~SequenceWriter() = default;

Status SequenceWriter::CheckImageSizes(const std::vector<Frame>& frames) const {
  if (rig_sizes_.empty()) return Status::Ok();
  for (size_t c = 0; c < frames.size(); ++c) {
    const cv::Mat& image = frames[c].image;
    if (image.cols != rig_sizes_[c].first || image.rows != rig_sizes_[c].second) {
      return Status::InvalidInput(fmt::format(
          "camera '{}': frames are {}x{} but rig.yaml gives image_size [{}, {}] (was the rig "
          "calibrated with another region or binning?)",
          camera_names_[c], image.cols, image.rows, rig_sizes_[c].first, rig_sizes_[c].second));
    }
  }
  return Status::Ok();
}

Status SequenceWriter::Append(const std::vector<Frame>& frames) {
  BCOT_CHECK(frames.size() == camera_names_.size());
  if (num_frames_ == 0) BCOT_RETURN_IF_ERROR(CheckImageSizes(frames));

  const std::string file_name = FrameFileName(num_frames_);
  std::vector<std::string> final_paths, temp_paths;
  const auto remove_all = [](const std::vector<std::string>& paths) {
    for (const std::string& path : paths) ::unlink(path.c_str());
  };
  // 1. Every image to a hidden temporary file.
  for (size_t c = 0; c < frames.size(); ++c) {
    const fs::path folder = fs::path(dir_) / camera_names_[c];
    final_paths.push_back((folder / file_name).string());
    temp_paths.push_back((folder / ("." + file_name + ".tmp")).string());
    std::vector<uchar> png;
    if (!cv::imencode(".png", frames[c].image, png, png_params_)) {
      remove_all(temp_paths);
      return Status::Internal(fmt::format("camera '{}': PNG encoding failed", camera_names_[c]));
    }
    const Status written = WriteNewFile(temp_paths.back(), png);
    if (!written.ok()) {
      remove_all(temp_paths);
      return written;
    }
  }
  // 2. All into place.
  for (size_t c = 0; c < frames.size(); ++c) {
    if (::rename(temp_paths[c].c_str(), final_paths[c].c_str()) != 0) {
      const int saved_errno = errno;
      remove_all(temp_paths);
      remove_all(std::vector<std::string>(final_paths.begin(), final_paths.begin() + c));
      return Status::IoError(
          fmt::format("{}: rename failed: {}", final_paths[c], std::strerror(saved_errno)));
    }
  }
  // 3. The timestamps; the frame set counts once both lines are in.
  std::string host_line = std::to_string(num_frames_);
  std::string device_line = host_line;
  for (const Frame& frame : frames) {
    host_line += "," + std::to_string(frame.host_timestamp_ns);
    device_line += "," + std::to_string(frame.device_timestamp_ns);
  }
  host_line += "\n";
  device_line += "\n";
  Status status = host_csv_->Append(host_line);
  if (status.ok()) {
    status = device_csv_->Append(device_line);
    if (!status.ok()) host_csv_->Uncommit(host_line.size());
  }
  if (!status.ok()) {
    remove_all(final_paths);
    return status;
  }
  ++num_frames_;
  return Status::Ok();
}

}  // namespace bcot

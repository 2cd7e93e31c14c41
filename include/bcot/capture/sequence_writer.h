// Writes a sequence directory (DESIGN.md input contract) frame set by frame set, so that a
// stop at any moment — Ctrl-C, a lost camera, a full disk, a killed process — leaves a valid
// directory holding every frame set committed so far:
//
//   <dir>/<camera>/000000.png ...   same count in every camera folder
//   <dir>/timestamps.csv            frame, then the host stamp (ns) per camera
//   <dir>/device_timestamps.csv     frame, then the camera-clock stamp (ns) per camera
//   <dir>/rig.yaml                  copied from a calibration (optional)
//
// Commit of one frame set: every PNG is written to a hidden temporary file (`.000042.png.tmp`,
// ignored by sequence readers), then all are renamed into place, then one line is appended to
// each CSV and flushed. A failure at any step removes what this frame set wrote (CSV files are
// truncated back) and leaves the earlier frame sets untouched. Files are not fsync'ed per
// frame (that would cap the frame rate); a process crash loses nothing written, a power cut
// may.
//
// Not thread-safe.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bcot/capture/frame_source.h"
#include "bcot/core/status.h"

namespace bcot {

class SequenceWriter {
 public:
  // Creates `dir` (it must not exist or be empty: InvalidConfig otherwise), one folder per
  // camera and the CSV headers. When `rig_yaml_path` is not empty the rig is read, its camera
  // names must equal `camera_names` in order (InvalidConfig naming both lists) and the file is
  // copied to <dir>/rig.yaml. `png_compression` is zlib's level, [0, 9].
  static StatusOr<std::unique_ptr<SequenceWriter>> Create(
      const std::string& dir, const std::vector<std::string>& camera_names,
      const std::string& rig_yaml_path, int png_compression);
  ~SequenceWriter();
  SequenceWriter(const SequenceWriter&) = delete;
  SequenceWriter& operator=(const SequenceWriter&) = delete;

  // Commits one frame set (one frame per camera, in camera order). When a rig was given, the
  // first frame of each camera must have the rig's image size (InvalidInput otherwise).
  // IoError names the file that could not be written; nothing of this set remains then.
  Status Append(const std::vector<Frame>& frames);

  int num_frames() const { return num_frames_; }
  const std::string& dir() const { return dir_; }

 private:
  struct CsvFile;
  SequenceWriter() = default;
  Status CheckImageSizes(const std::vector<Frame>& frames) const;

  std::string dir_;
  std::vector<std::string> camera_names_;
  std::vector<std::pair<int, int>> rig_sizes_;  // (width, height) per camera; empty = no rig
  std::vector<int> png_params_;
  std::unique_ptr<CsvFile> host_csv_;
  std::unique_ptr<CsvFile> device_csv_;
  int num_frames_ = 0;
};

}  // namespace bcot

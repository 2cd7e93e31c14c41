// DONE, the last file of an annotation directory (docs/architecture.md, output contract): it
// exists only when every other output is complete and consistent, and records what the
// annotation was made from, so that a rerun can skip it (same config and inputs) and `bcot
// report` can find the sequence again. The one reader and writer of the format:
//
//   config_hash: <16 hex digits>    AnnotateConfigHash of the options
//   input_hash: <16 hex digits>     SequenceInputHash of the sequence
//   sequence: <absolute path>       the sequence directory
//   frames: <n>
//   failed_frames: <n>
#pragma once

#include <string>

#include "bcot/core/status.h"

namespace bcot {

struct DoneRecord {
  std::string config_hash;
  std::string input_hash;
  std::string sequence_dir;
  int frames = 0;
  int failed_frames = 0;
};

std::string FormatDoneRecord(const DoneRecord& record);

// Reads `<annotation_dir>/DONE`: kNotFound when it is missing ("not a finished annotation"),
// kInvalidInput naming the file and line for a malformed one.
StatusOr<DoneRecord> ReadDoneFile(const std::string& annotation_dir);

// Writes `<annotation_dir>/DONE` atomically; call it after every other output.
Status WriteDoneFile(const std::string& annotation_dir, const DoneRecord& record);

// Removes `<annotation_dir>/DONE` (no error when absent); call it before any output changes.
Status RemoveDoneFile(const std::string& annotation_dir);

}  // namespace bcot

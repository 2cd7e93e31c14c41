#include "bcot/annotate/done_file.h"

#include <fmt/format.h>

#include <filesystem>
#include <system_error>

#include "bcot/core/file_util.h"

namespace bcot {

std::string FormatDoneRecord(const DoneRecord& record) {
  return fmt::format(
      "config_hash: {}\ninput_hash: {}\nsequence: {}\nframes: {}\nfailed_frames: {}\n",
      record.config_hash, record.input_hash, record.sequence_dir, record.frames,
      record.failed_frames);
}

StatusOr<DoneRecord> ReadDoneFile(const std::string& annotation_dir) {
  const std::string path = annotation_dir + "/DONE";
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return Status::NotFound(path + ": missing (not a finished annotation)");
  }
  BCOT_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  DoneRecord record;
  bool has_config = false, has_input = false;
  int line_number = 0;
  for (const std::string& line : SplitLines(text)) {
    ++line_number;
    if (line.empty()) continue;
    const size_t colon = line.find(": ");
    if (colon == std::string::npos) {
      return Status::InvalidInput(fmt::format("{}:{}: expected 'key: value'", path, line_number));
    }
    const std::string key = line.substr(0, colon);
    const std::string value = line.substr(colon + 2);
    auto to_int = [&](int* out) -> Status {
      try {
        size_t used = 0;
        *out = std::stoi(value, &used);
        if (used == value.size() && *out >= 0) return Status::Ok();
      } catch (const std::exception&) {
      }
      return Status::InvalidInput(
          fmt::format("{}:{}: {} = '{}', expected a count", path, line_number, key, value));
    };
    if (key == "config_hash") {
      record.config_hash = value;
      has_config = true;
    } else if (key == "input_hash") {
      record.input_hash = value;
      has_input = true;
    } else if (key == "sequence") {
      record.sequence_dir = value;
    } else if (key == "frames") {
      BCOT_RETURN_IF_ERROR(to_int(&record.frames));
    } else if (key == "failed_frames") {
      BCOT_RETURN_IF_ERROR(to_int(&record.failed_frames));
    }
    // Other keys are ignored, so that a later version's DONE still reads.
  }
  if (!has_config || !has_input) {
    return Status::InvalidInput(path + ": needs config_hash and input_hash");
  }
  return record;
}

Status WriteDoneFile(const std::string& annotation_dir, const DoneRecord& record) {
  return WriteFileAtomic(annotation_dir + "/DONE", FormatDoneRecord(record));
}

Status RemoveDoneFile(const std::string& annotation_dir) {
  std::error_code error;
  std::filesystem::remove(annotation_dir + "/DONE", error);
  if (error) return Status::IoError(annotation_dir + "/DONE: cannot remove: " + error.message());
  return Status::Ok();
}

}  // namespace bcot

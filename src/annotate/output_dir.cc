#include "bcot/annotate/output_dir.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <vector>

#include "bcot/annotate/image_response_file.h"
#include "bcot/annotate/output_lock.h"
#include "bcot/core/annotation_poses.h"

namespace bcot {
namespace {

namespace fs = std::filesystem;

// A hidden temp file of an atomic write of `name` (file_util.h: ".<name>.tmp.<hex>").
bool IsTempOf(const std::string& entry, const std::set<std::string>& names) {
  if (entry.size() < 2 || entry[0] != '.') return false;
  const size_t tmp = entry.find(".tmp.", 1);
  return tmp != std::string::npos && names.count(entry.substr(1, tmp - 1)) > 0;
}

// The first entry (in name order) of `dir` that is neither one of `files` (or its temp file)
// nor one of `subdirs`, or "" when there is none.
std::string FirstForeignEntry(const fs::path& dir, const std::set<std::string>& files,
                              const std::set<std::string>& subdirs) {
  std::error_code error;
  std::vector<fs::directory_entry> entries;
  for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) {
    entries.push_back(*it);
  }
  std::sort(entries.begin(), entries.end());
  for (const fs::directory_entry& entry : entries) {
    const std::string name = entry.path().filename().string();
    const bool is_dir = entry.is_directory(error) && !entry.is_symlink(error);
    if (is_dir && subdirs.count(name) > 0) continue;
    if (!is_dir && (files.count(name) > 0 || IsTempOf(name, files))) continue;
    return name;
  }
  return "";
}

}  // namespace

Status CheckAnnotationOutputDir(const std::string& out_dir, const std::string& sequence_dir,
                                const Rig& rig, bool overwrite) {
  std::error_code error;
  if (fs::exists(out_dir, error) && fs::exists(sequence_dir, error) &&
      fs::equivalent(out_dir, sequence_dir, error)) {
    return Status::InvalidConfig(fmt::format(
        "--out {} is the sequence directory; the annotation needs a directory of its own",
        out_dir));
  }
  if (overwrite || !fs::is_directory(out_dir, error)) return Status::Ok();
  const std::set<std::string> files = {"DONE",
                                       kRigFromObjectFileName,
                                       "frames.csv",
                                       "config.resolved.yaml",
                                       "quality.json",
                                       "quality.csv",
                                       "report.html",
                                       "batch.log",
                                       ".batch_config.yaml",
                                       "summary.json",
                                       "summary.html",
                                       kOutputLockFileName,
                                       kImageResponseFileName};
  std::set<std::string> cameras;
  for (const RigCamera& camera : rig.cameras()) cameras.insert(camera.camera.name);
  std::string foreign = FirstForeignEntry(out_dir, files, cameras);
  for (auto it = cameras.begin(); foreign.empty() && it != cameras.end(); ++it) {
    const fs::path camera_dir = fs::path(out_dir) / *it;
    if (!fs::is_directory(camera_dir, error)) continue;
    const std::string inside = FirstForeignEntry(camera_dir, {"pose.txt"}, {});
    if (!inside.empty()) foreign = *it + "/" + inside;
  }
  if (foreign.empty()) return Status::Ok();
  return Status::InvalidConfig(fmt::format(
      "--out {}: not an annotation directory (it holds '{}', which bcot annotate does not "
      "write); choose a new or empty directory, or pass --overwrite to write beside it",
      out_dir, foreign));
}

}  // namespace bcot

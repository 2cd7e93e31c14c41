#include "bcot/annotate/regenerate_report.h"

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/quality/quality_files.h"

namespace bcot {

StatusOr<QualityReport> RegenerateQualityReport(const std::string& annotation_dir,
                                                const std::string& sequence_dir,
                                                const std::vector<std::string>& overrides) {
  const std::string config_path = annotation_dir + "/config.resolved.yaml";
  BCOT_ASSIGN_OR_RETURN(const std::string config_text, ReadTextFile(config_path));
  std::string recorded_dir;
  for (const std::string& line : SplitLines(config_text)) {
    if (line.rfind("# sequence: ", 0) == 0) recorded_dir = line.substr(12);
  }
  const std::string dir = sequence_dir.empty() ? recorded_dir : sequence_dir;
  if (dir.empty()) {
    return Status::InvalidInput(config_path + ": no '# sequence:' line; pass --sequence");
  }
  BCOT_ASSIGN_OR_RETURN(const AnnotateOptions options, ReadAnnotateOptions(config_path, overrides));
  BCOT_ASSIGN_OR_RETURN(const Sequence sequence, LoadSequence(dir, /*require_init_pose=*/false));
  BCOT_ASSIGN_OR_RETURN(const std::vector<Eigen::Isometry3d> rig_from_object,
                        ReadPoseFile(annotation_dir + "/rig_from_object.txt"));
  return WriteQualityReport(annotation_dir, sequence, rig_from_object, options.views.cameras,
                            options.quality);
}

}  // namespace bcot

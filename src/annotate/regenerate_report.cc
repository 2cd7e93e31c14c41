#include "bcot/annotate/regenerate_report.h"

#include <fmt/format.h>

#include "bcot/annotate/annotate_options.h"
#include "bcot/annotate/annotator.h"
#include "bcot/annotate/done_file.h"
#include "bcot/annotate/image_response_file.h"
#include "bcot/core/annotation_poses.h"
#include "bcot/quality/quality_files.h"
#include "bcot/render/mesh.h"

namespace bcot {

StatusOr<QualityReport> RegenerateQualityReport(const std::string& annotation_dir,
                                                const std::string& sequence_dir,
                                                const std::string& config_path,
                                                const std::vector<std::string>& overrides) {
  // Only a finished annotation is reported on: DONE says the poses and the config beside them
  // belong together, and records the sequence they were solved from.
  BCOT_ASSIGN_OR_RETURN(const DoneRecord done, ReadDoneFile(annotation_dir));
  const std::string dir = sequence_dir.empty() ? done.sequence_dir : sequence_dir;
  if (dir.empty()) {
    return Status::InvalidInput(annotation_dir + "/DONE: records no sequence; pass --sequence");
  }
  BCOT_ASSIGN_OR_RETURN(
      const AnnotateOptions options,
      ReadAnnotateOptions(
          config_path.empty() ? annotation_dir + "/config.resolved.yaml" : config_path, overrides));
  BCOT_ASSIGN_OR_RETURN(const Sequence sequence, LoadSequence(dir, /*require_init_pose=*/false));
  BCOT_ASSIGN_OR_RETURN(const std::vector<Eigen::Isometry3d> rig_from_object,
                        ReadAnnotationPoses(annotation_dir));
  if (static_cast<int>(rig_from_object.size()) != sequence.num_frames) {
    return Status::InvalidInput(fmt::format("{}/{}: {} poses for the {} frames of {}",
                                            annotation_dir, kRigFromObjectFileName,
                                            rig_from_object.size(), sequence.num_frames, dir));
  }
  // The per-camera files are derived: they follow a hand edit of rig_from_object.txt.
  BCOT_RETURN_IF_ERROR(WriteDerivedCameraPoses(annotation_dir, sequence.rig, rig_from_object));
  BCOT_ASSIGN_OR_RETURN(const Mesh mesh,
                        Mesh::Load(sequence.object.mesh_path, sequence.object.unit_to_mm));
  const RayCaster caster(mesh);
  BCOT_ASSIGN_OR_RETURN(
      const ImageResponseRecord image_response,
      RecordedImageResponse(annotation_dir, options.tracker.frame.edge.lines.response));
  BCOT_ASSIGN_OR_RETURN(QualityReport report,
                        MeasureQuality(sequence, caster, rig_from_object, options.views.cameras,
                                       options.quality, image_response.response));
  report.provenance = CurrentProvenance(AnnotateConfigHash(options));
  BCOT_RETURN_IF_ERROR(
      WriteQualityFiles(annotation_dir, report, sequence, caster, rig_from_object));
  return report;
}

}  // namespace bcot

// `bcot report` on one annotation directory: the quality measurement and report files again,
// from the stored poses, without re-solving.
#pragma once

#include <string>
#include <vector>

#include "bcot/core/status.h"
#include "bcot/quality/quality_report.h"

namespace bcot {

// `bcot report`: regenerates quality.json, quality.csv and report.html of one annotation
// directory from its rig_from_object.txt without re-solving. The directory must hold DONE
// (kNotFound otherwise: not a finished annotation). The sequence is `sequence_dir`, or (when
// empty) the one recorded in DONE; the options are those of `config_path` (when not empty) or
// else of the annotation's config.resolved.yaml, with `overrides` (`quality.threshold_px=1`,
// ...) applied; only their `quality` and `views` sections matter. DONE is left as it is.
StatusOr<QualityReport> RegenerateQualityReport(const std::string& annotation_dir,
                                                const std::string& sequence_dir,
                                                const std::string& config_path,
                                                const std::vector<std::string>& overrides);

}  // namespace bcot

// Which directories `bcot annotate` may write an annotation into. An annotation directory holds
// only what bcot writes there (the output contract, docs/architecture.md): DONE,
// rig_from_object.txt, <camera>/pose.txt, frames.csv, config.resolved.yaml, quality.json,
// quality.csv, report.html, batch.log and .batch_config.yaml (bcot batch), summary.json and
// summary.html (bcot batch / report, when the batch root is itself a sequence), .bcot.lock
// (output_lock.h) and the hidden temp files of atomic writes. So an earlier annotation, resumed, reprocessed with another config
// or spliced
// (`--frames`), is written over without a flag, while a directory that holds anything else
// (a user's files, another tool's output, the images) is refused unless the user says
// `--overwrite`; even then nothing that is not bcot's is removed.
#pragma once

#include <string>

#include "bcot/core/rig.h"
#include "bcot/core/status.h"

namespace bcot {

// Ok when `out_dir` does not exist, is empty, or holds only annotation files of `rig`'s
// cameras (above). Otherwise kInvalidConfig naming the directory and its first foreign entry
// (in name order), unless `overwrite`. `out_dir` equal to `sequence_dir` is refused even with
// `overwrite`: the per-camera pose files would go into the image folders.
Status CheckAnnotationOutputDir(const std::string& out_dir, const std::string& sequence_dir,
                                const Rig& rig, bool overwrite);

}  // namespace bcot

// `bcot annotate SEQ --out ANN --frames A:B`: re-annotates frames A..B (inclusive, counted from
// the sequence's first image) of the finished annotation in ANN and splices them in.
//
// ANN must hold DONE, made with the same options (config hash), and one pose per frame of the
// sequence; the sequence may have moved since (DONE then records its new path). Tracking
// starts from the annotation's pose at A − 1 (or init_pose.txt when A = 0) and restarts at every
// keyframe in A..B (AnnotateFrames, FrameSpan); the temporal window runs over the range and a
// window's size of existing frames on each side, held constant, so the range joins its
// neighbours while every frame outside A..B keeps its pose exactly (its line of
// rig_from_object.txt is byte-identical). Then rig_from_object.txt, the derived
// <camera>/pose.txt, the range's rows of frames.csv, config.resolved.yaml (the new input hash)
// and the quality report of the whole sequence are rewritten.
//
// Atomicity: everything is solved and measured in memory first, with the old annotation and
// its DONE untouched; then DONE is removed, every file is replaced by temp + rename, and DONE
// is written last. An interruption therefore leaves the old annotation with DONE, or files
// without DONE (a directory without DONE is never taken as finished: batch redoes it, and a
// rerun without --frames rebuilds it) — never a mix with DONE present.
#pragma once

#include <string>

#include "bcot/annotate/annotate_options.h"
#include "bcot/annotate/annotator.h"
#include "bcot/core/status.h"

namespace bcot {

// "A:B" → frames [A, B + 1); errors name `--frames` and say what was expected.
StatusOr<FrameSpan> ParseFrameRange(const std::string& text, int num_frames);

// See the header comment. `inputs.frames` holds the range.
StatusOr<AnnotationOutcome> SpliceFrames(const std::string& sequence_dir,
                                         const std::string& out_dir, const AnnotateOptions& options,
                                         const AnnotateInputs& inputs,
                                         const AnnotateProgress& progress = {});

}  // namespace bcot

// Runs each sequence of a batch in its own process, so that nothing one sequence does — a
// crash, an abort, an out-of-memory kill — can take the batch or its other sequences down
// (bcot/annotate/batch.h, BatchOptions::runner).
//
// Per sequence: the options are written (FormatAnnotateOptions, atomically) to
// `<annotation dir>/.batch_config.yaml`, then `<executable> annotate <sequence> --out
// <annotation dir> --config <that file>` runs as a child process whose stdout and stderr are
// read through a pipe: its "frame d/N" progress drives `progress`, its last line is kept for
// the error message. The child dies with the batch (PR_SET_PDEATHSIG), so a killed batch leaves
// no process writing behind it. Exit 0: the outcome is read back from the annotation
// directory (quality.json, DONE). Non-zero exit: the child's last line ("bcot annotate: error:
// ..."). Killed by a signal: "the annotation process was killed by signal N (name)", plus its
// last line. Linux only (fork/exec, prctl).
#pragma once

#include <string>
#include <vector>

#include "bcot/annotate/batch.h"

namespace bcot {

// `executable` is the bcot binary (e.g. /proc/self/exe resolved); `extra_arguments` are
// appended to every child's `annotate` command line (e.g. {"--image-cache-mb", "512"}).
SequenceRunner MakeChildProcessRunner(const std::string& executable,
                                      const std::vector<std::string>& extra_arguments = {});

}  // namespace bcot

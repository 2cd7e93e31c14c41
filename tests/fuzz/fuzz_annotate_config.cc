// The annotate config (YAML): ReadAnnotateOptions (bcot/annotate/annotate_options.h), through a
// file as `bcot annotate --config` reads it.
#include "bcot/annotate/annotate_options.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)bcot::ReadAnnotateOptions(
      bcot::fuzz::ScratchFile("annotate.yaml", bcot::fuzz::Text(data, size)), {});
  return 0;
}

// rig.yaml: ParseRigYaml, with its plausibility checks (bcot/core/rig_io.h).
#include "bcot/core/rig_io.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)bcot::ParseRigYaml(bcot::fuzz::Text(data, size), "rig.yaml");
  return 0;
}

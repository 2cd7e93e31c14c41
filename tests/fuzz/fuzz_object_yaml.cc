// object.yaml: ReadObjectYaml (bcot/core/object_io.h), through a file as `bcot` reads it.
#include "bcot/core/object_io.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)bcot::ReadObjectYaml(bcot::fuzz::ScratchFile("object.yaml", bcot::fuzz::Text(data, size)));
  return 0;
}

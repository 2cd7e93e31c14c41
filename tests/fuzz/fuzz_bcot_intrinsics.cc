// K.txt of the BCOT release layout: ParseBcotIntrinsics (bcot/eval/bcot_layout.h).
#include "bcot/eval/bcot_layout.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)bcot::ParseBcotIntrinsics(bcot::fuzz::Text(data, size), "K.txt");
  return 0;
}

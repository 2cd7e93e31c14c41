// A cached sparse viewpoint model file: SparseViewpointModel::Deserialize
// (bcot/render/sparse_viewpoint_model.h). The expected key is taken from the input's own key
// field, so that the fuzzer reaches the viewpoints past the key check.
#include <string>

#include "bcot/render/sparse_viewpoint_model.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes = bcot::fuzz::Text(data, size);
  // Magic (8 bytes), format version and byte-order mark (4 each), then the 16-character key.
  constexpr size_t kKeyOffset = 16, kKeyLength = 16;
  const std::string key = size >= kKeyOffset + kKeyLength ? bytes.substr(kKeyOffset, kKeyLength)
                                                          : std::string(kKeyLength, '0');
  (void)bcot::SparseViewpointModel::Deserialize(bytes, key, "viewpoints.bin");
  return 0;
}

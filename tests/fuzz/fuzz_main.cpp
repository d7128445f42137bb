// libFuzzer entry point of one target: built once per target with LR_FUZZ_TARGET set to the
// target's function (see tests/fuzz/CMakeLists.txt).
#include "tests/fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return ::lr::fuzz::LR_FUZZ_TARGET(data, size);
}

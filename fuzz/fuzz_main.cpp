// One libFuzzer target: FUZZ_TARGET names the harness (see harness/fuzz_harness.h).
#include <cstdio>
#include <cstdlib>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        busdecode::fuzz::runTarget(FUZZ_TARGET, data, size);
    } catch (const busdecode::fuzz::HarnessFailure& e) {
        std::fprintf(stderr, "\n==busdecode fuzz finding (%s): %s\n", FUZZ_TARGET, e.what());
        std::abort();
    }
    return 0;
}

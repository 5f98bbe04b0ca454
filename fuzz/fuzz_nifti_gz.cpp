// Gzipped NIfTI (.nii.gz) through loadVolume.
#include "fuzz/support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    vr::fuzz::loadExpectingInputError(
        vr::fuzz::writeInput("input.nii.gz", {reinterpret_cast<const char*>(data), size}));
    return 0;
}

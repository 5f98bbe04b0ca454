// Headerless raw (.raw, .raw.gz) through loadVolume: the input's first line is the file name, which carries the dims
// and the voxel type (NAME_XxYxZ_TYPE.raw), the rest is the file.
#include "fuzz/support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const vr::fuzz::NamedInput input = vr::fuzz::splitNamedInput(data, size, {".raw", ".raw.gz"});
    vr::fuzz::loadExpectingInputError(vr::fuzz::writeInput(input.name, input.bytes));
    return 0;
}

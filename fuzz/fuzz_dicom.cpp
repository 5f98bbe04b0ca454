// A DICOM series through loadVolume: a folder holding the input as its slices. The input is split at each
// "\n--SLICE--\n" into up to 4 files, so that the slice sorting and spacing code sees series, not only one file.
#include <filesystem>
#include <string_view>

#include "fuzz/support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    namespace fs = std::filesystem;
    constexpr std::string_view separator = "\n--SLICE--\n";
    const fs::path folder = vr::fuzz::scratchDir() / "series";
    fs::remove_all(folder);
    fs::create_directory(folder);
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    for (int slice = 0; slice < 4 && !rest.empty(); ++slice) {
        const std::size_t end = slice == 3 ? rest.npos : rest.find(separator);
        vr::fuzz::writeInput("series/slice" + std::to_string(slice) + ".dcm", rest.substr(0, end));
        rest = end == rest.npos ? std::string_view() : rest.substr(end + separator.size());
    }
    vr::fuzz::loadExpectingInputError(folder);
    return 0;
}

// The files of preprocess/classify/presets/, embedded in the binary at build time (cmake/EmbedPresets.cmake), so
// that a tool finds its presets without the source tree.
#pragma once
#include <string_view>
#include <vector>

namespace vr {

struct EmbeddedFile {
    std::string_view name;  // the file's name, e.g. CT-Bone.json
    std::string_view text;
};

// Every preset file, in name order.
std::vector<EmbeddedFile> embeddedPresetFiles();

}  // namespace vr

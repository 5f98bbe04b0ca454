// OpenEXR files through OpenEXR's own library: linear float RGBA, kept exactly.
#pragma once
#include <filesystem>

#include "render/image.h"

namespace vr {

// A well-formed image as 32-bit float R, G, B, A, ZIP-compressed; written atomically. Throws InputError naming
// the path.
void writeExr(const std::filesystem::path& path, const Image& image);

// Any EXR's R, G, B and A channels (half or float) as float; a grey file (Y only) fills R, G and B; a missing colour
// channel reads 0 and a missing alpha 1. Throws InputError naming the path.
Image readExr(const std::filesystem::path& path);

}  // namespace vr

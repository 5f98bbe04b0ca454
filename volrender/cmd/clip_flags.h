// volrender's clipping flags: up to six planes (--clip, repeatable) and a crop box in voxel indices (--crop).
#pragma once
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/render_settings.h"

namespace vr {

struct ClipFlags {
    std::vector<std::string> planes;  // each "nx,ny,nz,d"
    std::string crop;                 // "x0,x1,y0,y1,z0,z1", empty when not given
};

void addClipFlags(CLI::App& app, ClipFlags& f);

// Parses the flags into the settings' clipPlanes and crop and makes the checks that need no volume (checkClipPlanes);
// InputError naming the flag. The crop is checked against the grid with the render's other settings.
void applyClipFlags(const ClipFlags& f, RenderSettings& settings);

// The flags as --stats reports them.
nlohmann::json clipStatistics(const ClipFlags& f);

}  // namespace vr

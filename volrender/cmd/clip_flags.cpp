#include "volrender/cmd/clip_flags.h"

#include <cmath>
#include <cstdlib>

#include "core/errors.h"
#include "render/render_checks.h"

namespace vr {

void addClipFlags(CLI::App& app, ClipFlags& f) {
    app.add_option("--clip", f.planes, "clipping plane nx,ny,nz,d in world units: keeps the side where "
                                       "nx x + ny y + nz z >= d (repeatable, up to 6)");
    app.add_option("--crop", f.crop, "keep only voxels x0..x1, y0..y1, z0..z1 (inclusive voxel indices): "
                                     "x0,x1,y0,y1,z0,z1");
}

namespace {

// The comma-separated numbers of `text`, exactly `count` of them; InputError naming the flag otherwise.
std::vector<double> numbers(const std::string& text, std::size_t count, const std::string& flag,
                            const std::string& expected) {
    std::vector<double> values;
    const char* p = text.c_str();
    for (;;) {
        char* end = nullptr;
        const double v = std::strtod(p, &end);
        if (end == p || (*end != ',' && *end != '\0')) break;
        values.push_back(v);
        if (*end == '\0') {
            if (values.size() == count) return values;
            break;
        }
        p = end + 1;
    }
    throw InputError(flag + " '" + text + "': expected " + expected);
}

}  // namespace

void applyClipFlags(const ClipFlags& f, RenderSettings& settings) {
    settings.clipPlanes.clear();
    for (const std::string& plane : f.planes) {
        const std::vector<double> v = numbers(plane, 4, "--clip", "nx,ny,nz,d: four numbers");
        settings.clipPlanes.push_back({{v[0], v[1], v[2]}, v[3]});
    }
    checkClipPlanes(settings.clipPlanes);
    settings.crop.reset();
    if (f.crop.empty()) return;
    const std::vector<double> v = numbers(f.crop, 6, "--crop", "x0,x1,y0,y1,z0,z1: six voxel indices");
    for (double x : v)
        if (!(x >= -1e9 && x <= 1e9) || x != std::floor(x))
            throw InputError("--crop '" + f.crop + "': expected x0,x1,y0,y1,z0,z1: six voxel indices (integers)");
    settings.crop = CropBox{{int(v[0]), int(v[2]), int(v[4])}, {int(v[1]), int(v[3]), int(v[5])}};
}

nlohmann::json clipStatistics(const ClipFlags& f) { return {{"clip", f.planes}, {"crop", f.crop}}; }

}  // namespace vr

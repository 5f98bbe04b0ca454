// volphantom: writes a synthetic phantom as a headerless raw file NAME_DxDxD_TYPE.raw (x fastest, little-endian),
// the naming the raw loader reads dims and type from.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "io/atomic_file.h"
#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/load/voxel_budget.h"
#include "tools/tool_main.h"

namespace {

template <typename T>
void writeAs(std::ostream& out, const std::vector<float>& values) {
    std::vector<T> converted(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        if constexpr (std::is_floating_point_v<T>) {
            converted[i] = values[i];
        } else {
            double v = std::round(double(values[i]));
            converted[i] =
                T(std::clamp(v, double(std::numeric_limits<T>::min()), double(std::numeric_limits<T>::max())));
        }
    }
    out.write(reinterpret_cast<const char*>(converted.data()), std::streamsize(converted.size() * sizeof(T)));
}

vr::Volume makePhantom(const std::string& kind, vr::Vec3i dims, vr::Vec3d spacing, int axis, uint32_t seed) {
    if (kind == "constant") return vr::constantPhantom(dims, 100, spacing);
    if (kind == "ramp") return vr::rampPhantom(dims, axis, 0, 255, spacing);
    if (kind == "shells") return vr::shellsPhantom(dims, spacing);
    if (kind == "checkerboard") return vr::checkerboardPhantom(dims, 0, 255, spacing);
    if (kind == "noise") return vr::noisePhantom(dims, seed, 0, 255, spacing);
    if (kind == "engine") return vr::enginePhantom(dims, spacing);
    throw vr::InputError("unknown phantom '" + kind + "'");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Writes a synthetic phantom volume as a headerless raw file named NAME_DxDxD_TYPE.raw."};
    std::string kind, outDir = ".", typeName;
    std::vector<int> dims{64, 64, 64};
    std::vector<double> spacing{1, 1, 1};
    int axis = 2;
    uint32_t seed = 1;
    app.add_option("kind", kind, "constant, ramp, shells (CT-like, HU), checkerboard, noise or engine")
        ->required()
        ->check(CLI::IsMember({"constant", "ramp", "shells", "checkerboard", "noise", "engine"}));
    app.add_option("-o,--out-dir", outDir, "folder to write into")->capture_default_str();
    app.add_option("--dims", dims, "grid size, e.g. 128x128x64")->delimiter('x')->expected(3)->capture_default_str();
    app.add_option("--spacing", spacing, "voxel size x,y,z (printed; not part of the name)")
        ->delimiter(',')
        ->expected(3)
        ->capture_default_str();
    app.add_option("--type", typeName,
                   "voxel type written: uint8, int16, uint16, float32 (default: the phantom's own)");
    app.add_option("--axis", axis, "ramp axis: 0, 1 or 2")->check(CLI::Range(0, 2))->capture_default_str();
    app.add_option("--seed", seed, "noise seed")->capture_default_str();
    return vr::runTool("volphantom", app, argc, argv, [&] {
        // The phantom's floats and the copy written (at most 4 bytes a voxel), checked before either is allocated.
        const vr::Vec3i n = vr::checkVoxelBudget("--dims", dims[0], dims[1], dims[2], 2 * sizeof(float));
        vr::Volume v = makePhantom(kind, n, {spacing[0], spacing[1], spacing[2]}, axis, seed);
        vr::ScalarType type = typeName.empty() ? v.sourceType : vr::parseScalarType(typeName);
        std::string name = kind + "_" + std::to_string(n.x) + "x" + std::to_string(n.y) + "x" + std::to_string(n.z) +
                           "_" + std::string(vr::scalarTypeName(type)) + ".raw";
        std::filesystem::path path = std::filesystem::path(outDir) / name;
        vr::writeFileAtomically(path, [&](std::ostream& out) {
            switch (type) {
                case vr::ScalarType::UInt8: writeAs<uint8_t>(out, v.values); break;
                case vr::ScalarType::Int16: writeAs<int16_t>(out, v.values); break;
                case vr::ScalarType::UInt16: writeAs<uint16_t>(out, v.values); break;
                case vr::ScalarType::Float32: writeAs<float>(out, v.values); break;
            }
        });
        std::printf("%s (spacing %g,%g,%g)\n", path.c_str(), spacing[0], spacing[1], spacing[2]);
        return 0;
    });
}

#include "bench/peers/vdb_peer.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <regex>
#include <sstream>

#include "core/errors.h"
#include "preprocess/classify/classify.h"

namespace vr {
namespace fs = std::filesystem;
namespace {

// vdb_render's ray intersector needs cubic voxels: the classified volume on the cubic lattice (voxel size u), as
// extinction per index unit (vdb_render integrates density * step with the step in voxels), active where non-zero.
void writeDensityGrid(const PeerScene& scene, const fs::path& path) {
    ClassifyParams params;
    params.transferFunction = scene.tf;
    params.normals = false;
    const ClassifiedVolume classified = classify(scene.volume, params);
    const GridGeometry& g = scene.volume.grid;
    const CubicLattice cubes(g);
    const double u = cubes.size;

    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.f);
    openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(u);
    xform->postTranslate(openvdb::Vec3d(g.origin.x + 0.5 * u, g.origin.y + 0.5 * u, g.origin.z + 0.5 * u));
    grid->setTransform(xform);
    auto acc = grid->getAccessor();
    for (int z = 0; z < cubes.dims.z; ++z)
        for (int y = 0; y < cubes.dims.y; ++y)
            for (int x = 0; x < cubes.dims.x; ++x) {
                const float sigma = classified.sigma[cubes.sourceIndex(g, x, y, z)];
                if (sigma > 0) acc.setValue(openvdb::Coord(x, y, z), float(sigma * u));
            }
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    openvdb::io::File(path.string()).write({grid});
}

std::string triple(const Vec3d& v) {
    std::ostringstream s;
    s.precision(17);
    s << v.x << ',' << v.y << ',' << v.z;
    return s.str();
}

// Runs a command, returning its stdout and stderr together; throws when it fails.
std::string runCommand(const std::string& command) {
    std::string output;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run: " + command);
    std::array<char, 4096> buffer;
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
    if (pclose(pipe) != 0) throw std::runtime_error("failed: " + command + "\n" + output);
    return output;
}

// vdb_render -v reports "ray-tracing density..." and then "...completed in X sec": the render alone, in ms.
std::optional<double> reportedRenderMs(const std::string& log) {
    static const std::regex line(R"(ray-tracing[^\n]*\n[^\n]*completed in ([0-9.]+(?:[eE][-+]?[0-9]+)?) sec)");
    std::smatch m;
    if (!std::regex_search(log, m, line)) return std::nullopt;
    return 1000 * std::stod(m[1]);
}

}  // namespace

PeerRun runVdbRenderPeer(const PeerScene& scene, const fs::path& outDir) {
    const GridGeometry& g = scene.volume.grid;
    const fs::path folder = outDir / "vdb_render";
    fs::create_directories(folder);
    const fs::path vdb = folder / "volume.vdb", exr = folder / "vdb_render_out.exr";
    const auto setup = std::chrono::steady_clock::now();
    writeDensityGrid(scene, vdb);
    const double setupMs = millisecondsSince(setup);

    const double ert = scene.options.ert;
    bool reported = true;
    PeerRun run = runViews("vdb_render", scene, outDir, [&](std::size_t i, Image& out) {
        const Camera& cam = scene.views[i];
        std::ostringstream cmd;
        cmd.precision(17);
        // Pure emission-absorption in white: scattering 1 with no absorption makes the albedo 1, and a shadow step
        // beyond the volume leaves every shadow ray empty (no self-shadowing). The cutoff ends rays where
        // 3 T^2 < cutoff, i.e. at our early ray termination, and skips densities below it.
        cmd << "vdb_render " << vdb << ' ' << exr << " -camera ortho -frame "
            << 2 * cam.halfHeight * cam.width / cam.height << " -translate " << triple(cam.eye) << " -lookat "
            << triple(g.centre()) << " -up " << triple(cam.up)
            << " -res " << cam.width << 'x' << cam.height << " -step " << scene.options.stepVoxels
            << " -absorb 0,0,0 -scatter 1,1,1 -light 0,0,1,1,1,1 -shadowstep 1e30 -cutoff "
            << 3 * (1 - ert) * (1 - ert) << " -cpus " << scene.options.threads << " -compression none -v";
        const auto start = std::chrono::steady_clock::now();
        const std::string log = runCommand(cmd.str());
        const double processMs = millisecondsSince(start);
        const std::optional<double> renderMs = reportedRenderMs(log);
        if (!renderMs) reported = false;
        out = readImage(exr);
        return renderMs.value_or(processMs);
    });
    fs::remove(exr);
    run.setupMs = setupMs;
    run.notes = std::string(reported ? "render time as vdb_render -v reports it (file load excluded)"
                                     : "time of the whole vdb_render process (file load included)") +
                "; white emission (one density grid: no TF colour), trilinear on extinction (pre-classified), "
                "anisotropic volumes resampled to cubic voxels of the smallest spacing; setup = classify + write .vdb";
    return run;
}

}  // namespace vr

// vr_peers: renders one volume with the peer renderers (VTK's CPU and GPU ray casters, VolPack, OpenVDB's
// vdb_render) and our CPU reference on the same views, image size, sample distance and thread count; writes
// every image, OUT/peers.json (per peer, per view: milliseconds and image) and prints a Markdown table. By default
// every peer samples nearest and unshaded; --user-settings renders trilinear and shaded (our Phong material, one
// headlight), skipping the peers that cannot.
// scripts/peers.sh installs the peers, builds this and runs it under xvfb-run (VTK needs an X display).
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench/peers/reference_peer.h"
#include "bench/peers/vdb_peer.h"
#include "bench/peers/volpack_peer.h"
#include "bench/peers/vtk_peer.h"
#include "io/atomic_file.h"
#include "core/errors.h"

namespace {
namespace fs = std::filesystem;

const std::vector<std::string> kPeers = {"ours-cpu-primitive", "vtk-fixed-point", "vtk-gpu", "volpack",
                                         "vdb_render"};

// Why a peer cannot render a blend other than composite, or empty when it can.
std::string blendSkipReason(const std::string& name, vr::Blend blend) {
    if (blend == vr::Blend::Composite || name == "ours-cpu-primitive" || name.rfind("vtk-", 0) == 0) return "";
    return name + " has no " + std::string(vr::blendName(blend)) + " blend";
}

// Why a peer cannot render at the user settings (trilinear, Phong-shaded), or empty when it can.
std::string userSettingsSkipReason(const std::string& name) {
    if (name == "volpack")
        return "VolPack cannot render at these settings: shear-warp samples each slice bilinearly (no trilinear "
               "samples at our sample distance) and shades per voxel before compositing (vpShadeTable over its "
               "encoded normals), not per sample";
    if (name == "vdb_render")
        return "vdb_render cannot render at these settings: it has no transfer function colour and no gradient "
               "(Phong) shading, only single scattering of a light through a density grid";
    return "";
}

nlohmann::json settingsJson(const vr::PeerSceneOptions& o) {
    if (!o.userSettings) return {{"name", "nearest-unshaded"}, {"interpolation", "nearest"}, {"shading", false}};
    const vr::ShadingModel m;
    return {{"name", "user"}, {"interpolation", "trilinear"}, {"shading", true},
            {"material", {{"model", "phong"}, {"ambient", m.ambient}, {"diffuse", m.diffuse},
                          {"specular", m.specular}, {"specular_power", m.shininess}}},
            {"light", "headlight"}};
}

vr::PeerRun runPeer(const std::string& name, const vr::PeerScene& scene, const fs::path& out) {
    if (name == "ours-cpu-primitive") return vr::runReferencePeer(scene, out);
    if (name == "vtk-fixed-point") return vr::runVtkPeer(scene, vr::VtkMapper::FixedPoint, out);
    if (name == "vtk-gpu") return vr::runVtkPeer(scene, vr::VtkMapper::Gpu, out);
    if (name == "volpack") return vr::runVolPackPeer(scene, out);
    return vr::runVdbRenderPeer(scene, out);
}

nlohmann::json runJson(const vr::PeerRun& run, const vr::PeerScene& scene) {
    nlohmann::json views = nlohmann::json::array();
    for (std::size_t i = 0; i < run.ms.size(); ++i)
        views.push_back({{"view", i}, {"azimuth_deg", 360.0 * double(i) / double(scene.views.size())},
                         {"elevation_deg", scene.options.elevationDeg},
                         {"ms", run.ms[i]}, {"image", fs::absolute(run.images[i]).string()}});
    return {{"peer", run.peer}, {"notes", run.notes}, {"setup_ms", run.setupMs}, {"median_ms", run.medianMs()},
            {"p95_ms", run.p95Ms()}, {"views", views}};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Renders one volume with VTK (fixed-point CPU and GPU ray casters), VolPack and vdb_render on our "
                 "views, timing each; see docs/BENCH.md \"Peers\""};
    vr::PeerSceneOptions o;
    std::string volume, tf, size = "512x512", out = "peers_out", blend = "composite";
    std::vector<double> spacing;
    std::vector<std::string> peers = kPeers;
    app.add_option("volume", volume, "volume file (e.g. a .raw.gz named NAME_XxYxZ_TYPE.raw.gz)")->required();
    app.add_option("--tf", tf, "a built-in preset's name or a ParaView transfer function preset (JSON)")->required();
    app.add_option("--spacing", spacing, "voxel size x,y,z for raw volumes")->delimiter(',')->expected(3);
    app.add_option("--views", o.views, "orbit of N views 360/N degrees apart")->capture_default_str();
    app.add_option("--elevation", o.elevationDeg, "elevation of every view, degrees")->capture_default_str();
    app.add_option("--size", size, "image size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--step", o.stepVoxels, "sample distance in voxels of the smallest spacing")->capture_default_str();
    app.add_option("--threads", o.threads, "threads for every peer that can use them")->capture_default_str();
    app.add_option("--blend", blend, "composite or mip (VTK's MAXIMUM_INTENSITY; VolPack and vdb_render are skipped)")
        ->capture_default_str();
    app.add_option("--peers", peers, "peers to run")->delimiter(',')->check(CLI::IsMember(kPeers));
    app.add_option("-o,--out", out, "output folder")->capture_default_str();
    app.add_flag("--user-settings", o.userSettings,
                 "render as users do: trilinear, shaded with our Phong material and a headlight (default: nearest, "
                 "unshaded); VolPack and vdb_render, which cannot, are skipped");
    CLI11_PARSE(app, argc, argv);

    try {
        if (std::sscanf(size.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 1 || o.height < 1)
            throw vr::InputError("--size " + size + ": expected WIDTHxHEIGHT");
        if (o.threads < 1) throw vr::InputError("--threads must be at least 1");
        o.blend = vr::parseBlend(blend);
        if (o.blend != vr::Blend::Composite && o.blend != vr::Blend::MIP)
            throw vr::InputError("--blend " + blend + ": the peers are set up for composite and mip only");
        o.volume = volume;
        o.transferFunction = tf;
        if (!spacing.empty()) o.raw.spacing = vr::Vec3d{spacing[0], spacing[1], spacing[2]};
        // llvmpipe reads its thread count when the first OpenGL context is made; TBB serves our reference.
        setenv("LP_NUM_THREADS", std::to_string(o.threads).c_str(), 1);
        tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(o.threads));

        const vr::PeerScene scene = vr::loadPeerScene(o);
        fs::create_directories(out);
        nlohmann::json runs = nlohmann::json::array();
        std::ostringstream table;
        nlohmann::json skipped = nlohmann::json::array();
        table << "Settings: " << vr::settingsDescription(o) << ". Each peer's notes say where it differs.\n\n"
              << "| peer | median ms | p95 ms | image size | views | notes |\n|---|---:|---:|---|---:|---|\n";
        for (const std::string& name : peers) {
            std::string why = blendSkipReason(name, o.blend);
            if (why.empty() && o.userSettings) why = userSettingsSkipReason(name);
            if (!why.empty()) {
                std::fprintf(stderr, "%s: skipped (%s)\n", name.c_str(), why.c_str());
                skipped.push_back({{"peer", name}, {"reason", why}});
                table << "| " << name << " | - | - | - | - | skipped: " << why << " |\n";
                continue;
            }
            std::fprintf(stderr, "%s ...\n", name.c_str());
            char row[256];
            try {
                const vr::PeerRun run = runPeer(name, scene, out);
                runs.push_back(runJson(run, scene));
                std::snprintf(row, sizeof row, "| %s | %.1f | %.1f | %dx%d | %zu | ", name.c_str(), run.medianMs(),
                              run.p95Ms(), o.width, o.height, run.ms.size());
                table << row << run.notes << " (setup " << std::lround(run.setupMs) << " ms) |\n";
            } catch (const std::exception& e) {  // one peer failing must not lose the others' figures
                runs.push_back({{"peer", name}, {"error", e.what()}});
                table << "| " << name << " | - | - | - | - | failed: " << e.what() << " |\n";
            }
        }
        const nlohmann::json doc = {
            {"volume", volume}, {"transfer_function", tf}, {"spacing", {scene.volume.grid.spacing.x,
             scene.volume.grid.spacing.y, scene.volume.grid.spacing.z}}, {"views", o.views},
            {"width", o.width}, {"height", o.height}, {"step_voxels", o.stepVoxels},
            {"sample_distance", scene.sampleDistance()}, {"threads", o.threads}, {"settings", settingsJson(o)},
            {"blend", blend},
            {"peers", runs}, {"skipped", skipped}};
        vr::writeFileAtomically(fs::path(out) / "peers.json", [&](std::ostream& s) { s << doc.dump(2) << '\n'; });
        std::fputs(table.str().c_str(), stdout);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vr_peers: %s\n", e.what());
        return 1;
    }
    return 0;
}

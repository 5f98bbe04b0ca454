#include "bench/peers/reference_peer.h"

#include <chrono>

#include "preprocess/pipeline/staged_prepare.h"
#include "render/cpu_renderer.h"

namespace vr {

PeerRun runReferencePeer(const PeerScene& scene, const std::filesystem::path& outDir) {
    const auto setup = std::chrono::steady_clock::now();
    PrepareOptions options;
    options.classify.transferFunction = scene.tf;
    options.classify.normals = false;
    options.fields = 0;  // the primitive caster leaps nowhere
    const PreparedVolume prepared = prepare(loadVolume(scene.options.volume, scene.options.raw), options);
    const double setupMs = millisecondsSince(setup);

    RenderSettings settings;
    settings.caster = Caster::Primitive;
    settings.blend = scene.options.blend;
    settings.stepVoxels = scene.options.stepVoxels;
    settings.ert = scene.options.ert;
    // The primitive caster leaps nowhere, so trilinear sampling needs no trilinear regions; shading takes its
    // normals from the scalars' gradient at each sample (no normals in the classification).
    settings.trilinear = scene.options.userSettings;
    settings.shading = scene.options.userSettings && scene.options.blend == Blend::Composite;
    PeerRun run = runViews("ours-cpu-primitive", scene, outDir, [&](std::size_t i, Image& out) {
        const auto start = std::chrono::steady_clock::now();
        out = renderCpu(prepared, scene.views[i], settings).image;
        return millisecondsSince(start);
    });
    run.setupMs = setupMs;
    run.notes = scene.options.blend == Blend::MIP
                    ? std::string("our CPU reference (volrender --cpu --caster primitive --blend mip") +
                          (scene.options.userSettings ? ")" : " --nearest)") +
                          ": the image to compare with; double precision, not a speed contender"
                : scene.options.userSettings
                    ? "our CPU reference (volrender --cpu --caster primitive): trilinear, Phong with a headlight "
                      "(gradient interpolated per sample, then shaded); the image to compare with; double precision, "
                      "not a speed contender; setup = load + classify + segment"
                    : "our CPU reference (volrender --cpu --caster primitive --nearest --no-shading): the image to "
                      "compare with; double precision, not a speed contender; setup = load + classify + segment";
    return run;
}

}  // namespace vr

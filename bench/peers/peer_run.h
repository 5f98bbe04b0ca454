// One peer's run over the views: per-view times and images, and the loop that produces them.
#pragma once
#include <filesystem>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "bench/peers/peer_scene.h"
#include "render/image.h"

namespace vr {

struct PeerRun {
    std::string peer;   // e.g. "vtk-fixed-point"
    std::string notes;  // what differs from our renderer
    double setupMs = 0; // one-off work outside the per-view times (classification, conversion, first upload)
    std::vector<double> ms;                    // per view, after the warm-up
    std::vector<std::filesystem::path> images; // per view: linear float RGBA EXR (a PNG beside it for looking)

    double medianMs() const;
    double p95Ms() const;  // nearest rank
};

// Renders view `index` into `image` (row 0 = top, premultiplied linear RGBA over black) and returns the
// milliseconds the peer spent rendering it, as the peer measures it.
using RenderView = std::function<double(std::size_t index, Image& image)>;

// One warm-up render of view 0, then every view once, timed; images go to OUT/PEER/view_NNN.{exr,png}.
PeerRun runViews(const std::string& peer, const PeerScene& scene, const std::filesystem::path& outDir,
                 const RenderView& render);

// Milliseconds since `start` on the steady clock.
double millisecondsSince(std::chrono::steady_clock::time_point start);

}  // namespace vr

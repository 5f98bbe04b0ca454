// Our CPU reference (primitive caster, emission-absorption, double precision) on the same views: the image the
// peers are compared with, rendered in the same run so that the side-by-side needs nothing else.
#pragma once
#include <filesystem>

#include "bench/peers/peer_run.h"

namespace vr {

PeerRun runReferencePeer(const PeerScene& scene, const std::filesystem::path& outDir);

}  // namespace vr

// VolPack (Lacroute's shear-warp with run-length encoded classified volumes) on our views.
#pragma once
#include <filesystem>

#include "bench/peers/peer_run.h"

namespace vr {

PeerRun runVolPackPeer(const PeerScene& scene, const std::filesystem::path& outDir);

}  // namespace vr

// OpenVDB's vdb_render (its CPU volume ray marcher over the VDB tree) on our views, on the classified volume
// converted to a .vdb fog volume; one vdb_render process per view.
#pragma once
#include <filesystem>

#include "bench/peers/peer_run.h"

namespace vr {

PeerRun runVdbRenderPeer(const PeerScene& scene, const std::filesystem::path& outDir);

}  // namespace vr

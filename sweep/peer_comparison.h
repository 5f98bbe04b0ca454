// The peers (bench/peers, scripts/peers.sh) against our reference: their times and their images' error.
#pragma once
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "render/image.h"

namespace vr {

// Reads PEERSDIR/peers.json and compares each peer's view images with our reference image of the view at the
// same azimuth (elevation 0; `references` maps azimuth in degrees to image). Returns a JSON array, one object per
// peer: peer, notes, median_ms, views compared, psnr (of the mean MSE), ssim (mean), image and error_map (the
// first compared view's PNG and its |difference| x10, written beside it), or error when the peer failed or
// nothing could be compared. Throws InputError when peers.json is missing or malformed.
nlohmann::json comparePeers(const std::filesystem::path& peersDir, const std::map<double, Image>& references);

}  // namespace vr

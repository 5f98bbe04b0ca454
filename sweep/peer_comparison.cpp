#include "sweep/peer_comparison.h"

#include <cmath>
#include <fstream>

#include "core/errors.h"
#include "core/number_text.h"
#include "core/printable_text.h"
#include "sweep/metrics/image_error.h"

namespace vr {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const Image* referenceAt(const std::map<double, Image>& references, double azimuth) {
    for (const auto& [a, image] : references)
        if (std::abs(a - azimuth) < 1e-6) return &image;
    return nullptr;
}

json comparePeer(const json& peer, const std::map<double, Image>& references, const fs::path& peersDir) {
    json out{{"peer", peer.value("peer", "?")}, {"notes", peer.value("notes", "")}};
    if (peer.contains("error")) {
        out["error"] = peer["error"];
        return out;
    }
    out["median_ms"] = peer.value("median_ms", 0.0);
    std::vector<ImageError> errors;
    std::string problem;
    for (const json& view : peer.value("views", json::array())) {
        const Image* reference = referenceAt(references, view.value("azimuth_deg", -1.0));
        if (!reference) {
            problem = "no reference view at azimuth " + numberText(view.value("azimuth_deg", -1.0));
            continue;
        }
        fs::path path = view.value("image", "");
        if (path.is_relative() && !fs::exists(path)) path = peersDir / path;
        const Image image = readImage(path);
        if (image.width != reference->width || image.height != reference->height) {
            problem = "image size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                      " differs from ours";
            continue;
        }
        errors.push_back(imageError(*reference, image));
        if (!out.contains("image")) {  // the first compared view, for the report's strip: its PNG and error map
            const fs::path png = fs::path(path).replace_extension(".png"), map = path.parent_path() /
                                 (path.stem().string() + "_error.png");
            writeImage(map, errorMap(*reference, image));
            out["image"] = (fs::exists(png) ? png : path).string();
            out["error_map"] = map.string();
        }
    }
    out["views_compared"] = errors.size();
    if (errors.empty()) {
        out["error"] = "not compared: " + (problem.empty() ? std::string("no views") : problem);
        return out;
    }
    const ErrorSummary s = summarize(errors);
    out["psnr"] = std::isinf(s.mean.psnr) ? json("inf") : json(s.mean.psnr);
    out["ssim"] = s.mean.ssim;
    return out;
}

}  // namespace

json comparePeers(const fs::path& peersDir, const std::map<double, Image>& references) {
    const fs::path file = peersDir / "peers.json";
    std::ifstream in(file);
    if (!in) throw fileError(file.string(), "cannot read the peers' results (run scripts/peers.sh)");
    json doc;
    try {
        doc = json::parse(in);
    } catch (const json::exception& e) {
        throw fileError(file.string(), std::string("malformed JSON: ") + printableText(e.what()));
    }
    if (!doc.contains("peers") || !doc["peers"].is_array()) throw fileError(file.string(), "no \"peers\" array");
    json result = json::array();
    for (const json& peer : doc["peers"]) {
        try {
            result.push_back(comparePeer(peer, references, peersDir));
        } catch (const std::exception& e) {  // one unreadable peer image must not lose the others
            result.push_back({{"peer", peer.value("peer", "?")}, {"error", e.what()}});
        }
    }
    return result;
}

}  // namespace vr

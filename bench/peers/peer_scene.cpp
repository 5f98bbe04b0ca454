#include "bench/peers/peer_scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "preprocess/classify/transfer_choice.h"

namespace vr {

std::size_t PeerScene::tableIndex(float value) const {
    const double i = std::round((value - table.lo) / table.step);
    return std::size_t(std::clamp(i, 0.0, double(table.opacity.size() - 1)));
}

std::string settingsDescription(const PeerSceneOptions& options) {
    if (options.blend == Blend::MIP)
        return std::string("maximum intensity projection (--blend mip), ") +
               (options.userSettings ? "trilinear (linear) interpolation" : "nearest sampling") +
               ", the largest scalar shown in its TF colour at its TF opacity";
    if (!options.userSettings)
        return "nearest sampling, unshaded (emission-absorption only), the algorithm comparison (--user-settings: "
               "trilinear and shaded)";
    const ShadingModel m;
    std::ostringstream s;
    s << "the user settings (--user-settings): trilinear (linear) interpolation, shaded: Phong, ambient " << m.ambient
      << ", diffuse " << m.diffuse << ", specular " << m.specular << ", specular power " << m.shininess
      << ", one white headlight";
    return s.str();
}

CubicLattice::CubicLattice(const GridGeometry& grid) : size(grid.smallestSpacing()) {
    for (int a = 0; a < 3; ++a) {
        dims[a] = std::max(1, int(std::lround(grid.dims[a] * grid.spacing[a] / size)));
        for (int i = 0; i < dims[a]; ++i)
            source[a].push_back(std::min(grid.dims[a] - 1, int((i + 0.5) * size / grid.spacing[a])));
    }
}

SampledTransferFunction peerTable(const Volume& volume, const TransferFunction& tf) {
    const auto [lo, hi] = std::minmax_element(volume.values.begin(), volume.values.end());
    const bool integer = volume.sourceType != ScalarType::Float32;
    const std::size_t count = integer ? std::size_t(*hi - *lo) + 1 : 4096;
    return sampleTransferFunction(tf, *lo, std::max(*hi, *lo + 1.0f), std::max<std::size_t>(count, 2));
}

PeerScene loadPeerScene(const PeerSceneOptions& options) {
    if (options.views < 1) throw InputError("--views must be at least 1");
    if (!(options.stepVoxels > 0)) throw InputError("--step must be positive");
    PeerScene scene;
    scene.options = options;
    scene.volume = loadVolume(options.volume, options.raw);
    scene.tf = namedTransferFunction(options.transferFunction);  // a preset's name or a file, as --tf takes

    scene.table = peerTable(scene.volume, scene.tf);

    ViewParams view;
    view.width = options.width;
    view.height = options.height;
    view.elevationDeg = options.elevationDeg;
    for (int i = 0; i < options.views; ++i) {
        view.azimuthDeg = 360.0 * i / options.views;
        scene.views.push_back(Camera::fit(scene.volume.grid, view));
    }
    return scene;
}

}  // namespace vr

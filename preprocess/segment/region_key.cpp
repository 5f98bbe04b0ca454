#include "preprocess/segment/region_key.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/errors.h"

namespace vr {
namespace {

// Finer bins than these do not fit the 32-bit key fields; such thresholds compare bit for bit instead (stricter).
constexpr double kMinBinWidth = 1.0 / double(1u << 30);
constexpr double kMaxCellsPerEdge = 16384;  // 6 K^2 < 2^31

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

double cellsPerEdgeFor(double angleDeg) { return 2 * std::numbers::sqrt2 / (angleDeg * std::numbers::pi / 180); }

void checkThreshold(double value, const char* what) {
    if (!(value >= 0)) {
        std::ostringstream msg;
        msg << "segmentation: the " << what << " must be a number >= 0, got " << value;
        throw InputError(msg.str());
    }
}

}  // namespace

int cubeMapCellsPerEdge(double angleDeg) {
    if (angleDeg >= 180) return 0;
    return int(std::max(1.0, std::ceil(cellsPerEdgeFor(angleDeg))));
}

uint32_t cubeMapCell(const std::array<float, 3>& d, int cellsPerEdge) {
    if (cellsPerEdge == 0) return 0;
    int major = 0;
    for (int a = 1; a < 3; ++a)
        if (std::abs(d[a]) > std::abs(d[major])) major = a;
    const double scale = 1.0 / std::abs(double(d[major]));
    const auto cell = [&](float t) {
        const int c = int(std::floor((double(t) * scale + 1) * 0.5 * cellsPerEdge));
        return uint32_t(std::clamp(c, 0, cellsPerEdge - 1));
    };
    const uint32_t face = 2 * major + (d[major] < 0);
    const uint32_t k = uint32_t(cellsPerEdge);
    return (face * k + cell(d[(major + 2) % 3])) * k + cell(d[(major + 1) % 3]);
}

RegionKeyer::RegionKeyer(const ClassifiedVolume& classified, const SegmentationParams& params)
    : classified_(classified) {
    checkThreshold(params.opacityThreshold, "opacity threshold T_o");
    checkThreshold(params.angleThresholdDeg, "angle threshold T_a");
    opacityWidth_ = params.opacityThreshold >= kMinBinWidth ? params.opacityThreshold : 0.0;
    useNormals_ = params.useNormals && classified.hasNormals();
    exactNormals_ = params.angleThresholdDeg == 0 || cellsPerEdgeFor(params.angleThresholdDeg) > kMaxCellsPerEdge;
    if (!exactNormals_) cellsPerEdge_ = cubeMapCellsPerEdge(params.angleThresholdDeg);
}

uint32_t RegionKeyer::bin(double value, double width, float exact) const {
    if (width == 0) return bits(exact);
    return uint32_t(std::floor(std::clamp(value, 0.0, 1.0) / width));
}

RegionKey RegionKeyer::operator()(std::size_t i) const {
    RegionKey key;
    const float sigma = classified_.sigma[i];
    if (!(sigma > 0)) return key;  // transparent: nothing else matters
    key.opacity = opacityWidth_ > 0 ? 1 + bin(classified_.opacity(i), opacityWidth_, sigma) : bits(sigma);
    for (int c = 0; c < 3; ++c) key.colour[c] = bin(classified_.colour[i][c], opacityWidth_, classified_.colour[i][c]);
    if (useNormals_) {
        const std::array<float, 3>& n = classified_.normal[i];
        if (exactNormals_) {
            key.normal = {bits(n[0]), bits(n[1]), bits(n[2])};
        } else {
            const bool flat = n[0] == 0 && n[1] == 0 && n[2] == 0;
            key.normal[0] = flat ? 0 : 1 + cubeMapCell(n, cellsPerEdge_);
        }
    }
    return key;
}

}  // namespace vr

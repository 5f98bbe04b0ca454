#include "preprocess/segment/region_key.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <sstream>
#include <type_traits>
#include <vector>

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

void checkThresholds(const SegmentationParams& params) {
    checkThreshold(params.opacityThreshold, "opacity threshold T_o");
    checkThreshold(params.angleThresholdDeg, "angle threshold T_a");
}

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
    // |t * scale| <= 1 but for rounding, so the position is > -1, where truncation and floor agree once clamped
    // to 0 (floor is a library call without SSE4.1; this runs per voxel).
    const auto cell = [&](float t) {
        const int c = int((double(t) * scale + 1) * 0.5 * cellsPerEdge);
        return uint32_t(std::clamp(c, 0, cellsPerEdge - 1));
    };
    const uint32_t face = 2 * major + (d[major] < 0);
    const uint32_t k = uint32_t(cellsPerEdge);
    return (face * k + cell(d[(major + 2) % 3])) * k + cell(d[(major + 1) % 3]);
}

RegionKeyer::RegionKeyer(const ClassifiedVoxels& voxels, const SegmentationParams& params) : voxels_(voxels) {
    checkThresholds(params);
    opacityWidth_ = params.opacityThreshold >= kMinBinWidth ? params.opacityThreshold : 0.0;
    useNormals_ = params.useNormals && voxels.hasNormals();
    exactNormals_ = params.angleThresholdDeg == 0 || cellsPerEdgeFor(params.angleThresholdDeg) > kMaxCellsPerEdge;
    if (!exactNormals_) cellsPerEdge_ = cubeMapCellsPerEdge(params.angleThresholdDeg);
    if (opacityWidth_ > 0) {
        // Bins 0 .. 1 + 1/T_o (opacity 1 + bin), cells 0 .. 6 K^2 (1 + cell).
        binBits_ = std::bit_width(uint64_t(1 + std::floor(1.0 / opacityWidth_)));
        const int normalBits =
            !useNormals_    ? 0
            : exactNormals_ ? 96
                            : std::bit_width(std::max<uint64_t>(1, uint64_t(6) * cellsPerEdge_ * cellsPerEdge_));
        packs_ = 4 * binBits_ + normalBits <= 64 && !voxels.labelled();
    }
}

uint32_t RegionKeyer::bin(double value, double width, float exact) const {
    if (width == 0) return bits(exact);
    return uint32_t(std::clamp(value, 0.0, 1.0) / width);  // >= 0: the conversion is the floor
}

void RegionKeyer::opacityAndColour(const VoxelOptics& o, RegionKey& key) const {
    key.opacity = opacityWidth_ > 0 ? 1 + bin(voxels_.opacity(o.sigma), opacityWidth_, o.sigma) : bits(o.sigma);
    for (int c = 0; c < 3; ++c) key.colour[c] = bin(o.colour[c], opacityWidth_, o.colour[c]);
}

void RegionKeyer::normal(std::size_t i, RegionKey& key) const { normal(voxels_.normal(i), key); }

void RegionKeyer::normal(const std::array<float, 3>& n, RegionKey& key) const {
    if (exactNormals_) {
        key.normal = {bits(n[0]), bits(n[1]), bits(n[2])};
    } else {
        const bool flat = n[0] == 0 && n[1] == 0 && n[2] == 0;
        key.normal[0] = flat ? 0 : 1 + cubeMapCell(n, cellsPerEdge_);
    }
}

RegionKey RegionKeyer::operator()(std::size_t i) const {
    RegionKey key;
    key.label = voxels_.label(i);
    const VoxelOptics o = voxels_.optics(i);
    if (!(o.sigma > 0)) return key;  // transparent: nothing else matters but the label
    opacityAndColour(o, key);
    if (useNormals_) normal(i, key);
    return key;
}

RegionKey RegionKeyer::normalKey(std::size_t i) const {
    RegionKey key;
    normalKeys(i, 1, &key);
    return key;
}

void RegionKeyer::normalKeys(std::size_t first, std::size_t count, RegionKey* out) const {
    const std::size_t nx = std::size_t(voxels_.grid().dims.x);
    constexpr std::size_t kPiece = 256;
    std::array<std::array<float, 3>, kPiece> normals;
    for (std::size_t at = first, end = first + count; at < end;) {
        const std::size_t n = std::min({kPiece, end - at, nx - at % nx});  // within one row
        RegionKey* keys = out + (at - first);
        bool shown = false;
        for (std::size_t i = 0; i < n; ++i) {
            keys[i] = RegionKey{};
            keys[i].opacity = voxels_.sigma(at + i) > 0 ? 1 : 0;
            shown = shown || keys[i].opacity;
        }
        if (shown && useNormals_) {
            voxels_.normals(at, int(n), normals.data());
            for (std::size_t i = 0; i < n; ++i)
                if (keys[i].opacity) normal(normals[i], keys[i]);
        }
        at += n;
    }
}

PackedKey RegionKeyer::pack(const RegionKey& key) const {
    PackedKey p = key.opacity;
    for (int c = 0; c < 3; ++c) p |= PackedKey(key.colour[c]) << ((c + 1) * binBits_);
    return p | PackedKey(key.normal[0]) << (4 * binBits_);
}

template <typename Key>
void RegionKeyer::keysInto(std::size_t first, std::size_t count, Key* out) const {
    // A direct-mapped cache from (sigma, colour) bits to their bins: the bins are a function of those bits.
    struct Entry {
        std::array<uint32_t, 4> in{~0u, 0, 0, 0};  // sigma = NaN bits: never a voxel's (sigma > 0 here)
        uint32_t opacity = 0;
        std::array<uint32_t, 3> colour{};
    };
    constexpr unsigned kCacheBits = 10;
    std::vector<Entry> cache(std::size_t(1) << kCacheBits);
    for (std::size_t j = 0; j < count; ++j) {
        const std::size_t i = first + j;
        RegionKey key;
        key.label = voxels_.label(i);
        const VoxelOptics o = voxels_.optics(i);
        if (o.sigma > 0) {
            const std::array<uint32_t, 4> in{bits(o.sigma), bits(o.colour[0]), bits(o.colour[1]), bits(o.colour[2])};
            const uint32_t hash = (in[0] ^ (in[1] * 3) ^ (in[2] * 5) ^ (in[3] * 7)) * 2654435761u;
            Entry& e = cache[hash >> (32 - kCacheBits)];
            if (e.in[0] != in[0] || e.in[1] != in[1] || e.in[2] != in[2] || e.in[3] != in[3]) {
                e.in = in;
                opacityAndColour(o, key);
                e.opacity = key.opacity;
                e.colour = key.colour;
            }
            key.opacity = e.opacity;
            key.colour = e.colour;
            if (useNormals_) normal(i, key);
        }
        if constexpr (std::is_same_v<Key, PackedKey>) {
            out[j] = pack(key);
        } else {
            out[j] = key;
        }
    }
}

void RegionKeyer::keys(std::size_t first, std::size_t count, RegionKey* out) const { keysInto(first, count, out); }

void RegionKeyer::keys(std::size_t first, std::size_t count, PackedKey* out) const { keysInto(first, count, out); }

}  // namespace vr

// VulkanRenderer::renderStereo: a pair's right eye reprojected from its left, and cast again only where the
// reprojection cannot vouch for a pixel (docs/ALGORITHMS.md section 12).
#include <algorithm>
#include <cmath>
#include <cstring>

#include <tbb/parallel_for.h>

#include "volrender/vulkan/stereo_reprojector.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace vr {
namespace {

// The disparity one depth stands for in a pair (maxSpreadPixels: a composite band's width, another blend's narrow
// interval) and, for composite, the bands of that width from the disparity of the volume's nearest point to its
// farthest's (none where that takes more than device::kMaxBands).
struct Bands {
    double width = 0;
    double first = 0;
    int count = 0;
};

Bands bandsOf(const StereoPair& pair, const DepthRange& depths, bool composite) {
    Bands b{maxSpreadPixels(pair.left.height)};
    if (!composite || depths.nearest <= 0) return b;
    const double first = disparityAt(pair, depths.nearest);
    const double count = std::ceil((disparityAt(pair, depths.farthest) - first) / b.width);
    if (count <= device::kMaxBands) {
        b.first = first;
        b.count = std::max(1, int(count));
    }
    return b;
}

device::StereoParams reprojection(const StereoPair& pair, const DepthRange& depths, const RenderSettings& settings,
                                  const Bands& bands, int rowStride) {
    const Camera& left = pair.left;
    device::StereoParams p{};
    p.imageSize = {left.width, left.height};
    p.disparityScale = float(disparityScale(pair));
    p.focusInverse = float(1 / pair.focus);
    p.halfHeight = float(left.halfHeight);
    p.leftShift = float(left.shift);
    p.maxSpread = float(bands.width);
    p.maxStep = float(settings.blend == Blend::Composite ? kMaxBandStep : kMaxColourStep);
    p.maxGap = float(kMaxGapPixels);
    // The disparities lie between the volume's nearest point's and infinity's; eyes inside the volume search the row.
    const double nearest = depths.nearest;
    const double lowest = nearest > 0 ? std::max(disparityAt(pair, nearest), -double(left.width)) : -left.width;
    const double highest = std::min(disparityAt(pair, INFINITY), double(left.width));
    p.window = {int(std::floor(lowest)) - 2, int(std::ceil(highest)) + 2};
    p.background = {float(settings.background.x), float(settings.background.y), float(settings.background.z), 0};
    p.firstDisparity = float(bands.first);
    p.bandCount = bands.count;
    p.rowStride = rowStride;
    p.faintAlpha = float(kFaintAlpha);
    return p;
}

// A packed pixel's place in the order of 8 x 8 blocks (shaders/stereo_reprojection.h packListPixel).
uint64_t blockOrder(uint32_t pixel) {
    const uint64_t x = pixel & 0xffffu, y = pixel >> 16;
    return (y >> 3) << 48 | (x >> 3) << 32 | (y & 7) << 16 | (x & 7);
}

}  // namespace

VulkanRenderer::PairBuffers::PairBuffers(const VulkanContext& ctx, std::size_t pixels, std::size_t segments,
                                         std::size_t leftPixels)
    : pixels(pixels), segments(segments), leftPixels(leftPixels),
      left(ctx, std::max<std::size_t>(leftPixels, 1) * sizeof(device::OutPixel),
           vk::BufferUsageFlagBits::eStorageBuffer),
      right(ctx, pixels * sizeof(device::uvec4), vk::BufferUsageFlagBits::eStorageBuffer),
      recast(ctx, sizeof(uint32_t) + pixels * sizeof(device::ListRay), vk::BufferUsageFlagBits::eStorageBuffer) {
    if (segments > 0) bands.emplace(ctx, segments * sizeof(device::uvec4), kBandSegmentUsage);
}

VulkanRenderer::PairBuffers& VulkanRenderer::pairBuffers(std::size_t pixels, std::size_t segments,
                                                         std::size_t leftPixels) {
    if (!pair_ || pair_->pixels < pixels || pair_->segments < segments || pair_->leftPixels < leftPixels) {
        // As large as every pair so far has needed, so that pairs of alternating sizes do not make them afresh.
        const std::size_t p = std::max(pixels, pair_ ? pair_->pixels : 0);
        const std::size_t s = std::max(segments, pair_ ? pair_->segments : 0);
        const std::size_t l = std::max(leftPixels, pair_ ? pair_->leftPixels : 0);
        pair_.reset();  // the old ones freed before the larger are allocated
        pair_.emplace(ctx_, p, s, l);
    }
    return *pair_;
}

StereoRender VulkanRenderer::renderStereo(const GpuVolume& volume, const StereoPair& pair,
                                          const RenderSettings& settings, bool reuse) {
    StereoRender out;
    const int width = pair.left.width, height = pair.left.height;
    const std::size_t pixels = std::size_t(width) * height;
    const bool composite = settings.blend == Blend::Composite;
    const DepthRange depths = depthRange(pair, volume.grid());
    const Bands bands = bandsOf(pair, depths, composite);
    // The bands' segments in one buffer, bound whole as a storage buffer and as a texel buffer, then the plane of
    // the left pixels' masks of used bands (shaders/stereo_reprojection.h bandMaskTexel).
    const vk::PhysicalDeviceLimits limits = ctx_.physicalDevice().getProperties().limits;
    const uint64_t segments = bands.count > 0 ? uint64_t(pixels) * uint64_t(bands.count + 1) : 0;
    const bool segmentsFit = segments <= limits.maxTexelBufferElements &&
                             segments * sizeof(device::uvec4) <= limits.maxStorageBufferRange;
    if (!reuse || (composite && (bands.count == 0 || !segmentsFit))) {
        out.left = render(volume, pair.left, settings);
        out.right = render(volume, pair.right, settings);
        out.recast.assign(pixels, 1);
        out.recastFrom.assign(pixels, 0.0f);
        return out;
    }
    checkRender(volume, pair.left, settings);
    checkRender(volume, pair.right, settings);
    return deviceErrors([&] {
        // Composite reprojects the left eye's bands alone: its pixels stay in the frame's buffers.
        PairBuffers& buffers = pairBuffers(pixels, segments, composite ? 0 : pixels);
        const HostBuffer &right = buffers.right, &recast = buffers.recast;
        const DeviceBuffer* leftBands = composite ? &*buffers.bands : nullptr;
        const StereoLeft leftEye{composite ? nullptr : buffers.left.data(), leftBands,
                                 {float(disparityScale(pair)), float(1 / pair.focus), float(bands.first),
                                  float(bands.width)},
                                 bands.count};
        out.left = renderOnDevice(volume, pair.left, settings, nullptr, &leftEye);
        auto* count = static_cast<uint32_t*>(recast.data());
        auto* rays = reinterpret_cast<device::ListRay*>(count + 1);
        *count = 0;
        out.reprojectMilliseconds =
            reprojector().reproject(pool_, reprojection(pair, depths, settings, bands, rowStride(height)),
                                    buffers.left, leftBands, right, recast);
        // By the depth each ray starts from (the bands' near depths: a few values), then in blocks of 8 x 8 pixels
        // in row order, each block's pixels in row order: a SIMD batch's rays start together and stay close, so
        // that they take nearly as long (the device appended them in any order). Sorted by block alone, rays cast
        // whole and rays cast from deep bands shared batches, which waited on the whole ones: the re-casts took
        // about twice as long on lavapipe (docs/BENCH.md, stereo pairs).
        std::sort(rays, rays + *count, [](const device::ListRay& a, const device::ListRay& b) {
            if (a.startDepth != b.startDepth) return a.startDepth < b.startDepth;
            return blockOrder(a.pixel) < blockOrder(b.pixel);
        });
        PixelList recastPixels{recast, std::vector<uint32_t>(*count)};
        out.recast.assign(pixels, 0);
        out.recastFrom.assign(pixels, 0.0f);
        std::size_t inPart = 0;
        for (uint32_t i = 0; i < *count; ++i) {
            const uint32_t p = recastPixels.pixels[i] = rays[i].pixel;
            const std::size_t index = std::size_t(p >> 16) * width + (p & 0xffffu);
            out.recast[index] = 1;
            out.recastFrom[index] = rays[i].startDepth;
            inPart += rays[i].startDepth > 0;
        }
        recastPixels.pieces = piecesFor(volume.bricks().bricks().size() > 1, settings,
                                        recastPiecesAsked(recastPixels.pixels.size(), pixels));
        out.recastPieces = recastPixels.pieces;
        out.right = renderOnDevice(volume, pair.right, settings, &recastPixels);
        out.right.deviceMilliseconds += out.reprojectMilliseconds;
        const auto* reprojected = static_cast<const device::uvec4*>(right.data());
        tbb::parallel_for(std::size_t(0), pixels, [&](std::size_t i) {
            if (!out.recast[i]) std::memcpy(&out.right.image.rgba[4 * i], &reprojected[i], 4 * sizeof(float));
        });
        out.recastFraction = double(recastPixels.pixels.size()) / double(pixels);
        out.recastInPartFraction = double(inPart) / double(pixels);
        return out;
    });
}

}  // namespace vr

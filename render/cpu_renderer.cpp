// The CPU reference: one loop for the casters and the blends (docs/ALGORITHMS.md sections 5 and 11), double
// precision throughout. The caster only decides n, the number of lattice samples one fetch stands for; the blend
// what the ray makes of them. Each span is shaded once, at
// its first sample (as the thesis does); with a headlight or any directional light the shade is constant along
// a ray, so with thresholds 0 this equals shading every sample.
#include "render/cpu_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <climits>
#include <limits>
#include <optional>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/errors.h"
#include "core/gradient.h"
#include "render/block_extrema.h"
#include "render/flat_table_ends.h"
#include "render/ray_setup.h"
#include "render/render_checks.h"
#include "render/span.h"
#include "render/stored_gradients.h"
#include "shaders/blend.h"
#include "shaders/label_lookup.h"
#include "shaders/transfer_lookup.h"

namespace vr {
namespace {

struct SampleValue {
    double sigma = 0;
    Vec3d colour{0, 0, 0};
    Vec3d normal{0, 0, 0};  // unit, or zero where flat
};

// Every sample classified from the scalars (docs/ALGORITHMS.md section 2), as the casters classify it: the scalar
// (and, for shading, the gradient) at the sample, looked up in the transfer table; the formulas are
// shaders/transfer_lookup.h's, here in double.
class Sampler {
public:
    // stored: shade by the gradients it stores (render/stored_gradients.h); empty: by the scalars' differences.
    Sampler(const Volume& scalars, const ScalarClassification& c, const LabelMap* labels, bool trilinear,
            std::optional<GradientPacker> stored)
        : scalars_(scalars), c_(c), labels_(labels), trilinear_(trilinear), stored_(stored) {}

    // The scalar of the sample at grid position p, whose voxel is v: v's (nearest), or cell-centred trilinear
    // (voxel u's value sits at u + 0.5; clamped to the edge outside), interpolated before it is classified.
    double scalar(const Vec3d& p, const Vec3i& v) const {
        if (!trilinear_) return scalars_.at(v.x, v.y, v.z);
        const Cell c = cellOf(p);
        std::array<double, 8> s;
        for (int i = 0; i < 8; ++i) s[i] = scalars_.at(c.corner[i].x, c.corner[i].y, c.corner[i].z);
        return device::trilinearBlend(s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], c.f.x, c.f.y, c.f.z);
    }

    // The unit gradient at the sample, or zero where flat: v's central difference, or the same trilinear blend of
    // the corners' gradients as the scalar's. Where v's label shapes the normal (shaders/label_lookup.h), the
    // gradient of that label's smoothed indicator instead, taken the same way (flat only where it is 0).
    Vec3d normal(const Vec3d& p, const Vec3i& v) const {
        const std::size_t i = linearIndex(scalars_.grid.dims, v.x, v.y, v.z);
        if (labels_ && device::labelShapesNormal(device::labelSigmaOf(*labels_, i))) {
            const int l = labels_->label[i];
            return normalOf(gradientAt(p, v, [&](const Vec3i& u) {
                                return device::indicatorGradient(labels_->label, scalars_.grid.dims,
                                                                 scalars_.grid.spacing, u, l);
                            }),
                            0);
        }
        return normalOf(gradientAt(p, v,
                                   [&](const Vec3i& u) {
                                       return stored_ ? stored_->stored(scalars_, u)
                                                      : centralGradient(scalars_, u.x, u.y, u.z);
                                   }),
                        c_.flatGradient);
    }

    const Vec3i& dims() const { return scalars_.grid.dims; }

    SampleValue classified(double scalar) const {
        const device::TableSample t = device::lookUpTable(c_.table, scalar);
        return {t.sigma, {t.colour[0], t.colour[1], t.colour[2]}, {0, 0, 0}};
    }
    // The scalar's classification with the label of voxel v mixed in (shaders/label_lookup.h): never interpolated.
    SampleValue classified(double scalar, const Vec3i& v) const {
        SampleValue s = classified(scalar);
        if (!labels_) return s;
        const std::size_t i = linearIndex(scalars_.grid.dims, v.x, v.y, v.z);
        const std::size_t l = device::labelClassOf(*labels_, i);
        const double ls = labels_->classes.sigma[l];
        for (int a = 0; a < 3; ++a)
            s.colour[a] = device::labelledChannel(s.sigma, s.colour[a], ls, labels_->classes.colour[l][a]);
        s.sigma = device::labelledSigma(s.sigma, ls);
        return s;
    }

private:
    // The cell of a trilinear sample at p: its corners, clamped to the volume (x fastest: c000, c100, c010, c110,
    // c001, ...), and the weights of the upper ones.
    struct Cell {
        std::array<Vec3i, 8> corner;
        Vec3d f;
    };
    Cell cellOf(const Vec3d& p) const {
        const Vec3d q = p - Vec3d{0.5, 0.5, 0.5};
        const Vec3i base = floorVoxel(q);
        Cell c;
        c.f = q - Vec3d(base);
        for (int i = 0; i < 8; ++i)
            c.corner[i] = clampVoxel({base.x + (i & 1), base.y + ((i >> 1) & 1), base.z + ((i >> 2) & 1)},
                                     scalars_.grid.dims);
        return c;
    }

    // The gradient at the sample from `gradientAt(voxel)`: v's, or the trilinear blend of the corners' as the
    // scalar is blended.
    template <typename VoxelGradient>
    Vec3d gradientAt(const Vec3d& p, const Vec3i& v, const VoxelGradient& voxelGradient) const {
        if (!trilinear_) return voxelGradient(v);
        const Cell c = cellOf(p);
        std::array<Vec3d, 8> g;
        for (int i = 0; i < 8; ++i) g[i] = voxelGradient(c.corner[i]);
        Vec3d gradient;
        for (int a = 0; a < 3; ++a)
            gradient[a] = device::trilinearBlend(g[0][a], g[1][a], g[2][a], g[3][a], g[4][a], g[5][a], g[6][a],
                                                 g[7][a], c.f.x, c.f.y, c.f.z);
        return gradient;
    }

    // The unit gradient, or zero where the gradient is no longer than `flat`.
    static Vec3d normalOf(const Vec3d& g, double flat) {
        const double len = length(g);
        return len > flat ? g / len : Vec3d{0, 0, 0};
    }

    const Volume& scalars_;
    const ScalarClassification& c_;
    const LabelMap* labels_;
    bool trilinear_;
    std::optional<GradientPacker> stored_;
};

// What MIP, MinIP and average show (docs/ALGORITHMS.md section 11): the value's TF colour at the TF's opacity,
// or opaque (a grey window), over the background; the background alone for a ray without samples.
Vec3d shownValue(const Sampler& sampler, const ScalarClassification& c, double value, bool sampled, bool opaque,
                 const Vec3d& background, double& alpha) {
    if (!sampled) {
        alpha = 0;
        return background;
    }
    const SampleValue s = sampler.classified(value);
    alpha = opaque ? 1 : opacityFromExtinction(s.sigma, c.referenceStep);
    return s.colour * alpha + background * (1 - alpha);
}

// The extents of the box from v to the far faces of its block of `size` voxels in the ray's octant: a block's leap
// (shaders/blend.h).
Vec3i blockExtents(const Vec3i& v, int oct, int size) {
    Vec3i ext;
    for (int a = 0; a < 3; ++a) ext[a] = device::blockExtent(v[a], octantSign(oct, a), size);
    return ext;
}

// The iso-surface between samples k - 1 and k of the ray, on opposite sides of the iso-value: the interval halved
// kIsoBisections times by the side of the interpolated scalar at its middle, the hit at the middle of the last one.
// Returns its TF colour, shaded with the normal there.
Vec3d isoSurface(const Sampler& sampler, const GridRay& g, const RayClip& clip, const RayInterval& iv, double dt,
                 int64_t k, double iso, bool shading, const Vec3d& toEye, const Vec3d& toLight) {
    double before = latticeT(iv, dt, k - 1), beyond = latticeT(iv, dt, k);
    const bool insideBeyond = device::isoInside(sampler.scalar(g.at(beyond), sampleVoxel(g, beyond, clip)), iso);
    for (int i = 0; i < device::kIsoBisections; ++i) {
        const double middle = (before + beyond) / 2;
        const bool insideMiddle = device::isoInside(sampler.scalar(g.at(middle), sampleVoxel(g, middle, clip)), iso);
        (insideMiddle == insideBeyond ? beyond : before) = middle;
    }
    const double t = (before + beyond) / 2;
    const Vec3d colour = sampler.classified(iso).colour;
    return shading ? shade(colour, sampler.normal(g.at(t), sampleVoxel(g, t, clip)), toEye, toLight) : colour;
}

}  // namespace

RenderResult renderCpu(const PreparedVolume& prepared, const Camera& camera, const RenderSettings& settings) {
    checkRenderInputs(prepared, settings);
    floatValues(prepared.scalars);  // the samplers read them
    const auto start = std::chrono::steady_clock::now();

    const GridGeometry& grid = prepared.grid();
    const DistanceFields& fields = prepared.fields;
    const Vec3i dims = grid.dims;
    const double dt = settings.stepVoxels * grid.smallestSpacing(), ertDepth = terminationDepth(settings.ert);
    const Sampler sampler(prepared.scalars, prepared.classification, prepared.labels ? &*prepared.labels : nullptr,
                          settings.trilinear,
                          settings.readsStoredGradients()
                              ? std::optional(GradientPacker(prepared.scalars, prepared.classification.table))
                              : std::nullopt);
    const Blend blend = settings.blend;
    const int deviceBlend = int(blend);  // shaders/blend.h's numbering
    static_assert(int(Blend::Iso) == device::kBlendIso && int(Blend::Average) == device::kBlendAverage);
    const double iso = settings.isoValue;
    const std::optional<BlockExtrema> blocks =
        settings.caster == Caster::Blocks ? std::optional(blockExtrema(prepared.scalars)) : std::nullopt;
    // MIP and MinIP with blocks start, probe and end a sampled block as the device's casters do (shaders/blend.h).
    const bool extremeBlocks = blocks && device::keepsExtreme(deviceBlend);
    const FlatTableEnds flat =
        extremeBlocks ? flatTableEnds(prepared.classification.table, settings.opaqueValues) : FlatTableEnds{};
    // ACD and EACD may hold only the octants some views need (volrender's one-command path).
    const unsigned heldOctants = settings.caster == Caster::ACD    ? fields.acdOctants()
                                 : settings.caster == Caster::EACD ? fields.eacdOctants()
                                 : settings.caster == Caster::Hier ? fields.hier.octants()
                                                                   : kAllOctants;
    static_assert(kHomogeneousBlockBit == device::kHomogeneousBlock);
    const std::optional<Vec3d> light =
        settings.lightDirection ? std::optional<Vec3d>(normalize(*settings.lightDirection)) : std::nullopt;

    RenderResult result = RenderResult::blank(camera.width, camera.height);
    const RayClip clip = RayClip::of(grid, settings);

    // Leaps by the casters' margin where they take it (leapsByTheMargin), so that both leap alike.
    const bool marginLeaps = leapsByTheMargin(grid, camera, dt);
    auto trace = [&](int px, int py) {
        const Ray ray = camera.ray(px + 0.5, py + 0.5);
        const GridRay g = toGridRay(ray, grid);
        const RayInterval iv = settings.jitter ? jitteredInterval(clipInterval(g, clip), dt, device::jitterFraction(
                                                                    device::uint(px), device::uint(py)))
                                               : clipInterval(g, clip);
        const int64_t kCount = latticeCount(iv, dt);
        const LeapSlack slack = marginLeaps ? leapSlack(g, iv, grid.dims) : LeapSlack{};
        const int oct = rayOctant(g);
        const Vec3d toEye = -ray.direction;
        const Vec3d toLight = light ? *light : toEye;

        Accumulator acc;
        // The other blends' running values: the largest or smallest scalar, the sum, the iso-surface's side. The
        // blocks caster starts MIP and MinIP where the table stops changing what they show, as the device's casters
        // do (shaders/blend.h initialRunning), so that auto's probe counts their iterations; the primitive caster,
        // the plain definition, at -inf and +inf: the images are the same.
        double running = blend == Blend::MinIP ? std::numeric_limits<double>::infinity()
                                               : -std::numeric_limits<double>::infinity();
        if (extremeBlocks)
            running = device::initialRunning(deviceBlend, flat.above, flat.below);
        double sum = 0;
        bool inside = false, hit = false;
        long long iterations = 0;
        // MIP and MinIP with blocks: the running value starts at the probe samples (shaders/blend.h).
        if (extremeBlocks && kCount > 0 && kCount <= INT32_MAX)
            for (int i = 0; i < device::kProbes; ++i, ++iterations) {
                const double t = latticeT(iv, dt, device::probeSample(i, device::uint(kCount)));
                running = device::foldRunning(deviceBlend, running, sampler.scalar(g.at(t), sampleVoxel(g, t, clip)));
            }
        int64_t blockEnd = 0;  // blocks: the samples before it lie in a block that could change the result
        double finestLo = 0, finestHi = 0;  // that block's scalar range
        int64_t k = 0;  // the next lattice sample: also the samples the spans so far represent
        for (int64_t n = 1; k < kCount && acc.alpha < settings.ert; k += n) {
            if (++iterations > settings.maxIterationsPerRay)
                throw std::runtime_error("CPU renderer: a ray at pixel (" + std::to_string(px) + ", " +
                                         std::to_string(py) + ") passed the iteration cap of " +
                                         std::to_string(settings.maxIterationsPerRay) + " (a bug)");
            const double t = latticeT(iv, dt, k);
            const Vec3i v = sampleVoxel(g, t, clip);
            const std::size_t i = linearIndex(dims, v.x, v.y, v.z);
            // Blocks, at a new block: the coarsest block that cannot change the result is leapt over without a
            // sample (average adds its one value n times); else the finest block's samples are taken one by one,
            // without another lookup.
            if (blocks && k >= blockEnd) {
                int size = 0;
                double value = 0;
                // Fine to coarse: a block contains its finer ones, so it can be leapt only where they can.
                for (int level = 0;
                     level < device::kBlockLevels && size == (level == 0 ? 0 : device::kBlockSize << (level - 1));
                     ++level)
                    if (device::blockSkipped(deviceBlend, blocks->lo(level, v), blocks->hi(level, v), running, iso,
                                             inside)) {
                        size = device::kBlockSize << level;
                        value = blocks->lo(level, v);
                    }
                const Vec3i ext = blockExtents(v, oct, size > 0 ? size : device::kBlockSize);
                n = leapCount(g, iv, dt, k, kCount, boxLeapSamples(boxExitT(g, v, oct, ext, slack), t, dt),
                              octantBox(v, oct, ext));
                if (size > 0) {
                    sum += double(n) * value;
                    continue;
                }
                blockEnd = k + n;
                finestLo = blocks->lo(0, v);
                finestHi = blocks->hi(0, v);
            }
            const double scalar = sampler.scalar(g.at(t), v);
            if (blend == Blend::Iso) {  // the surface lies between the last sample and this one: refined below
                hit = k > 0 && device::isoInside(scalar, iso) != inside;
                if (hit) break;
                inside = device::isoInside(scalar, iso);
            }
            running = device::foldRunning(deviceBlend, running, scalar);
            // MIP and MinIP: once the running value passes the sampled block's range, the ray leaps to its end.
            if (extremeBlocks && k + 1 < blockEnd &&
                device::blockSkipped(deviceBlend, finestLo, finestHi, running, iso, inside)) {
                n = blockEnd - k;
                continue;
            }
            const SampleValue s = blend == Blend::Composite ? sampler.classified(scalar, v) : SampleValue{};

            double wanted = 1;
            VoxelBox box{v, v};
            switch (settings.caster) {
                case Caster::Primitive: break;
                case Caster::PC:
                    wanted = pcLeapSamples(fields.pc[i], dt, g, slack);
                    box = chebyshevBall(v, fields.pc[i]);
                    break;
                case Caster::ACD: {
                    if (!(heldOctants >> oct & 1u)) break;  // no field for this ray: it steps sample by sample
                    // A stored 0 would be a corrupt field; 1 (this voxel) is always true.
                    const int e = std::max<int>(1, fields.acd[oct][i]);
                    box = octantBox(v, oct, {e, e, e});
                    wanted = boxLeapSamples(boxExitT(g, v, oct, {e, e, e}, slack), t, dt);
                    break;
                }
                case Caster::EACD: {
                    if (!(heldOctants >> oct & 1u)) break;
                    const auto& x = fields.eacd[oct][i];
                    const Vec3i ext{std::max<int>(1, x[0]), std::max<int>(1, x[1]), std::max<int>(1, x[2])};
                    box = octantBox(v, oct, ext);
                    wanted = boxLeapSamples(boxExitT(g, v, oct, ext, slack), t, dt);
                    break;
                }
                case Caster::Hier: {
                    if (!(heldOctants >> oct & 1u)) break;
                    // A mixed block is stepped sample by sample; a homogeneous one leaps to its box's far faces.
                    const uint16_t code = fields.hier.code(oct, v);
                    if (!(code & kHomogeneousBlockBit)) break;
                    const Extents blocks = decodeExtents(ExtentCode::Log16, code);
                    Vec3i ext;
                    for (int a = 0; a < 3; ++a)
                        ext[a] = device::blockBoxExtent(v[a], octantSign(oct, a), fields.hier.blockShift, blocks[a]);
                    box = octantBox(v, oct, ext);
                    wanted = boxLeapSamples(boxExitT(g, v, oct, ext, slack), t, dt);
                    break;
                }
                case Caster::Blocks: break;  // one sample here (above: its leaps)
            }
            // The primitive caster steps one sample (n = 1): it needs no termination count and no leap check.
            n = 1;
            if (settings.caster != Caster::Primitive && settings.caster != Caster::Blocks) {
                if (settings.trilinear) wanted = trilinearLeapSamples(wanted, box);
                wanted = std::min(wanted, samplesToTermination(acc.depth, s.sigma, dt, ertDepth));
                n = leapCount(g, iv, dt, k, kCount, wanted, box);
            }
            if (blend == Blend::Average) sum += double(n) * scalar;
            if (blend != Blend::Composite) continue;

            const double length = double(n) * dt, spanAlpha = spanOpacity(s.sigma, length);
            if (spanAlpha > 0) {
                const Vec3d shaded =
                    settings.shading ? shade(s.colour, sampler.normal(g.at(t), v), toEye, toLight) : s.colour;
                acc.composite(shaded, spanAlpha, s.sigma * length);
            }
        }

        Vec3d c = acc.colour + settings.background * (1 - acc.alpha);
        double alpha = acc.alpha;
        const ScalarClassification& classification = prepared.classification;
        if (blend == Blend::MIP || blend == Blend::MinIP)
            c = shownValue(sampler, classification, running, kCount > 0, settings.opaqueValues, settings.background,
                           alpha);
        if (blend == Blend::Average)
            c = shownValue(sampler, classification, sum / double(kCount), kCount > 0, settings.opaqueValues,
                           settings.background, alpha);
        if (blend == Blend::Iso) {
            alpha = hit ? 1 : 0;
            c = hit ? isoSurface(sampler, g, clip, iv, dt, k, iso, settings.shading, toEye, toLight)
                    : settings.background;
        }
        const std::size_t p = std::size_t(py) * camera.width + px;
        float* out = result.image.pixel(px, py);
        out[0] = float(c.x);
        out[1] = float(c.y);
        out[2] = float(c.z);
        out[3] = float(alpha);
        result.iterations[p] = uint32_t(std::min<long long>(iterations, UINT32_MAX));
        result.samples[p] = uint64_t(k);
    };

    tbb::parallel_for(tbb::blocked_range<int>(0, camera.height), [&](const tbb::blocked_range<int>& rows) {
        for (int py = rows.begin(); py < rows.end(); ++py)
            for (int px = 0; px < camera.width; ++px) trace(px, py);
    });

    result.wallMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace vr

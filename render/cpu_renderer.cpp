// The CPU reference: one loop for the four casters (docs/ALGORITHMS.md section 5), double precision throughout.
// The caster only decides n, the number of lattice samples one fetch stands for. Each span is shaded once, at
// its first sample (as the thesis does); with a headlight or any directional light the shade is constant along
// a ray, so with thresholds 0 this equals shading every sample.
#include "render/cpu_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <climits>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/errors.h"
#include "core/gradient.h"
#include "render/ray_setup.h"
#include "render/render_checks.h"
#include "render/span.h"
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
    Sampler(const Volume& scalars, const ScalarClassification& c, bool shading)
        : scalars_(scalars), c_(c), shading_(shading) {}

    SampleValue nearest(const Vec3i& v) const {
        SampleValue s = classified(scalars_.at(v.x, v.y, v.z));
        if (shading_) s.normal = normalOf(centralGradient(scalars_, v.x, v.y, v.z));
        return s;
    }

    // Cell-centred trilinear: voxel v's value sits at v + 0.5; clamped to the edge outside. The scalar is
    // interpolated, then classified (post-classification); the gradient is the same blend of the corners' gradients.
    SampleValue trilinear(const Vec3d& p) const {
        const Vec3i& dims = scalars_.grid.dims;
        const Vec3d q = p - Vec3d{0.5, 0.5, 0.5};
        const Vec3i base = floorVoxel(q);
        const Vec3d f = q - Vec3d(base);
        std::array<Vec3i, 8> corner;  // x fastest: c000, c100, c010, c110, c001, ...
        for (int c = 0; c < 8; ++c)
            corner[c] = clampVoxel({base.x + (c & 1), base.y + ((c >> 1) & 1), base.z + ((c >> 2) & 1)}, dims);
        auto blend = [&](auto value) {
            std::array<double, 8> v;
            for (int c = 0; c < 8; ++c) v[c] = value(corner[c]);
            return device::trilinearBlend(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], f.x, f.y, f.z);
        };
        SampleValue s = classified(blend([&](const Vec3i& u) { return double(scalars_.at(u.x, u.y, u.z)); }));
        if (shading_) {
            std::array<Vec3d, 8> g;
            for (int c = 0; c < 8; ++c) g[c] = centralGradient(scalars_, corner[c].x, corner[c].y, corner[c].z);
            Vec3d gradient;
            for (int a = 0; a < 3; ++a)
                gradient[a] = device::trilinearBlend(g[0][a], g[1][a], g[2][a], g[3][a], g[4][a], g[5][a], g[6][a],
                                                     g[7][a], f.x, f.y, f.z);
            s.normal = normalOf(gradient);
        }
        return s;
    }

private:
    SampleValue classified(double scalar) const {
        const device::TableSample t = device::lookUpTable(c_.table, scalar);
        return {t.sigma, {t.colour[0], t.colour[1], t.colour[2]}, {0, 0, 0}};
    }

    // The unit gradient, or zero where the gradient is no longer than the flat length.
    Vec3d normalOf(const Vec3d& g) const {
        const double len = length(g);
        return len > c_.flatGradient ? g / len : Vec3d{0, 0, 0};
    }

    const Volume& scalars_;
    const ScalarClassification& c_;
    bool shading_;
};

}  // namespace

RenderResult renderCpu(const PreparedVolume& prepared, const Camera& camera, const RenderSettings& settings) {
    checkRenderInputs(prepared, settings);
    const auto start = std::chrono::steady_clock::now();

    const GridGeometry& grid = prepared.grid();
    const DistanceFields& fields = prepared.fields;
    const Vec3i dims = grid.dims;
    const double dt = settings.stepVoxels * grid.smallestSpacing(), ertDepth = terminationDepth(settings.ert);
    const Sampler sampler(prepared.scalars, prepared.classification, settings.shading);
    // ACD and EACD may hold only the octants some views need (volrender's one-command path).
    const unsigned heldOctants = settings.caster == Caster::ACD    ? fields.acdOctants()
                                 : settings.caster == Caster::EACD ? fields.eacdOctants()
                                                                   : kAllOctants;
    const std::optional<Vec3d> light =
        settings.lightDirection ? std::optional<Vec3d>(normalize(*settings.lightDirection)) : std::nullopt;

    RenderResult result = RenderResult::blank(camera.width, camera.height);
    const RayClip clip = RayClip::of(grid, settings);

    auto trace = [&](int px, int py) {
        const Ray ray = camera.ray(px + 0.5, py + 0.5);
        const GridRay g = toGridRay(ray, grid);
        const RayInterval iv = clipInterval(g, clip);
        const int64_t kCount = latticeCount(iv, dt);
        const int oct = rayOctant(g);
        const Vec3d toEye = -ray.direction;
        const Vec3d toLight = light ? *light : toEye;

        Accumulator acc;
        long long iterations = 0;
        int64_t k = 0;  // the next lattice sample: also the samples the spans so far represent
        for (int64_t n = 1; k < kCount && acc.alpha < settings.ert; k += n) {
            if (++iterations > settings.maxIterationsPerRay)
                throw std::runtime_error("CPU renderer: a ray at pixel (" + std::to_string(px) + ", " +
                                         std::to_string(py) + ") passed the iteration cap of " +
                                         std::to_string(settings.maxIterationsPerRay) + " (a bug)");
            const double t = latticeT(iv, dt, k);
            const Vec3i v = sampleVoxel(g, t, clip);
            const std::size_t i = linearIndex(dims, v.x, v.y, v.z);
            const SampleValue s = settings.trilinear ? sampler.trilinear(g.at(t)) : sampler.nearest(v);

            double wanted = 1;
            VoxelBox box{v, v};
            switch (settings.caster) {
                case Caster::Primitive: break;
                case Caster::PC:
                    wanted = pcLeapSamples(fields.pc[i], dt, g);
                    box = chebyshevBall(v, fields.pc[i]);
                    break;
                case Caster::ACD: {
                    if (!(heldOctants >> oct & 1u)) break;  // no field for this ray: it steps sample by sample
                    // A stored 0 would be a corrupt field; 1 (this voxel) is always true.
                    const int e = std::max<int>(1, fields.acd[oct][i]);
                    box = octantBox(v, oct, {e, e, e});
                    wanted = boxLeapSamples(boxExitT(g, v, oct, {e, e, e}), t, dt);
                    break;
                }
                case Caster::EACD: {
                    if (!(heldOctants >> oct & 1u)) break;
                    const auto& x = fields.eacd[oct][i];
                    const Vec3i ext{std::max<int>(1, x[0]), std::max<int>(1, x[1]), std::max<int>(1, x[2])};
                    box = octantBox(v, oct, ext);
                    wanted = boxLeapSamples(boxExitT(g, v, oct, ext), t, dt);
                    break;
                }
            }
            // The primitive caster steps one sample (n stays 1): it needs no termination count and no leap check.
            if (settings.caster != Caster::Primitive) {
                if (settings.trilinear) wanted = trilinearLeapSamples(wanted, box);
                wanted = std::min(wanted, samplesToTermination(acc.depth, s.sigma, dt, ertDepth));
                n = leapCount(g, iv, dt, k, kCount, wanted, box);
            }

            const double length = double(n) * dt, spanAlpha = spanOpacity(s.sigma, length);
            if (spanAlpha > 0)
                acc.composite(settings.shading ? shade(s.colour, s.normal, toEye, toLight) : s.colour, spanAlpha,
                              s.sigma * length);
        }

        const std::size_t p = std::size_t(py) * camera.width + px;
        float* out = result.image.pixel(px, py);
        const Vec3d c = acc.colour + settings.background * (1 - acc.alpha);
        out[0] = float(c.x);
        out[1] = float(c.y);
        out[2] = float(c.z);
        out[3] = float(acc.alpha);
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

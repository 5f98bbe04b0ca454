#include "support/blend_cases.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "datasets/phantoms.h"
#include "preprocess/classify/transfer_choice.h"
#include "render/ray_setup.h"
#include "shaders/blend.h"
#include "shaders/transfer_lookup.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/volumes.h"
#include "support/views.h"

namespace vr::test {
namespace {

std::string blendText(Blend b) { return std::string(blendName(b)); }

BlendVolume blendVolume(const std::string& name, const Volume& volume, const std::string& tf) {
    const auto [lo, hi] = std::minmax_element(volume.values.begin(), volume.values.end());
    // Between two integers, so that no integer voxel lies on the surface.
    const double iso = std::floor((double(*lo) + double(*hi)) / 2) + 0.25;
    return {name, prepareVolume(volume, datasetTransferFunction(tf), {0, 0, false, false}, 0), iso};
}

// Noise in float scalars, whose blends round (the block extrema are widened for them).
Volume floatNoise() {
    Volume v = noisePhantom({20, 21, 22}, 11);
    for (float& x : v.values) x = x * 1.37f + 0.1f;
    v.sourceType = ScalarType::Float32;
    return v;
}

// The first `count` of: a diagonal, a perspective view, views along -z, -x and +y, and a diagonal in another octant.
std::vector<ViewParams> blendViews(int size, std::size_t count) {
    std::vector<ViewParams> views{orbitView(37, 23, size, size),
                                  orbitView(25, 35, size, size, Projection::Perspective),
                                  orbitView(0, 0, size, size),
                                  orbitView(90, 0, size, size),
                                  orbitView(0, -90, size, size),
                                  orbitView(-130, -50, size, size)};
    views.resize(std::min(count, views.size()));
    return views;
}

std::string where(const std::string& volume, Blend blend, bool trilinear, const std::string& view) {
    return volume + " " + blendText(blend) + (trilinear ? " trilinear" : " nearest") + " " + view;
}

std::string viewText(const ViewParams& v) {
    return "az " + std::to_string(v.azimuthDeg) + " el " + std::to_string(v.elevationDeg) +
           (v.projection == Projection::Perspective ? " perspective" : " ortho");
}

// The colour and alpha a blend shows for a scalar value (MIP, MinIP, average), over a black background.
std::array<double, 4> shown(const PreparedVolume& p, double value) {
    const device::TableSample s = device::lookUpTable(p.classification.table, value);
    const double alpha = opacityFromExtinction(s.sigma, p.classification.referenceStep);
    return {s.colour[0] * alpha, s.colour[1] * alpha, s.colour[2] * alpha, alpha};
}

// The scalar at grid position p: the voxel's, or the trilinear interpolation of the cell-centred voxel values,
// written as the weighted sum of the 8 corners.
double bruteScalar(const Volume& v, const Vec3d& p, bool trilinear) {
    const Vec3i dims = v.grid.dims;
    if (!trilinear) {
        const Vec3i u = clampVoxel(floorVoxel(p), dims);
        return v.at(u.x, u.y, u.z);
    }
    const Vec3d q = p - Vec3d{0.5, 0.5, 0.5};
    const Vec3i base = floorVoxel(q);
    const Vec3d f = q - Vec3d(base);
    double sum = 0;
    for (int c = 0; c < 8; ++c) {
        const Vec3i corner = clampVoxel({base.x + (c & 1), base.y + (c >> 1 & 1), base.z + (c >> 2 & 1)}, dims);
        const double w = ((c & 1) ? f.x : 1 - f.x) * ((c >> 1 & 1) ? f.y : 1 - f.y) * ((c >> 2 & 1) ? f.z : 1 - f.z);
        sum += w * v.at(corner.x, corner.y, corner.z);
    }
    return sum;
}

// What a blend shows at one pixel, from every sample of its ray, and the samples to the iso-crossing.
struct BruteForce {
    std::array<double, 4> rgba{0, 0, 0, 0};
    uint64_t samples = 0;
};

BruteForce bruteForce(const PreparedVolume& p, const Camera& camera, int px, int py, const RenderSettings& s) {
    const Ray ray = camera.ray(px + 0.5, py + 0.5);
    const GridRay g = toGridRay(ray, p.grid());
    const RayInterval iv = intersectGrid(g, p.grid().dims);
    const double dt = s.stepVoxels * p.grid().smallestSpacing();
    const int64_t count = latticeCount(iv, dt);
    std::vector<double> values;
    for (int64_t k = 0; k < count; ++k)
        values.push_back(bruteScalar(p.scalars, g.at(latticeT(iv, dt, k)), s.trilinear));
    BruteForce b;
    b.samples = uint64_t(count);
    if (values.empty()) return b;
    if (s.blend == Blend::MIP) b.rgba = shown(p, *std::max_element(values.begin(), values.end()));
    if (s.blend == Blend::MinIP) b.rgba = shown(p, *std::min_element(values.begin(), values.end()));
    if (s.blend == Blend::Average)
        b.rgba = shown(p, std::accumulate(values.begin(), values.end(), 0.0) / double(values.size()));
    if (s.blend == Blend::Iso)
        for (std::size_t k = 1; k < values.size(); ++k)
            if ((values[k] >= s.isoValue) != (values[k - 1] >= s.isoValue)) {
                const device::TableSample c = device::lookUpTable(p.classification.table, s.isoValue);
                b.rgba = {c.colour[0], c.colour[1], c.colour[2], 1};
                b.samples = k;
                break;
            }
    return b;
}

// Renders `s` with the blocks caster and the primitive one: equal images and samples, and no pixel with more
// iterations. Returns the iterations of both.
std::pair<double, double> expectBlocksEqualPrimitive(const RenderFn& render, const PreparedVolume& p,
                                                     const Camera& camera, RenderSettings s, double tolerance,
                                                     const std::string& what, CaseCount& n) {
    s.caster = Caster::Primitive;
    const RenderResult primitive = render(p, camera, s);
    s.caster = Caster::Blocks;
    const RenderResult blocks = render(p, camera, s);
    n.renders += 2;
    n.rays += camera.width * camera.height;
    for (uint64_t k : primitive.samples) n.hits += k > 0;
    EXPECT_LE(maxAbsDifference(primitive.image, blocks.image), tolerance) << what;
    EXPECT_EQ(primitive.samples, blocks.samples) << what;
    // Each iteration stands for one sample or more; MIP and MinIP add their probes.
    const uint32_t probes = device::keepsExtreme(int(s.blend)) ? device::kProbes : 0;
    std::size_t worse = 0;
    for (std::size_t i = 0; i < blocks.iterations.size(); ++i)
        worse += blocks.iterations[i] > primitive.iterations[i] + probes;
    EXPECT_EQ(worse, 0u) << what;
    return {std::accumulate(primitive.iterations.begin(), primitive.iterations.end(), 0.0),
            std::accumulate(blocks.iterations.begin(), blocks.iterations.end(), 0.0)};
}

// A camera looking along +axis (or -axis) through the centre of every voxel column of the volume (spacing 1,
// origin 0): one pixel per column, 1 voxel apart; `flipped` looks the other way with right mirrored.
Camera columnCamera(const Vec3i& dims, int axis, bool flipped) {
    const int a = axis, b = (axis + 1) % 3, c = (axis + 2) % 3;  // forward, right, up's axes
    Vec3d eye, forward{0, 0, 0}, right{0, 0, 0};
    eye[a] = flipped ? dims[a] + 1.0 : -1.0;
    eye[b] = dims[b] / 2.0;
    eye[c] = dims[c] / 2.0;
    forward[a] = flipped ? -1 : 1;
    right[b] = flipped ? -1 : 1;
    return orthoCamera(eye, forward, right, dims[b], dims[c], dims[c] / 2.0);
}

}  // namespace

const std::vector<BlendVolume>& blendVolumes() {
    static const std::vector<BlendVolume> volumes{
        blendVolume("engine", enginePhantom({40, 36, 30}, {0.8, 0.8, 1.2}), "mri.tf.json"),
        blendVolume("shells", shellsPhantom({36, 32, 24}, {1, 1, 2}), "cranium_ct.tf.json"),
        blendVolume("noise", noisePhantom({20, 21, 22}, 7), "mri.tf.json"),
        blendVolume("float noise", floatNoise(), "mri.tf.json"),
        blendVolume("cranium_ct block", centralBlock(loadDataset("cranium_ct"), 48), "cranium_ct.tf.json")};
    return volumes;
}

RenderSettings blendSettings(Blend blend, Caster caster, bool trilinear, double isoValue) {
    RenderSettings s;
    s.blend = blend;
    s.caster = caster;
    s.trilinear = trilinear;
    s.shading = blend == Blend::Iso;
    s.isoValue = isoValue;
    return s;
}

CaseCount blocksEqualPrimitive(const RenderFn& render, const BlendCaseOptions& options) {
    CaseCount n;
    for (const BlendVolume& v : blendVolumes())
        for (Blend blend : kScalarBlends) {
            double primitive = 0, blocks = 0;
            for (bool trilinear : {false, true})
                for (const ViewParams& view : blendViews(24, options.views)) {
                    const RenderSettings s = blendSettings(blend, Caster::Primitive, trilinear, v.isoValue);
                    const auto [p, b] =
                        expectBlocksEqualPrimitive(render, v.prepared, Camera::fit(v.prepared.grid(), view), s,
                                                   options.equal, where(v.name, blend, trilinear, viewText(view)), n);
                    primitive += p;
                    blocks += b;
                }
            std::printf("%s %s: iterations per ray blocks / primitive %.3f\n", v.name.c_str(), blendText(blend).c_str(),
                        blocks / primitive);
            // Air around the phantoms' structures: MIP leaps past air below its probes, the iso-surface past
            // everything on the ray's side (noise and the CT's central block have little to leap over).
            if ((v.name == "engine" || v.name == "shells") && (blend == Blend::MIP || blend == Blend::Iso)) {
                EXPECT_LT(blocks, 0.9 * primitive) << v.name << " " << blendText(blend);
            }
        }
    return n;
}

CaseCount blendsMatchBruteForce(const RenderFn& render, double allowedShare) {
    CaseCount n;
    for (const BlendVolume& v : blendVolumes())
        for (Blend blend : kScalarBlends)
            for (bool trilinear : {false, true})
                for (const ViewParams& view : {orbitView(30, 20, 20, 18), orbitView(-100, 60, 18, 20)}) {
                    const Camera camera = Camera::fit(v.prepared.grid(), view);
                    RenderSettings s = blendSettings(blend, Caster::Blocks, trilinear, v.isoValue);
                    s.shading = false;  // the brute force shows the iso-surface's colour as it is
                    const RenderResult r = render(v.prepared, camera, s);
                    ++n.renders;
                    std::size_t differ = 0;
                    for (int py = 0; py < camera.height; ++py)
                        for (int px = 0; px < camera.width; ++px) {
                            const BruteForce b = bruteForce(v.prepared, camera, px, py, s);
                            const std::size_t i = std::size_t(py) * camera.width + px;
                            const float* got = r.image.pixel(px, py);
                            double d = 0;
                            for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(got[c] - b.rgba[c]));
                            differ += d > 1e-4 || (blend == Blend::Iso && r.samples[i] != b.samples);
                            ++n.rays;
                            n.hits += b.samples > 0;
                        }
                    EXPECT_LE(double(differ), allowedShare * camera.width * camera.height)
                        << where(v.name, blend, trilinear, viewText(view));
                }
    return n;
}

CaseCount axisMipIsColumnMaximum(const RenderFn& render, const BlendCaseOptions& options) {
    CaseCount n;
    const Volume volume = enginePhantom({31, 27, 23});
    const PreparedVolume p = prepareVolume(volume, datasetTransferFunction("mri.tf.json"), {0, 0, false, false}, 0);
    const Vec3i dims = volume.grid.dims;
    for (int axis = 0; axis < 3; ++axis)
        for (bool trilinear : {false, true})
            for (Caster caster : {Caster::Primitive, Caster::Blocks}) {
                const Camera camera = columnCamera(dims, axis, false);
                const RenderResult r = render(p, camera, blendSettings(Blend::MIP, caster, trilinear, 0));
                ++n.renders;
                double worst = 0;
                for (int py = 0; py < camera.height; ++py)
                    for (int px = 0; px < camera.width; ++px) {
                        const Vec3d o = camera.ray(px + 0.5, py + 0.5).origin;
                        Vec3i column = floorVoxel(o);
                        double largest = -std::numeric_limits<double>::infinity();
                        for (int i = 0; i < dims[axis]; ++i) {
                            column[axis] = i;
                            largest = std::max(largest, double(volume.at(column.x, column.y, column.z)));
                        }
                        const std::array<double, 4> want = shown(p, largest);
                        for (int c = 0; c < 4; ++c)
                            worst = std::max(worst, std::abs(r.image.pixel(px, py)[c] - want[c]));
                        ++n.rays;
                        ++n.hits;
                    }
                EXPECT_LE(worst, options.equal) << "axis " << axis << (trilinear ? " trilinear " : " nearest ")
                                       << casterName(caster);
            }
    return n;
}

CaseCount oppositeViewsMirror(const RenderFn& render, const BlendCaseOptions& options) {
    CaseCount n;
    const Volume volume = enginePhantom({31, 27, 23});
    const PreparedVolume p = prepareVolume(volume, datasetTransferFunction("mri.tf.json"), {0, 0, false, false}, 0);
    for (Blend blend : {Blend::MIP, Blend::MinIP})
        for (int axis = 0; axis < 3; ++axis)
            for (bool trilinear : {false, true}) {
                const RenderSettings s = blendSettings(blend, Caster::Blocks, trilinear, 0);
                const Camera front = columnCamera(volume.grid.dims, axis, false);
                const Camera back = columnCamera(volume.grid.dims, axis, true);
                const RenderResult a = render(p, front, s), b = render(p, back, s);
                n.renders += 2;
                double worst = 0;
                for (int py = 0; py < front.height; ++py)
                    for (int px = 0; px < front.width; ++px) {
                        for (int c = 0; c < 4; ++c)
                            worst = std::max(worst, double(std::abs(a.image.pixel(px, py)[c] -
                                                                    b.image.pixel(front.width - 1 - px, py)[c])));
                        ++n.rays;
                        n.hits += a.samples[std::size_t(py) * front.width + px] > 0;
                    }
                EXPECT_LE(worst, options.equal)
                    << blendText(blend) << " axis " << axis << (trilinear ? " trilinear" : " nearest");
            }
    return n;
}

CaseCount greyWindowIsLinear(const RenderFn& render, const BlendCaseOptions& options) {
    CaseCount n;
    const Volume volume = enginePhantom({31, 27, 23});
    const double window = 400, level = 180, lo = level - window / 2;  // air 0, metal 200 and 255 inside it
    const PreparedVolume p =
        prepareVolume(volume, windowLevelTransferFunction(window, level, nullptr), {0, 0, false, false}, 0);
    const Vec3i dims = volume.grid.dims;
    for (Blend blend : {Blend::MIP, Blend::MinIP})
        for (bool opaque : {true, false}) {
            const Camera camera = columnCamera(dims, 2, false);
            RenderSettings s = blendSettings(blend, Caster::Blocks, false, 0);
            s.opaqueValues = opaque;
            const RenderResult r = render(p, camera, s);
            ++n.renders;
            double worst = 0;
            for (int py = 0; py < camera.height; ++py)
                for (int px = 0; px < camera.width; ++px) {
                    Vec3i column = floorVoxel(camera.ray(px + 0.5, py + 0.5).origin);
                    double value = blend == Blend::MIP ? -1e30 : 1e30;
                    for (int i = 0; i < dims.z; ++i) {
                        column.z = i;
                        const double v = volume.at(column.x, column.y, column.z);
                        value = blend == Blend::MIP ? std::max(value, v) : std::min(value, v);
                    }
                    // Opaque: the window's grey, linear in the value. Else the ramp's opacity weighs the same grey,
                    // over a black background: its square.
                    const double grey = std::clamp((value - lo) / window, 0.0, 1.0);
                    const double shown =
                        opaque ? grey
                               : grey * opacityFromExtinction(device::lookUpTable(p.classification.table, value).sigma,
                                                              p.classification.referenceStep);
                    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(r.image.pixel(px, py)[c] - shown));
                    if (opaque) worst = std::max(worst, std::abs(r.image.pixel(px, py)[3] - 1.0));
                    ++n.rays;
                    ++n.hits;
                }
            EXPECT_LE(worst, std::max(options.equal, 1e-6)) << blendName(blend) << (opaque ? " opaque" : " TF opacity");
        }
    return n;
}

}  // namespace vr::test

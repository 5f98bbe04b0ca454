// EACD (ALGORITHMS.md section 4): the ACD cube of edge k, extended greedily along the axis giving the largest box,
// then along the better of the two others. The extension along axis a is the minimum, over the box's near face
// (the voxels with e_a = 0), of the axial runs along s_a. Those face minima are O(1) queries of a 2D sparse table
// over each slice of the run field (instead of the thesis' quadratic face walk); one table serves every octant of
// the batch that shares the slice's run direction.
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "preprocess/fields/axial_runs.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/rect_min.h"
#include "preprocess/fields/scan_order.h"

namespace vr {

namespace {

// The six axial run fields, each computed when first needed and kept for every batch.
class RunFields {
public:
    explicit RunFields(const Regions& regions) : regions_(regions) {}
    const Regions& regions() const { return regions_; }
    const std::vector<uint8_t>& get(int axis, int sign) {
        std::vector<uint8_t>& run = runs_[2 * axis + (sign < 0)];
        if (run.empty()) run = axialRuns(regions_, axis, sign);
        return run;
    }

private:
    const Regions& regions_;
    std::array<std::vector<uint8_t>, 6> runs_;
};

// The octants built together. Their extents live in planar byte arrays while being built (ext[o][a][v]: each
// step reads and writes whole slots, so one byte per voxel moves instead of three) and are interleaved at the end.
// widest[o][v] is the axis step 1 extends (see widestAxis).
struct OctantBatch {
    std::vector<int> octants;
    std::array<const std::vector<uint8_t>*, kOctants> acd{};
    std::array<std::array<std::vector<uint8_t>, 3>, kOctants> ext;
    std::array<std::vector<uint8_t>, kOctants> widest;

    std::vector<int> withSign(int axis, int sign) const {
        std::vector<int> out;
        for (int o : octants)
            if (octantSign(o, axis) == sign) out.push_back(o);
        return out;
    }
};

// The first axis with the largest extent (ties go to x, then y, then z).
inline int widestAxis(uint8_t ex, uint8_t ey, uint8_t ez) {
    int a = 0;
    uint8_t best = ex;
    if (ey > best) a = 1, best = ey;
    if (ez > best) a = 2;
    return a;
}

// Slices [t0, t1) across axis a, gathered into local planes: u fastest, then w (the two other axes, u < w), then t.
struct Slab {
    int a, u, w, nu, nw, t0, t1;
    std::size_t plane;
    std::array<std::size_t, 3> stride;

    Slab(const Vec3i& n, int axis, int first, int last)
        : a(axis), u(axis == 0 ? 1 : 0), w(axis == 2 ? 1 : 2), nu(n[u]), nw(n[w]), t0(first), t1(last),
          plane(std::size_t(nu) * nw), stride{1, std::size_t(n.x), std::size_t(n.x) * n.y} {}

    std::size_t size() const { return plane * std::size_t(t1 - t0); }

    // f(local, voxel) for every voxel, in an order that reads the volume by whole cache lines: across x,
    // consecutive slices are neighbours in memory (hence slabs of many slices); across y or z, u is x.
    template <typename F>
    void forEachVoxel(F f) const {
        if (a == 0) {
            for (int pw = 0; pw < nw; ++pw)
                for (int pu = 0; pu < nu; ++pu) {
                    const std::size_t local = std::size_t(pw) * nu + pu, voxel = pu * stride[u] + pw * stride[w];
                    for (int t = t0; t < t1; ++t) f(local + (t - t0) * plane, voxel + t);
                }
            return;
        }
        for (int t = t0; t < t1; ++t)
            for (int pw = 0; pw < nw; ++pw) {
                const std::size_t local = ((t - t0) * std::size_t(nw) + pw) * nu;
                const std::size_t voxel = t * stride[a] + pw * stride[w];
                for (int pu = 0; pu < nu; ++pu) f(local + pu, voxel + pu);
            }
    }
};

// Per-thread working memory of one slab: its run planes and, per octant of the slab's run direction, each
// voxel's face (lenU x lenW; lenU = 0 for none), lenU being overwritten by the minimum over the face.
struct SlabScratch {
    RectMin table;
    std::vector<uint8_t> runs;
    std::array<std::vector<uint8_t>, 4> lenU, lenW;
};

// Corner of a box's face along one in-plane axis: the face starts at p and goes toward `sign` for `len` voxels.
inline int faceStart(int p, int sign, int len) { return sign > 0 ? p : p - len + 1; }

// For every slice of the slab: lenU = minimum of the runs over each voxel's face (skipped where lenU is 0), for
// the octants `octs`. Square faces (kSquares: lenU == lenW, lenW unused) need only the square tables.
template <bool kSquares>
void faceMinima(const Slab& slab, const std::vector<int>& octs, SlabScratch& sc) {
    const int nu = slab.nu, nw = slab.nw;
    for (int t = 0; t < slab.t1 - slab.t0; ++t) {
        const std::size_t off = t * slab.plane;
        uint8_t maxU = 0, maxW = 0;
        for (std::size_t j = 0; j < octs.size(); ++j) {
            maxU = std::max(maxU, maxOfRow(sc.lenU[j].data() + off, slab.plane));
            if (!kSquares) maxW = std::max(maxW, maxOfRow(sc.lenW[j].data() + off, slab.plane));
        }
        if (maxU == 0) continue;  // no face in this slice
        std::copy_n(sc.runs.data() + off, slab.plane, sc.table.resize(nu, nw));
        if (kSquares)
            sc.table.buildSquares(maxU);
        else
            sc.table.build(maxU, maxW);
        const RectMin::Query faceMin = sc.table.query();
        for (std::size_t j = 0; j < octs.size(); ++j) {
            const int su = octantSign(octs[j], slab.u), sw = octantSign(octs[j], slab.w);
            uint8_t* lenU = sc.lenU[j].data() + off;
            const uint8_t* lenW = (kSquares ? sc.lenU[j] : sc.lenW[j]).data() + off;
            const uint8_t* run = sc.runs.data() + off;
            for (int pw = 0; pw < nw; ++pw, lenU += nu, lenW += nu, run += nu)
                for (int pu = 0; pu < nu; ++pu) {
                    const int lu = lenU[pu], lw = kSquares ? lu : lenW[pu], k = std::min(lu, lw);
                    if (lu == 0) continue;
                    // The minimum lies between the box's edge along the axis (k: the box is homogeneous) and the
                    // run of v itself (v is on the face): no query when those meet.
                    lenU[pu] = run[pu] == k ? k : faceMin(faceStart(pu, su, lu), faceStart(pw, sw, lw), lu, lw);
                }
        }
    }
}

// Runs body(slab, octs, scratch) on every slab across `axis`, for both run directions, with the slab's runs
// loaded; octs are the batch's octants whose sign along the axis is the direction.
template <typename Body>
void forEachSlab(RunFields& runFields, const OctantBatch& batch, int axis, Body body) {
    const Vec3i& n = runFields.regions().dims;
    std::array<const uint8_t*, 2> runs{};  // index 0: sign +1, 1: sign -1
    std::array<std::vector<int>, 2> octs;
    for (int d = 0; d < 2; ++d) {
        octs[d] = batch.withSign(axis, d ? -1 : 1);
        if (!octs[d].empty()) runs[d] = runFields.get(axis, d ? -1 : 1).data();
    }
    // Slices per slab. Across x: at least 4 (whole cache-line chunks of the volume) and up to what keeps the
    // slab's scratch (9 bytes per voxel) within about 2 MB of cache (measured: 4-8 on 256^3, 2-3x faster than 1
    // or 64). Across y or z, rows of x are already contiguous.
    const std::size_t plane = std::size_t(n[axis == 0 ? 1 : 0]) * n[axis == 2 ? 1 : 2];
    const int width = axis == 0 ? int(std::clamp<std::size_t>((std::size_t(2) << 20) / (9 * plane + 1), 4, 32)) : 1;
    const int slabs = (n[axis] + width - 1) / width;
    tbb::enumerable_thread_specific<SlabScratch> scratch;
    tbb::parallel_for(0, 2 * slabs, [&](int job) {
        const int d = job / slabs, first = job % slabs * width;
        if (octs[d].empty()) return;
        const Slab slab(n, axis, first, std::min(n[axis], first + width));
        SlabScratch& sc = scratch.local();
        sc.runs.resize(slab.size());
        for (std::size_t j = 0; j < octs[d].size(); ++j) {
            sc.lenU[j].resize(slab.size());
            sc.lenW[j].resize(slab.size());
        }
        const uint8_t* r = runs[d];
        slab.forEachVoxel([&](std::size_t l, std::size_t v) { sc.runs[l] = r[v]; });
        body(slab, octs[d], sc);
    });
}

// Step 1: ext[o][a] = extension along a of the ACD cube (minimum of runs over its k x k near face).
void cubeExtensions(RunFields& runs, OctantBatch& batch, int a) {
    forEachSlab(runs, batch, a, [&](const Slab& slab, const std::vector<int>& octs, SlabScratch& sc) {
        for (std::size_t j = 0; j < octs.size(); ++j) {
            const uint8_t* acd = batch.acd[octs[j]]->data();
            uint8_t* k = sc.lenU[j].data();
            slab.forEachVoxel([&](std::size_t l, std::size_t v) { k[l] = acd[v]; });
        }
        faceMinima<true>(slab, octs, sc);
        for (std::size_t j = 0; j < octs.size(); ++j) {
            uint8_t* ext = batch.ext[octs[j]][a].data();
            const uint8_t* minimum = sc.lenU[j].data();
            slab.forEachVoxel([&](std::size_t l, std::size_t v) { ext[v] = minimum[l]; });
        }
    });
}

// Between steps 1 and 2: the axis that step 1 extends, per voxel.
void findWidestAxes(OctantBatch& batch) {
    for (int o : batch.octants) {
        const uint8_t *ex = batch.ext[o][0].data(), *ey = batch.ext[o][1].data(), *ez = batch.ext[o][2].data();
        std::vector<uint8_t>& widest = batch.widest[o];
        widest.resize(batch.acd[o]->size());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, widest.size(), 1 << 16), [&](const auto& range) {
            for (std::size_t v = range.begin(); v != range.end(); ++v)
                widest[v] = uint8_t(widestAxis(ex[v], ey[v], ez[v]));
        });
    }
}

// Step 2, for axis b: ext[o][b] = extension along b of the box extended along its widest axis a (a != b), whose
// near face is ext[a] along a by k along the third axis. Step 2 never writes slot a of a voxel (b == a is skipped),
// so the three axes could even run at once.
void boxExtensions(RunFields& runs, OctantBatch& batch, int b) {
    forEachSlab(runs, batch, b, [&](const Slab& slab, const std::vector<int>& octs, SlabScratch& sc) {
        for (std::size_t j = 0; j < octs.size(); ++j) {
            const uint8_t* acd = batch.acd[octs[j]]->data();
            const auto& ext = batch.ext[octs[j]];
            const uint8_t *ex = ext[0].data(), *ey = ext[1].data(), *ez = ext[2].data();
            const uint8_t* widestAxes = batch.widest[octs[j]].data();
            uint8_t *lenU = sc.lenU[j].data(), *lenW = sc.lenW[j].data();
            slab.forEachVoxel([&](std::size_t l, std::size_t v) {
                // All three slots are read, so that every array is read in order (the prefetcher follows).
                const int a = widestAxes[v];
                const uint8_t e0 = ex[v], e1 = ey[v], e2 = ez[v];
                const uint8_t widest = a == 0 ? e0 : a == 1 ? e1 : e2, k = acd[v];
                // Nothing to do when b is the widest axis, or when nothing extended (then every slot is k).
                lenU[l] = a == b || widest == k ? 0 : slab.u == a ? widest : k;
                lenW[l] = slab.w == a ? widest : k;
            });
        }
        faceMinima<false>(slab, octs, sc);
        for (std::size_t j = 0; j < octs.size(); ++j) {
            uint8_t* ext = batch.ext[octs[j]][b].data();
            const uint8_t* minimum = sc.lenU[j].data();
            slab.forEachVoxel([&](std::size_t l, std::size_t v) {
                if (minimum[l]) ext[v] = minimum[l];
            });
        }
    });
}

// Step 3: the box is k on every axis but the widest a (step 1's extension) and the better of the two others.
void chooseBoxes(const OctantBatch& batch, int o, EACDField& out) {
    const uint8_t* acd = batch.acd[o]->data();
    const uint8_t *ex = batch.ext[o][0].data(), *ey = batch.ext[o][1].data(), *ez = batch.ext[o][2].data();
    const uint8_t* widest = batch.widest[o].data();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 1 << 16), [&](const auto& range) {
        for (std::size_t v = range.begin(); v != range.end(); ++v) {
            const std::array<uint8_t, 3> e{ex[v], ey[v], ez[v]};
            const int a = widest[v], b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
            const int second = e[b] >= e[c] ? b : c;
            std::array<uint8_t, 3> box{acd[v], acd[v], acd[v]};
            box[a] = e[a];
            box[second] = e[second];
            out[v] = box;
        }
    });
}

// EACD of `octants`. The planar extents take 4 bytes per voxel and octant while the batch is built.
void buildBatch(RunFields& runs, const std::vector<int>& octants,
                const std::array<const std::vector<uint8_t>*, kOctants>& acd,
                const std::array<EACDField*, kOctants>& out) {
    const std::size_t voxels = runs.regions().label.size();
    OctantBatch batch;
    batch.octants = octants;
    for (int o : octants) {
        if (acd[o]->size() != voxels)
            throw std::invalid_argument("buildEACD: the ACD of octant " + std::to_string(o) +
                                        " does not match the regions");
        batch.acd[o] = acd[o];
        for (auto& slot : batch.ext[o]) slot.resize(voxels);
    }
    for (int a = 0; a < 3; ++a) cubeExtensions(runs, batch, a);
    findWidestAxes(batch);
    for (int b = 0; b < 3; ++b) boxExtensions(runs, batch, b);
    for (int o : octants) {
        out[o]->resize(voxels);
        chooseBoxes(batch, o, *out[o]);
        batch.ext[o] = {};
        batch.widest[o] = {};
    }
}

}  // namespace

EACDField buildEACD(const Regions& regions, const std::vector<uint8_t>& acd, int octant) {
    if (octant < 0 || octant >= kOctants) throw std::invalid_argument("buildEACD: no octant " + std::to_string(octant));
    EACDField out;
    std::array<const std::vector<uint8_t>*, kOctants> acds{};
    std::array<EACDField*, kOctants> outs{};
    acds[octant] = &acd;
    outs[octant] = &out;
    requireLabelPerVoxel(regions, "buildEACD");
    RunFields runs(regions);
    buildBatch(runs, {octant}, acds, outs);
    return out;
}

std::array<EACDField, kOctants> buildEACD(const Regions& regions,
                                          const std::array<std::vector<uint8_t>, kOctants>& acd) {
    std::array<EACDField, kOctants> out;
    std::array<const std::vector<uint8_t>*, kOctants> acds{};
    std::array<EACDField*, kOctants> outs{};
    for (int o = 0; o < kOctants; ++o) {
        acds[o] = &acd[o];
        outs[o] = &out[o];
    }
    // Two batches, +z and -z, to bound the working memory; each still shares every table between two (across x
    // or y) or four (across z) octants.
    requireLabelPerVoxel(regions, "buildEACD");
    RunFields runs(regions);
    buildBatch(runs, {0, 1, 2, 3}, acds, outs);
    buildBatch(runs, {4, 5, 6, 7}, acds, outs);
    return out;
}

}  // namespace vr

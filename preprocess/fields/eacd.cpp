#include <ctime>
#include <cstdio>
// EACD (ALGORITHMS.md section 4): the ACD cube of edge k, extended greedily along the axis giving the largest box,
// then along the better of the two others. The extension along axis a is the minimum, over the box's near face
// (the voxels with e_a = 0), of the axial runs along s_a. Those face minima are O(1) queries of a 2D sparse table
// over each slice of the run field (instead of the thesis' quadratic face walk); one table serves the four
// octants that share the slice's run direction.
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "preprocess/fields/axial_runs.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/rect_min.h"
#include "preprocess/fields/scan_order.h"

namespace vr {

namespace {

// The octants being built: acd[o] and out[o] are null for the octants left out.
struct OctantSet {
    std::array<const std::vector<uint8_t>*, kOctants> acd{};
    std::array<EACDField*, kOctants> out{};
    bool uses(int axis, int sign) const {
        for (int o = 0; o < kOctants; ++o)
            if (out[o] && octantSign(o, axis) == sign) return true;
        return false;
    }
};

// The first axis with the largest value (ties go to x, then y, then z).
inline int widestAxis(const std::array<uint8_t, 3>& e) {
    int a = 0;
    if (e[1] > e[a]) a = 1;
    if (e[2] > e[a]) a = 2;
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

    // f(local, voxel) for every voxel, in an order that reads the volume by whole cache lines: across x,
    // consecutive slices are neighbours in memory (hence slabs of several slices); across y or z, u is x.
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
                const std::size_t local = ((t - t0) * std::size_t(nw) + pw) * nu, voxel = t * stride[a] + pw * stride[w];
                for (int pu = 0; pu < nu; ++pu) f(local + pu, voxel + pu);
            }
    }
};

// Per-thread working memory of one slab: its run planes and, per octant of the slab's run direction,
// the face of each voxel (lenU x lenW, 0 for none) and the minimum over it.
struct SlabScratch {
    RectMin table;
    std::vector<uint8_t> runs;
    std::array<std::vector<uint8_t>, 4> lenU, lenW, result;
};

// Corner of a box's face along one in-plane axis: the face starts at p and goes toward `sign` for `len` voxels.
inline int faceStart(int p, int sign, int len) { return sign > 0 ? p : p - len + 1; }

// For every slice of the slab: result = minimum of the runs over each voxel's face (lenU x lenW, skipped where 0),
// for the octants `octs` (those whose sign along the slab's axis is the runs' direction). Square faces need only
// the square tables.
void faceMinima(const Slab& slab, const std::vector<int>& octs, SlabScratch& sc, bool squares) {
    for (int t = 0; t < slab.t1 - slab.t0; ++t) {
        const std::size_t off = t * slab.plane;
        uint8_t maxU = 0, maxW = 0;
        for (std::size_t j = 0; j < octs.size(); ++j) {
            maxU = std::max(maxU, maxOfRow(sc.lenU[j].data() + off, slab.plane));
            maxW = std::max(maxW, maxOfRow(sc.lenW[j].data() + off, slab.plane));
        }
        if (maxU == 0) continue;  // no face in this slice
        std::copy_n(sc.runs.data() + off, slab.plane, sc.table.resize(slab.nu, slab.nw));
        if (squares)
            sc.table.buildSquares(maxU);
        else
            sc.table.build(maxU, maxW);
        const RectMin::Query faceMin = sc.table.query();
        for (std::size_t j = 0; j < octs.size(); ++j) {
            const int su = octantSign(octs[j], slab.u), sw = octantSign(octs[j], slab.w);
            const uint8_t *lenU = sc.lenU[j].data() + off, *lenW = sc.lenW[j].data() + off;
            uint8_t* result = sc.result[j].data() + off;
            for (int pw = 0; pw < slab.nw; ++pw)
                for (int pu = 0; pu < slab.nu; ++pu) {
                    const std::size_t l = std::size_t(pw) * slab.nu + pu;
                    if (lenU[l] == 0) continue;
                    result[l] = faceMin(faceStart(pu, su, lenU[l]), faceStart(pw, sw, lenW[l]), lenU[l], lenW[l]);
                }
        }
    }
}

// Runs body(slab, octs, scratch) on every slab across `axis`, for both run directions, with the slab's runs
// loaded; octs are the octants of the set whose sign along the axis is the direction.
template <typename Body>
void forEachSlab(const Regions& regions, const OctantSet& set, int axis, Body body) {
    const Vec3i& n = regions.dims;
    std::array<std::vector<uint8_t>, 2> runs;  // index 0: sign +1, 1: sign -1
    std::array<std::vector<int>, 2> octs;
    for (int d = 0; d < 2; ++d) {
        for (int o = 0; o < kOctants; ++o)
            if (set.out[o] && octantSign(o, axis) == (d ? -1 : 1)) octs[d].push_back(o);
        if (!octs[d].empty()) runs[d] = axialRuns(regions, axis, d ? -1 : 1);
    }
    const int width = axis == 0 ? 8 : 1;  // slices per slab
    const int slabs = (n[axis] + width - 1) / width;
    tbb::enumerable_thread_specific<SlabScratch> scratch;
    tbb::parallel_for(0, 2 * slabs, [&](int job) {
        const int d = job / slabs, first = job % slabs * width;
        if (octs[d].empty()) return;
        const Slab slab(n, axis, first, std::min(n[axis], first + width));
        SlabScratch& sc = scratch.local();
        const std::size_t size = slab.plane * (slab.t1 - slab.t0);
        sc.runs.resize(size);
        for (std::size_t j = 0; j < octs[d].size(); ++j) {
            sc.lenU[j].resize(size);
            sc.lenW[j].resize(size);
            sc.result[j].resize(size);
        }
        const uint8_t* r = runs[d].data();
        slab.forEachVoxel([&](std::size_t l, std::size_t v) { sc.runs[l] = r[v]; });
        body(slab, octs[d], sc);
    });
}

// Step 1: out[o][v][a] = extension along a of the ACD cube (minimum of runs over its k x k near face).
void cubeExtensions(const Regions& regions, const OctantSet& set, int a) {
    forEachSlab(regions, set, a, [&](const Slab& slab, const std::vector<int>& octs, SlabScratch& sc) {
        for (std::size_t j = 0; j < octs.size(); ++j) {
            const uint8_t* acd = set.acd[octs[j]]->data();
            slab.forEachVoxel([&](std::size_t l, std::size_t v) { sc.lenU[j][l] = sc.lenW[j][l] = acd[v]; });
        }
        faceMinima(slab, octs, sc, true);
        for (std::size_t j = 0; j < octs.size(); ++j) {
            EACDField& out = *set.out[octs[j]];
            slab.forEachVoxel([&](std::size_t l, std::size_t v) { out[v][a] = sc.result[j][l]; });
        }
    });
}

// Step 2, for axis b: out[o][v][b] = extension along b of the box extended along its widest axis a (a != b),
// whose near face is e[a] along a by k along the third axis. Slot a keeps the largest value (the new value is a
// minimum over a larger face, so never above the old one), so widestAxis still finds a afterwards.
void boxExtensions(const Regions& regions, const OctantSet& set, int b) {
    forEachSlab(regions, set, b, [&](const Slab& slab, const std::vector<int>& octs, SlabScratch& sc) {
        for (std::size_t j = 0; j < octs.size(); ++j) {
            const uint8_t* acd = set.acd[octs[j]]->data();
            const EACDField& out = *set.out[octs[j]];
            slab.forEachVoxel([&](std::size_t l, std::size_t v) {
                const std::array<uint8_t, 3> e = out[v];
                const int a = widestAxis(e);
                sc.lenU[j][l] = a == b ? 0 : slab.u == a ? e[a] : acd[v];
                sc.lenW[j][l] = a == b ? 0 : slab.w == a ? e[a] : acd[v];
            });
        }
        faceMinima(slab, octs, sc, false);
        for (std::size_t j = 0; j < octs.size(); ++j) {
            EACDField& out = *set.out[octs[j]];
            slab.forEachVoxel([&](std::size_t l, std::size_t v) {
                if (sc.lenU[j][l]) out[v][b] = sc.result[j][l];
            });
        }
    });
}

// Step 3: the box is k on every axis but the widest a (step 1's extension) and the better of the two others.
void chooseBoxes(const OctantSet& set) {
    for (int o = 0; o < kOctants; ++o) {
        if (!set.out[o]) continue;
        EACDField& out = *set.out[o];
        const std::vector<uint8_t>& acd = *set.acd[o];
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 1 << 16), [&](const auto& range) {
            for (std::size_t v = range.begin(); v != range.end(); ++v) {
                const std::array<uint8_t, 3> e = out[v];
                const int a = widestAxis(e), b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
                const int second = e[b] >= e[c] ? b : c;
                std::array<uint8_t, 3> box{acd[v], acd[v], acd[v]};
                box[a] = e[a];
                box[second] = e[second];
                out[v] = box;
            }
        });
    }
}

void buildEACDOctants(const Regions& regions, const OctantSet& set) {
    requireLabelPerVoxel(regions, "buildEACD");
    const std::size_t voxels = voxelCount(regions.dims);
    for (int o = 0; o < kOctants; ++o) {
        if (!set.out[o]) continue;
        if (set.acd[o]->size() != voxels)
            throw std::invalid_argument("buildEACD: ACD of octant " + std::to_string(o) + " does not match the regions");
        set.out[o]->assign(voxels, {0, 0, 0});
    }
    if (voxels == 0) return;
    for (int a = 0; a < 3; ++a) { auto t=std::clock(); cubeExtensions(regions, set, a); fprintf(stderr,"cube %d %.3f\n",a,double(std::clock()-t)/CLOCKS_PER_SEC);}
    for (int b = 0; b < 3; ++b) { auto t=std::clock(); boxExtensions(regions, set, b); fprintf(stderr,"box %d %.3f\n",b,double(std::clock()-t)/CLOCKS_PER_SEC);}
    auto t=std::clock();chooseBoxes(set);fprintf(stderr,"choose %.3f\n",double(std::clock()-t)/CLOCKS_PER_SEC);
}

}  // namespace

EACDField buildEACD(const Regions& regions, const std::vector<uint8_t>& acd, int octant) {
    EACDField out;
    OctantSet set;
    set.acd[octant] = &acd;
    set.out[octant] = &out;
    buildEACDOctants(regions, set);
    return out;
}

std::array<EACDField, kOctants> buildEACD(const Regions& regions,
                                          const std::array<std::vector<uint8_t>, kOctants>& acd) {
    std::array<EACDField, kOctants> out;
    OctantSet set;
    for (int o = 0; o < kOctants; ++o) {
        set.acd[o] = &acd[o];
        set.out[o] = &out[o];
    }
    buildEACDOctants(regions, set);
    return out;
}

}  // namespace vr

// EACD steps 1 and 2 (docs/ALGORITHMS.md section 4): the extension of a box along an axis is the minimum, over its
// near face, of the axial runs along the octant's direction. Slices across the axis are walked toward -s (s the
// octant's sign there), so that the neighbour w = v + s e_a is done first: where w's face is v's, one step on,
// v's extension follows from w's in O(1) (16 voxels at a time), and the few others are queries of sparse tables
// over the slice's runs (instead of the thesis' quadratic face walk): O(1) for step 1's square faces, O(shorter
// side) for step 2's rectangles (1D tables: a few levels a slice, where 2D ones took dozens for a few queries).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <initializer_list>
#include <utility>

#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/eacd_state.h"
#include "preprocess/fields/rect_min.h"
#include "preprocess/fields/slab.h"

namespace vr {

namespace {

// Slice t of an array the walk reads or writes (`volume`): the volume itself when the slab is in place, else the
// slab's copy, or for t outside the slab the plane kept from the slab before.
template <typename Byte>
RowsOf<Byte> sliceRows(const Slab& slab, int t, Byte* volume, std::vector<uint8_t>& copy,
                       std::vector<uint8_t>& before) {
    if (slab.inPlace()) return slab.inVolume(volume, t);
    const bool inSlab = t >= 0 && t < slab.t1 - slab.t0;
    return {inSlab ? copy.data() + std::size_t(t) * slab.pitch : before.data(), std::size_t(slab.nu)};
}

// Slice t of the runs toward `sign` along the walked axis: in place, or across x the copy made once.
Rows runRows(const OctantState& state, const Slab& slab, int t, int sign) {
    if (slab.inPlace()) return slab.inVolume(state.runs.get(slab.a, sign).data(), t);
    return {state.runsAcrossX[sign < 0].data() + std::size_t(slab.t0 + t) * slab.pitch, std::size_t(slab.nu)};
}

// Copies `volumes` (a copy each, same order) for a slab across x; nothing in place.
void gatherSlab(const Slab& slab, std::initializer_list<std::pair<const uint8_t*, std::vector<uint8_t>*>> volumes) {
    if (slab.inPlace()) return;
    for (const auto& [volume, copy] : volumes) {
        copy->resize(slab.size());
        slab.gather(volume, copy->data());
    }
}

// After a slab across x: keeps its last slice t of each copy in its plane, and writes ext back.
using KeptSlice = std::pair<std::vector<uint8_t>*, std::vector<uint8_t>*>;  // a copy and its kept plane
void finishSlab(const Slab& slab, int t, std::initializer_list<KeptSlice> kept, const std::vector<uint8_t>& ext,
                uint8_t* extVolume) {
    if (slab.inPlace()) return;
    for (const auto& [copy, before] : kept) {
        before->resize(slab.plane);
        std::copy_n(copy->data() + t * slab.pitch, slab.plane, before->data());
    }
    slab.scatter(ext.data(), extVolume);
}

// Corner of a box's face along one in-plane axis: the face starts at p and goes toward `sign` for `len` voxels.
inline int faceStart(int p, int sign, int len) { return sign > 0 ? p : p - len + 1; }

// ext = minimum of the runs over each voxel's face where lenU is not 0, in the current slice. Square faces
// (kSquares: lenU == lenW, lenW unused) need only the square tables; rectangles the strips along their longer side.
template <bool kSquares>
void faceMinima(const Slab& slab, Rows runs, MutableRows ext, int octant, WalkScratch& sc) {
    const int nu = slab.nu, nw = slab.nw;
    const uint8_t* lenU = sc.lenU.data();
    const uint8_t* lenW = (kSquares ? sc.lenU : sc.lenW).data();
    // The tables worth building for those faces: squares, or strips along u for the faces not taller than wide and
    // along w for the taller ones.
    LevelPlan alongU(kSquares), alongW(false);
    forEachNonzero(lenU, int(slab.plane), [&](int l) {
        if (lenW[l] <= lenU[l])
            alongU.add(lenU[l], lenW[l]);
        else
            alongW.add(lenW[l], lenU[l]);
    });
    const int maxU = alongU.longest(slab.plane), maxW = alongW.longest(slab.plane);
    if (maxU == 0 && maxW == 0) return;  // no face in this slice
    uint8_t* image = sc.table.resize(nu, nw);
    for (int pw = 0; pw < nw; ++pw) std::copy_n(runs.row(pw), nu, image + std::size_t(pw) * nu);
    if (kSquares)
        sc.table.buildSquares(maxU);
    else
        sc.table.buildStrips(maxU, maxW);
    const RectMin::Query faceMin = sc.table.query();
    const int su = octantSign(octant, slab.u), sw = octantSign(octant, slab.w);
    for (int pw = 0; pw < nw; ++pw, lenU += nu, lenW += nu) {
        uint8_t* e = ext.row(pw);
        forEachNonzero(lenU, nu, [&](int pu) {
            const int lu = lenU[pu], lw = lenW[pu];
            e[pu] = faceMin(faceStart(pu, su, lu), faceStart(pw, sw, lw), lu, lw);
        });
    }
}

// Runs step(axis, sign, scratch) for the three walks of a step (one per axis, toward the octant; each a serial
// walk of slices). The walks read the same inputs and write different extents, so they run at once; x first: its
// walk is the longest (it copies its slabs).
template <typename Step>
void everyWalk(OctantState& state, Step step) {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, 3, 1),
        [&](const tbb::blocked_range<int>& axes) {
            for (int a = axes.begin(); a != axes.end(); ++a) step(a, octantSign(state.octant, a), state.scratch[a]);
        },
        tbb::simple_partitioner());
}

}  // namespace

OctantState::OctantState(AxialRuns& allRuns, unsigned octants) : runs(allRuns) {
    runs.computeAll(octants);  // before the walks share them
    const Vec3i& n = runs.dims();
    const std::size_t voxels = voxelCount(n);
    for (ByteVolume* v : {&ext[0], &ext[1], &ext[2], &widest, &longest}) v->allocate(voxels);
    const int width = slabWidth(0), slabs = (n.x + width - 1) / width;
    for (int sign : {1, -1})
        if (AxialRuns::read(octants, 0, sign)) runsAcrossX[sign < 0].resize(Slab(n, 0, 0, n.x).size());
    tbb::parallel_for(0, 2 * slabs, [&](int i) {
        const int sign = i < slabs ? 1 : -1, s = i % slabs;
        if (!AxialRuns::read(octants, 0, sign)) return;
        const Slab slab(n, 0, s * width, std::min(n.x, (s + 1) * width));
        slab.gather(runs.get(0, sign).data(), runsAcrossX[sign < 0].data() + std::size_t(slab.t0) * slab.pitch);
    });
}

// Step 1: ext[a] = extension along a of the ACD cube (minimum of the runs over its k x k near face). With k, kw
// the ACD edges of v and w, r the run of v and ew the extension of w:
//   kw < k:        ext = k (the cube of edge k at w is not homogeneous, so no box at v longer than k is);
//   kw == k:       ext = min(r, 1 + ew) (w's face is v's, one step on);
//   r == k:        ext = k (v is on its face);
//   r <= 1 + ew:   ext = r (kw > k: w's face holds v's, one step on, so that reaches at least ew);
//   otherwise a query. Capped values keep every case exact: a capped k is the face's edge, 1 + ew saturates.
void cubeExtensions(OctantState& st) {
    everyWalk(st, [&](int a, int sign, WalkScratch& sc) {
        const uint8_t* acd = st.acd->data();
        uint8_t* extVolume = st.ext[a].data();
        auto gather = [&](const Slab& slab) {
            sc.lenU.resize(slab.plane);
            gatherSlab(slab, {{acd, &sc.edge}});
            if (!slab.inPlace()) sc.ext.resize(slab.size());
        };
        auto slice = [&](const Slab& slab, int t, int tw) {
            const Rows r = runRows(st, slab, t, sign);
            const Rows k = sliceRows(slab, t, acd, sc.edge, sc.edgeBefore);
            const MutableRows ext = sliceRows(slab, t, extVolume, sc.ext, sc.extBefore);
            if (tw == kBorder) {  // the border slice: every run and edge is 1
                for (int pw = 0; pw < slab.nw; ++pw) std::copy_n(r.row(pw), slab.nu, ext.row(pw));
                return;
            }
            const Rows kw = sliceRows(slab, tw, acd, sc.edge, sc.edgeBefore);
            const MutableRows ew = sliceRows(slab, tw, extVolume, sc.ext, sc.extBefore);
            uint8_t* query = sc.lenU.data();
            for (int pw = 0; pw < slab.nw; ++pw, query += slab.nu) {
                const uint8_t *rRow = r.row(pw), *kRow = k.row(pw), *kwRow = kw.row(pw), *ewRow = ew.row(pw);
                uint8_t* eRow = ext.row(pw);
                forEachLane(slab.nu, [&](std::size_t i, auto lanes) {
                    const auto rv = load(rRow + i, lanes), kv = load(kRow + i, lanes), kwv = load(kwRow + i, lanes);
                    const auto next = plusOne(load(ewRow + i, lanes)), none = splat(0, lanes);
                    const auto e = select(kwv < kv, kv,
                                          select(kwv == kv, minOf(rv, next),
                                                 select((rv == kv) | (rv <= next), rv, none)));
                    store(eRow + i, e);
                    store(query + i, select(e == none, kv, none));
                });
            }
            faceMinima<true>(slab, r, ext, st.octant, sc);
        };
        auto finish = [&](const Slab& slab, int last) {
            finishSlab(slab, last, {{&sc.edge, &sc.edgeBefore}, {&sc.ext, &sc.extBefore}}, sc.ext, extVolume);
        };
        walkSlices(st.runs.dims(), a, sign, gather, slice, finish);
    });
}

// Step 2, for axis b: ext[b] = extension along b of the box extended along its widest axis a (a != b), whose
// near face is L = ext[a] along a by k along the third axis. No face where b is the widest axis (ext stays L) or
// where nothing extended (L == k: every extent is k). Otherwise, with r the run of v, kw and Lw the ACD edge and
// longest step-1 extension of w, w's face if it has one (as rectangles in the slice, whichever axis each
// extended) and its extension ew:
//   w's face is v's:                      ext = min(r, 1 + ew) (one step on);
//   r == k:                               ext = k (v is on its face);
//   w's face holds v's, r <= 1 + ew:      ext = r;
//   kw < k, or kw == k and Lw < L:        ext = k (the box of depth k + 1 along b holds w's cube of edge k, or
//                                         that cube extended along a by L, more than its extension there, which
//                                         is at most Lw: in both cases not homogeneous);
//   otherwise a query. Step 2 never writes slot a of a voxel, so `longest` stays step 1's.
void boxExtensions(OctantState& st) {
    everyWalk(st, [&](int b, int sign, WalkScratch& sc) {
        const uint8_t *acd = st.acd->data(), *widest = st.widest.data(), *longest = st.longest.data();
        uint8_t* extVolume = st.ext[b].data();
        auto gather = [&](const Slab& slab) {
            sc.lenU.resize(slab.plane);
            sc.lenW.resize(slab.plane);
            gatherSlab(slab, {{acd, &sc.edge}, {widest, &sc.widest}, {longest, &sc.longest}});
            if (!slab.inPlace()) sc.ext.resize(slab.size());
        };
        auto slice = [&](const Slab& slab, int t, int tw) {
            const Rows r = runRows(st, slab, t, sign);
            const bool border = tw == kBorder;
            const Rows k = sliceRows(slab, t, acd, sc.edge, sc.edgeBefore),
                       axis = sliceRows(slab, t, widest, sc.widest, sc.widestBefore),
                       len = sliceRows(slab, t, longest, sc.longest, sc.longestBefore);
            const MutableRows ext = sliceRows(slab, t, extVolume, sc.ext, sc.extBefore);
            // The neighbour's (unread at the border: any slice will do).
            const int n = border ? t : tw;
            const Rows kw = sliceRows(slab, n, acd, sc.edge, sc.edgeBefore),
                       axisW = sliceRows(slab, n, widest, sc.widest, sc.widestBefore),
                       lenW = sliceRows(slab, n, longest, sc.longest, sc.longestBefore);
            const MutableRows ew = sliceRows(slab, n, extVolume, sc.ext, sc.extBefore);
            uint8_t *queryU = sc.lenU.data(), *queryW = sc.lenW.data();
            for (int pw = 0; pw < slab.nw; ++pw, queryU += slab.nu, queryW += slab.nu) {
                const uint8_t *rRow = r.row(pw), *kRow = k.row(pw), *aRow = axis.row(pw), *lRow = len.row(pw);
                const uint8_t *kwRow = kw.row(pw), *awRow = axisW.row(pw), *lwRow = lenW.row(pw), *ewRow = ew.row(pw);
                uint8_t* eRow = ext.row(pw);
                forEachLane(slab.nu, [&](std::size_t i, auto lanes) {
                    const auto none = splat(0, lanes), onB = splat(uint8_t(b), lanes);
                    const auto onU = splat(uint8_t(slab.u), lanes), onW = splat(uint8_t(slab.w), lanes);
                    const auto rv = load(rRow + i, lanes), kv = load(kRow + i, lanes), av = load(aRow + i, lanes);
                    const auto lv = load(lRow + i, lanes);
                    // The face: lu x lw (u, w the slice's axes), where there is one.
                    const auto face = (av != onB) & (lv != kv);
                    const auto lu = select(av == onU, lv, kv), lw = select(av == onW, lv, kv);
                    auto e = select(face, none, select(av == onB, lv, kv));
                    if (!border) {
                        const auto kwv = load(kwRow + i, lanes), awv = load(awRow + i, lanes);
                        const auto lwv = load(lwRow + i, lanes);
                        const auto faceW = face & (awv != onB) & (lwv != kwv);
                        const auto luW = select(awv == onU, lwv, kwv), lwW = select(awv == onW, lwv, kwv);
                        const auto next = plusOne(load(ewRow + i, lanes));
                        const auto same = faceW & (luW == lu) & (lwW == lw);
                        const auto holds = faceW & (luW >= lu) & (lwW >= lw) & (rv <= next);
                        const auto blocked = face & ((kwv < kv) | ((kwv == kv) & (lwv < lv)));
                        e = select(same, minOf(rv, next),
                                   select(face & ((rv == kv) | holds), rv, select(blocked, kv, e)));
                    } else {
                        e = select(face & (rv == kv), rv, e);
                    }
                    store(eRow + i, e);
                    const auto query = e == none;
                    store(queryU + i, select(query, lu, none));
                    store(queryW + i, select(query, lw, none));
                });
            }
            faceMinima<false>(slab, r, ext, st.octant, sc);
        };
        auto finish = [&](const Slab& slab, int last) {
            finishSlab(slab, last,
                       {{&sc.edge, &sc.edgeBefore}, {&sc.widest, &sc.widestBefore}, {&sc.longest, &sc.longestBefore},
                        {&sc.ext, &sc.extBefore}},
                       sc.ext, extVolume);
        };
        walkSlices(st.runs.dims(), b, sign, gather, slice, finish);
    });
}

}  // namespace vr

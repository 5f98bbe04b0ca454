// EACD steps 1 and 2 (ALGORITHMS.md section 4): the extension of a box along an axis is the minimum, over its
// near face, of the axial runs along the octant's direction. Slices across the axis are walked toward -s (s the
// octant's sign there), so that the neighbour w = v + s e_a is done first: where w's face is v's, one step on,
// v's extension follows from w's in O(1) (16 voxels at a time), and the few others are queries of sparse tables
// over the slice's runs (instead of the thesis' quadratic face walk), shared by the octants of the batch with the
// same direction: O(1) for step 1's square faces, O(shorter side) for step 2's rectangles (1D tables: a few
// levels a slice, where 2D ones took dozens for a few queries).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <initializer_list>
#include <utility>

#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/eacd_batch.h"
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

// The face-query planes of every octant, one slice each.
void sizeQueries(const Slab& slab, std::size_t octants, WalkScratch& sc, bool rectangles) {
    for (std::size_t j = 0; j < octants; ++j) {
        sc.lenU[j].resize(slab.plane);
        if (rectangles) sc.lenW[j].resize(slab.plane);
    }
}

// Corner of a box's face along one in-plane axis: the face starts at p and goes toward `sign` for `len` voxels.
inline int faceStart(int p, int sign, int len) { return sign > 0 ? p : p - len + 1; }

// ext = minimum of the runs over each voxel's face where lenU is not 0, in the current slice of the octants
// `octs`. Square faces (kSquares: lenU == lenW, lenW unused) need only the square tables; rectangles the strips
// along their longer side.
template <bool kSquares>
void faceMinima(const Slab& slab, Rows runs, const std::array<MutableRows, 4>& ext, const std::vector<int>& octs,
                WalkScratch& sc) {
    const int nu = slab.nu, nw = slab.nw;
    // The tables those faces need: squares up to the largest; strips along u up to the longest face not taller
    // than wide, along w up to the longest taller one.
    uint8_t maxU = 0, maxW = 0;
    for (std::size_t j = 0; j < octs.size(); ++j) {
        const uint8_t* lenU = sc.lenU[j].data();
        if (kSquares) {
            maxU = std::max(maxU, maxOfRow(lenU, slab.plane));
            continue;
        }
        const uint8_t* lenW = sc.lenW[j].data();
        forEachNonzero(lenU, int(slab.plane), [&](int l) {
            if (lenW[l] <= lenU[l])
                maxU = std::max(maxU, lenU[l]);
            else
                maxW = std::max(maxW, lenW[l]);
        });
    }
    if (maxU == 0 && maxW == 0) return;  // no face in this slice
    uint8_t* image = sc.table.resize(nu, nw);
    for (int pw = 0; pw < nw; ++pw) std::copy_n(runs.row(pw), nu, image + std::size_t(pw) * nu);
    if (kSquares)
        sc.table.buildSquares(maxU);
    else
        sc.table.buildStrips(maxU, maxW);
    const RectMin::Query faceMin = sc.table.query();
    for (std::size_t j = 0; j < octs.size(); ++j) {
        const int su = octantSign(octs[j], slab.u), sw = octantSign(octs[j], slab.w);
        const uint8_t* lenU = sc.lenU[j].data();
        const uint8_t* lenW = (kSquares ? sc.lenU[j] : sc.lenW[j]).data();
        for (int pw = 0; pw < nw; ++pw, lenU += nu, lenW += nu) {
            uint8_t* e = ext[j].row(pw);
            forEachNonzero(lenU, nu, [&](int pu) {
                const int lu = lenU[pu], lw = lenW[pu];
                e[pu] = faceMin(faceStart(pu, su, lu), faceStart(pw, sw, lw), lu, lw);
            });
        }
    }
}

// Runs step(axis, sign, octs, scratch) for the six walks of a step (3 axes x 2 run directions; each a serial walk
// of slices), octs the batch's octants of that direction. The walks read the same inputs and write different
// extents, so they run at once: threads that finish early take another walk rather than wait for the slowest
// direction of an axis (at 512^3, 1.7 of 2 cores busy, walking one axis at a time). x first: its walks are longest.
template <typename Step>
void everyWalk(AxialRuns& runs, OctantBatch& batch, Step step) {
    runs.computeAll();  // before the threads share them
    std::vector<int> walks;  // axis + 3 * (sign < 0), of the directions the batch has octants in
    for (int axis = 0; axis < 3; ++axis)
        for (int d = 0; d < 2; ++d)
            if (!batch.withSign(axis, d ? -1 : 1).empty()) walks.push_back(axis + 3 * d);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, walks.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const int axis = walks[i] % 3, sign = walks[i] < 3 ? 1 : -1;
                step(axis, sign, batch.withSign(axis, sign), batch.scratch[walks[i]]);
            }
        },
        tbb::simple_partitioner());
}

}  // namespace

// Step 1: ext[o][a] = extension along a of the ACD cube (minimum of the runs over its k x k near face). With k, kw
// the ACD edges of v and w, r the run of v and ew the extension of w:
//   kw < k:        ext = k (the cube of edge k at w is not homogeneous, so no box at v longer than k is);
//   kw == k:       ext = min(r, 1 + ew) (w's face is v's, one step on);
//   r == k:        ext = k (v is on its face);
//   r <= 1 + ew:   ext = r (kw > k: w's face holds v's, one step on, so that reaches at least ew);
//   otherwise a query. Capped values keep every case exact: a capped k is the face's edge, 1 + ew saturates.
void cubeExtensions(AxialRuns& runFields, OctantBatch& batch) {
    everyWalk(runFields, batch, [&](int a, int sign, const std::vector<int>& octs, WalkScratch& sc) {
        const uint8_t* runs = runFields.get(a, sign).data();
        auto gather = [&](const Slab& slab) {
            sizeQueries(slab, octs.size(), sc, false);
            gatherSlab(slab, {{runs, &sc.runs}});
            for (std::size_t j = 0; j < octs.size(); ++j) {
                gatherSlab(slab, {{batch.acd[octs[j]]->data(), &sc.edge[j]}});
                if (!slab.inPlace()) sc.ext[j].resize(slab.size());
            }
        };
        auto slice = [&](const Slab& slab, int t, int tw) {
            const Rows r = sliceRows(slab, t, runs, sc.runs, sc.runs);
            std::array<MutableRows, 4> ext;
            for (std::size_t j = 0; j < octs.size(); ++j) {
                const int o = octs[j];
                const uint8_t* acd = batch.acd[o]->data();
                uint8_t* extVolume = batch.ext[o][a].data();
                const Rows k = sliceRows(slab, t, acd, sc.edge[j], sc.edgeBefore[j]);
                ext[j] = sliceRows(slab, t, extVolume, sc.ext[j], sc.extBefore[j]);
                uint8_t* query = sc.lenU[j].data();
                if (tw == kBorder) {  // the border slice: every run and edge is 1
                    for (int pw = 0; pw < slab.nw; ++pw) std::copy_n(r.row(pw), slab.nu, ext[j].row(pw));
                    std::fill_n(query, slab.plane, uint8_t(0));
                    continue;
                }
                const Rows kw = sliceRows(slab, tw, acd, sc.edge[j], sc.edgeBefore[j]);
                const MutableRows ew = sliceRows(slab, tw, extVolume, sc.ext[j], sc.extBefore[j]);
                for (int pw = 0; pw < slab.nw; ++pw, query += slab.nu) {
                    const uint8_t *rRow = r.row(pw), *kRow = k.row(pw), *kwRow = kw.row(pw), *ewRow = ew.row(pw);
                    uint8_t* eRow = ext[j].row(pw);
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
            }
            faceMinima<true>(slab, r, ext, octs, sc);
        };
        auto finish = [&](const Slab& slab, int last) {
            for (std::size_t j = 0; j < octs.size(); ++j)
                finishSlab(slab, last, {{&sc.edge[j], &sc.edgeBefore[j]}, {&sc.ext[j], &sc.extBefore[j]}}, sc.ext[j],
                           batch.ext[octs[j]][a].data());
        };
        walkSlices(runFields.dims(), a, sign, gather, slice, finish);
    });
}

// Step 2, for axis b: ext[o][b] = extension along b of the box extended along its widest axis a (a != b), whose
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
void boxExtensions(AxialRuns& runFields, OctantBatch& batch) {
    everyWalk(runFields, batch, [&](int b, int sign, const std::vector<int>& octs, WalkScratch& sc) {
        const uint8_t* runs = runFields.get(b, sign).data();
        auto gather = [&](const Slab& slab) {
            sizeQueries(slab, octs.size(), sc, true);
            gatherSlab(slab, {{runs, &sc.runs}});
            for (std::size_t j = 0; j < octs.size(); ++j) {
                const int o = octs[j];
                gatherSlab(slab, {{batch.acd[o]->data(), &sc.edge[j]},
                                  {batch.widest[o].data(), &sc.widest[j]},
                                  {batch.longest[o].data(), &sc.longest[j]}});
                if (!slab.inPlace()) sc.ext[j].resize(slab.size());
            }
        };
        auto slice = [&](const Slab& slab, int t, int tw) {
            const Rows r = sliceRows(slab, t, runs, sc.runs, sc.runs);
            const bool border = tw == kBorder;
            std::array<MutableRows, 4> ext;
            for (std::size_t j = 0; j < octs.size(); ++j) {
                const int o = octs[j];
                const uint8_t *acd = batch.acd[o]->data(), *widest = batch.widest[o].data(),
                              *longest = batch.longest[o].data();
                uint8_t* extVolume = batch.ext[o][b].data();
                const Rows k = sliceRows(slab, t, acd, sc.edge[j], sc.edgeBefore[j]),
                           axis = sliceRows(slab, t, widest, sc.widest[j], sc.widestBefore[j]),
                           len = sliceRows(slab, t, longest, sc.longest[j], sc.longestBefore[j]);
                ext[j] = sliceRows(slab, t, extVolume, sc.ext[j], sc.extBefore[j]);
                // The neighbour's (unread at the border: any slice will do).
                const int n = border ? t : tw;
                const Rows kw = sliceRows(slab, n, acd, sc.edge[j], sc.edgeBefore[j]),
                           axisW = sliceRows(slab, n, widest, sc.widest[j], sc.widestBefore[j]),
                           lenW = sliceRows(slab, n, longest, sc.longest[j], sc.longestBefore[j]);
                const MutableRows ew = sliceRows(slab, n, extVolume, sc.ext[j], sc.extBefore[j]);
                uint8_t *queryU = sc.lenU[j].data(), *queryW = sc.lenW[j].data();
                for (int pw = 0; pw < slab.nw; ++pw, queryU += slab.nu, queryW += slab.nu) {
                    const uint8_t *rRow = r.row(pw), *kRow = k.row(pw), *aRow = axis.row(pw), *lRow = len.row(pw);
                    const uint8_t *kwRow = kw.row(pw), *awRow = axisW.row(pw), *lwRow = lenW.row(pw),
                                  *ewRow = ew.row(pw);
                    uint8_t* eRow = ext[j].row(pw);
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
            }
            faceMinima<false>(slab, r, ext, octs, sc);
        };
        auto finish = [&](const Slab& slab, int last) {
            for (std::size_t j = 0; j < octs.size(); ++j)
                finishSlab(slab, last,
                           {{&sc.edge[j], &sc.edgeBefore[j]}, {&sc.widest[j], &sc.widestBefore[j]},
                            {&sc.longest[j], &sc.longestBefore[j]}, {&sc.ext[j], &sc.extBefore[j]}},
                           sc.ext[j], batch.ext[octs[j]][b].data());
        };
        walkSlices(runFields.dims(), b, sign, gather, slice, finish);
    });
}

}  // namespace vr

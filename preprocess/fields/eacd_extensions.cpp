// EACD steps 1 and 2 (ALGORITHMS.md section 4): the extension of a box along an axis is the minimum, over its
// near face, of the axial runs along the octant's direction. Slices across the axis are walked toward -s (s the
// octant's sign there), so that the neighbour w = v + s e_a is done first: where w's face is v's, one step on,
// v's extension follows from w's in O(1) (16 voxels at a time), and the few others are O(1) queries of a 2D sparse
// table over the slice's runs (instead of the thesis' quadratic face walk), shared by the octants of the batch
// with the same direction.
#include <tbb/parallel_for.h>

#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/eacd_batch.h"
#include "preprocess/fields/rect_min.h"
#include "preprocess/fields/slab.h"

namespace vr {

namespace {

// Working memory of one run direction's walk: the slab's runs and, per octant of that direction, its inputs
// (ACD edge k; step 2: widest axis and its extent), its extension along the walked axis (ext) and each voxel's face
// to query (lenU x lenW; lenU = 0 for none), lenU being overwritten by the minimum over the face. The *Before
// planes keep the slice done last in the slab before: the neighbour of this slab's first.
struct WalkScratch {
    RectMin table;
    std::vector<uint8_t> runs;
    std::array<std::vector<uint8_t>, 4> edge, widest, longest, ext, lenU, lenW;
    std::array<std::vector<uint8_t>, 4> edgeBefore, widestBefore, longestBefore, extBefore;
};

// Local slice t of a per-octant array, its kept plane for kSlabBefore, null for kBorder (nothing to read there).
const uint8_t* sliceOf(const std::vector<uint8_t>& local, const std::vector<uint8_t>& before, const Slab& slab, int t) {
    if (t == kBorder) return nullptr;
    return t == kSlabBefore ? before.data() : local.data() + std::size_t(t) * slab.pitch;
}

// Keeps local slice t of `local` in `before`.
void keepSlice(const std::vector<uint8_t>& local, std::vector<uint8_t>& before, const Slab& slab, int t) {
    before.resize(slab.plane);
    std::copy_n(local.data() + t * slab.pitch, slab.plane, before.data());
}

// Corner of a box's face along one in-plane axis: the face starts at p and goes toward `sign` for `len` voxels.
inline int faceStart(int p, int sign, int len) { return sign > 0 ? p : p - len + 1; }

// For slice t of the slab: lenU = minimum of the runs over each voxel's face (skipped where lenU is 0), for the
// octants `octs`. Square faces (kSquares: lenU == lenW, lenW unused) need only the square tables.
template <bool kSquares>
void faceMinima(const Slab& slab, int t, const std::vector<int>& octs, WalkScratch& sc) {
    const int nu = slab.nu, nw = slab.nw;
    const std::size_t off = t * slab.pitch;
    // The tables those faces need: squares up to the largest; rectangles of the level pairs met.
    uint8_t maxU = 0;
    RectMin::Levels levels{};
    for (std::size_t j = 0; j < octs.size(); ++j) {
        const uint8_t* lenU = sc.lenU[j].data() + off;
        if (kSquares) {
            maxU = std::max(maxU, maxOfRow(lenU, slab.plane));
            continue;
        }
        const uint8_t* lenW = sc.lenW[j].data() + off;
        forEachNonzero(lenU, int(slab.plane), [&](int l) { RectMin::addLevels(levels, lenU[l], lenW[l]); });
    }
    if (maxU == 0 && levels == RectMin::Levels{}) return;  // no face in this slice
    std::copy_n(sc.runs.data() + off, slab.plane, sc.table.resize(nu, nw));
    if (kSquares)
        sc.table.buildSquares(maxU);
    else
        sc.table.build(levels);
    const RectMin::Query faceMin = sc.table.query();
    for (std::size_t j = 0; j < octs.size(); ++j) {
        const int su = octantSign(octs[j], slab.u), sw = octantSign(octs[j], slab.w);
        uint8_t* lenU = sc.lenU[j].data() + off;
        const uint8_t* lenW = (kSquares ? sc.lenU[j] : sc.lenW[j]).data() + off;
        for (int pw = 0; pw < nw; ++pw, lenU += nu, lenW += nu)
            forEachNonzero(lenU, nu, [&](int pu) {
                const int lu = lenU[pu], lw = lenW[pu];
                lenU[pu] = faceMin(faceStart(pu, su, lu), faceStart(pw, sw, lw), lu, lw);
            });
    }
}

// ext = the face minimum where one was queried (lenU != 0), for slice t of every octant.
void takeMinima(const Slab& slab, int t, std::size_t octants, WalkScratch& sc) {
    const std::size_t off = t * slab.pitch;
    for (std::size_t j = 0; j < octants; ++j) {
        uint8_t *ext = sc.ext[j].data() + off, *minimum = sc.lenU[j].data() + off;
        forEachLane(slab.plane, [&](std::size_t i, auto lanes) {
            const auto m = load(minimum + i, lanes);
            store(ext + i, select(m == splat(0, lanes), load(ext + i, lanes), m));
        });
    }
}

// Runs step(sign, octs, scratch) for both run directions along `axis` at once (each a serial walk of slices);
// octs are the batch's octants of that direction.
template <typename Step>
void bothDirections(AxialRuns& runs, const OctantBatch& batch, int axis, Step step) {
    runs.get(axis, 1);  // computed before the threads share them
    runs.get(axis, -1);
    std::array<WalkScratch, 2> scratch;
    tbb::parallel_for(0, 2, [&](int d) {
        const int sign = d ? -1 : 1;
        const std::vector<int> octs = batch.withSign(axis, sign);
        if (!octs.empty()) step(sign, octs, scratch[d]);
    });
}

}  // namespace

// Step 1: ext[o][a] = extension along a of the ACD cube (minimum of the runs over its k x k near face). With k, kw
// the ACD edges of v and w, r the run of v and ew the extension of w:
//   kw < k:        ext = k (the cube of edge k at w is not homogeneous, so no box at v longer than k is);
//   kw == k:       ext = min(r, 1 + ew) (w's face is v's, one step on);
//   r == k:        ext = k (v is on its face);
//   r <= 1 + ew:   ext = r (kw > k: w's face holds v's, one step on, so that reaches at least ew);
//   otherwise a query. Capped values keep every case exact: a capped k is the face's edge, 1 + ew saturates.
void cubeExtensions(AxialRuns& runFields, OctantBatch& batch, int a) {
    bothDirections(runFields, batch, a, [&](int sign, const std::vector<int>& octs, WalkScratch& sc) {
        const uint8_t* runs = runFields.get(a, sign).data();
        auto gather = [&](const Slab& slab) {
            sc.runs.resize(slab.size());
            slab.gather(runs, sc.runs.data());
            for (std::size_t j = 0; j < octs.size(); ++j) {
                for (auto* v : {&sc.edge[j], &sc.ext[j], &sc.lenU[j]}) v->resize(slab.size());
                slab.gather(batch.acd[octs[j]]->data(), sc.edge[j].data());
            }
        };
        auto slice = [&](const Slab& slab, int t, int tw) {
            const std::size_t off = t * slab.pitch;
            for (std::size_t j = 0; j < octs.size(); ++j) {
                const uint8_t *r = sc.runs.data() + off, *k = sc.edge[j].data() + off;
                const uint8_t *kw = sliceOf(sc.edge[j], sc.edgeBefore[j], slab, tw),
                              *ew = sliceOf(sc.ext[j], sc.extBefore[j], slab, tw);
                uint8_t *ext = sc.ext[j].data() + off, *query = sc.lenU[j].data() + off;
                if (tw == kBorder) {  // the border slice: every run and edge is 1
                    std::copy_n(r, slab.plane, ext);
                    std::fill_n(query, slab.plane, uint8_t(0));
                    continue;
                }
                forEachLane(slab.plane, [&](std::size_t i, auto lanes) {
                    const auto rv = load(r + i, lanes), kv = load(k + i, lanes), kwv = load(kw + i, lanes);
                    const auto next = plusOne(load(ew + i, lanes)), none = splat(0, lanes);
                    const auto e = select(kwv < kv, kv,
                                          select(kwv == kv, minOf(rv, next),
                                                 select((rv == kv) | (rv <= next), rv, none)));
                    store(ext + i, e);
                    store(query + i, select(e == none, kv, none));
                });
            }
            faceMinima<true>(slab, t, octs, sc);
            takeMinima(slab, t, octs.size(), sc);
        };
        auto finish = [&](const Slab& slab, int last) {
            for (std::size_t j = 0; j < octs.size(); ++j) {
                keepSlice(sc.edge[j], sc.edgeBefore[j], slab, last);
                keepSlice(sc.ext[j], sc.extBefore[j], slab, last);
                slab.scatter(sc.ext[j].data(), batch.ext[octs[j]][a].data());
            }
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
void boxExtensions(AxialRuns& runFields, OctantBatch& batch, int b) {
    bothDirections(runFields, batch, b, [&](int sign, const std::vector<int>& octs, WalkScratch& sc) {
        const uint8_t* runs = runFields.get(b, sign).data();
        auto gather = [&](const Slab& slab) {
            sc.runs.resize(slab.size());
            slab.gather(runs, sc.runs.data());
            for (std::size_t j = 0; j < octs.size(); ++j) {
                const int o = octs[j];
                for (auto* v : {&sc.edge[j], &sc.widest[j], &sc.longest[j], &sc.ext[j], &sc.lenU[j], &sc.lenW[j]})
                    v->resize(slab.size());
                slab.gather(batch.acd[o]->data(), sc.edge[j].data());
                slab.gather(batch.widest[o].data(), sc.widest[j].data());
                slab.gather(batch.longest[o].data(), sc.longest[j].data());
            }
        };
        auto slice = [&](const Slab& slab, int t, int tw) {
            const std::size_t off = t * slab.pitch;
            for (std::size_t j = 0; j < octs.size(); ++j) {
                const uint8_t *r = sc.runs.data() + off, *k = sc.edge[j].data() + off;
                const uint8_t *axis = sc.widest[j].data() + off, *longest = sc.longest[j].data() + off;
                const uint8_t *kw = sliceOf(sc.edge[j], sc.edgeBefore[j], slab, tw),
                              *axisW = sliceOf(sc.widest[j], sc.widestBefore[j], slab, tw),
                              *longestW = sliceOf(sc.longest[j], sc.longestBefore[j], slab, tw),
                              *ew = sliceOf(sc.ext[j], sc.extBefore[j], slab, tw);
                uint8_t *ext = sc.ext[j].data() + off, *lenU = sc.lenU[j].data() + off, *lenW = sc.lenW[j].data() + off;
                const bool border = tw == kBorder;
                forEachLane(slab.plane, [&](std::size_t i, auto lanes) {
                    const auto none = splat(0, lanes), onB = splat(uint8_t(b), lanes);
                    const auto onU = splat(uint8_t(slab.u), lanes), onW = splat(uint8_t(slab.w), lanes);
                    const auto rv = load(r + i, lanes), kv = load(k + i, lanes), av = load(axis + i, lanes);
                    const auto lv = load(longest + i, lanes);
                    // The face: lu x lw (u, w the slice's axes), where there is one.
                    const auto face = (av != onB) & (lv != kv);
                    const auto lu = select(av == onU, lv, kv), lw = select(av == onW, lv, kv);
                    auto e = select(face, none, select(av == onB, lv, kv));
                    if (!border) {
                        const auto kwv = load(kw + i, lanes), awv = load(axisW + i, lanes);
                        const auto lwv = load(longestW + i, lanes);
                        const auto faceW = face & (awv != onB) & (lwv != kwv);
                        const auto luW = select(awv == onU, lwv, kwv), lwW = select(awv == onW, lwv, kwv);
                        const auto next = plusOne(load(ew + i, lanes));
                        const auto same = faceW & (luW == lu) & (lwW == lw);
                        const auto holds = faceW & (luW >= lu) & (lwW >= lw) & (rv <= next);
                        const auto blocked = face & ((kwv < kv) | ((kwv == kv) & (lwv < lv)));
                        e = select(same, minOf(rv, next),
                                   select(face & ((rv == kv) | holds), rv, select(blocked, kv, e)));
                    } else {
                        e = select(face & (rv == kv), rv, e);
                    }
                    store(ext + i, e);
                    const auto query = e == none;
                    store(lenU + i, select(query, lu, none));
                    store(lenW + i, select(query, lw, none));
                });
            }
            faceMinima<false>(slab, t, octs, sc);
            takeMinima(slab, t, octs.size(), sc);
        };
        auto finish = [&](const Slab& slab, int last) {
            for (std::size_t j = 0; j < octs.size(); ++j) {
                keepSlice(sc.edge[j], sc.edgeBefore[j], slab, last);
                keepSlice(sc.widest[j], sc.widestBefore[j], slab, last);
                keepSlice(sc.longest[j], sc.longestBefore[j], slab, last);
                keepSlice(sc.ext[j], sc.extBefore[j], slab, last);
                slab.scatter(sc.ext[j].data(), batch.ext[octs[j]][b].data());
            }
        };
        walkSlices(runFields.dims(), b, sign, gather, slice, finish);
    });
}

}  // namespace vr

// EACD (docs/ALGORITHMS.md section 4): the ACD cube of edge k, extended greedily along the axis giving the largest box
// (step 1, eacd_extensions.cpp), then along the better of the two others (step 2, ibid.; step 3 here picks it).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <bit>
#include <cstring>

#include "preprocess/fields/build_fields.h"
#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/eacd_state.h"

namespace vr {

namespace {

// Between steps 1 and 2: the axis that step 1 extends (the first with the largest extent: ties go to x, then y,
// then z), and its extent, per voxel.
void findWidestAxes(OctantState& st) {
    const uint8_t *ex = st.ext[0].data(), *ey = st.ext[1].data(), *ez = st.ext[2].data();
    uint8_t *widest = st.widest.data(), *longest = st.longest.data();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, st.acd->size(), 1 << 16), [&](const auto& range) {
        forEachLane(range.size(), [&, at = range.begin()](std::size_t i, auto t) {
            const std::size_t v = at + i;
            const auto x = load(ex + v, t), y = load(ey + v, t), z = load(ez + v, t);
            const auto yWins = y > x;  // a mask: its own declaration (its type is not the bytes' type)
            const auto best = select(yWins, y, x);
            const auto zWins = z > best;
            store(widest + v, select(zWins, splat(2, t), select(yWins, splat(1, t), splat(0, t))));
            store(longest + v, select(zWins, z, best));
        });
    });
}

// Step 3: the box is k on every axis but the widest a (step 1's extension) and the better of the two others
// (ties to the lower axis). Computed in planar blocks, then written in the field's code: the sum of one term per
// axis (extent_code.h), stored as the code's bytes.
void chooseBoxes(const OctantState& st, ExtentField& out) {
    const uint8_t* acd = st.acd->data();
    const uint8_t *ex = st.ext[0].data(), *ey = st.ext[1].data(), *ez = st.ext[2].data();
    const uint8_t* widest = st.widest.data();
    const ExtentCodeTerms& term = extentCodeTerms(out.code());
    const std::size_t codeBytes = extentCodeBytes(out.code());
    static_assert(std::endian::native == std::endian::little, "a code's bytes are the low bytes of its word");
    constexpr std::size_t kBlock = 4096;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), kBlock), [&](const auto& range) {
        for (std::size_t at = range.begin(); at < range.end(); at += kBlock) {
            const std::size_t count = std::min(kBlock, range.end() - at);
            uint8_t box[3][kBlock];
            forEachLane(count, [&](std::size_t i, auto t) {
                const std::size_t v = at + i;
                const auto a = load(widest + v, t), k = load(acd + v, t);
                const auto x = load(ex + v, t), y = load(ey + v, t), z = load(ez + v, t);
                const auto onX = a == splat(0, t), onY = a == splat(1, t), onZ = a == splat(2, t);
                const auto xy = x >= y, xz = x >= z, yz = y >= z;
                store(box[0] + i, select(onX | (onY & xz) | (onZ & xy), x, k));
                store(box[1] + i, select(onY | (onX & yz) | (onZ & (xy == 0)), y, k));
                store(box[2] + i, select(onZ | (onX & (yz == 0)) | (onY & (xz == 0)), z, k));
            });
            // A voxel's 4-byte word spills into the next voxels' bytes, rewritten next; the block's last voxels
            // write only their own, as the bytes after the block may be another thread's.
            uint8_t* bytes = out.data() + at * codeBytes;
            std::size_t i = 0;
            auto word = [&] { return term[0][box[0][i]] + term[1][box[1][i]] + term[2][box[2][i]]; };
            for (; codeBytes * i + 4 <= codeBytes * count; ++i) {
                const uint32_t w = word();
                std::memcpy(bytes + codeBytes * i, &w, 4);
            }
            for (; i < count; ++i) {
                const uint32_t w = word();
                std::memcpy(bytes + codeBytes * i, &w, codeBytes);
            }
        }
    });
}

// The ACD of octant o, checked against the regions.
void checkACD(const AxialRuns& runs, int o, const std::vector<uint8_t>& acd) {
    if (acd.size() != voxelCount(runs.dims()))
        throw std::invalid_argument("buildEACD: the ACD of octant " + std::to_string(o) +
                                    " does not match the regions");
}

// Steps 1 and 2 of octant o: its extents, in the state's planar volumes.
void extendOctant(OctantState& st, int o, const std::vector<uint8_t>& acd) {
    st.octant = o;
    st.acd = &acd;
    cubeExtensions(st);
    findWidestAxes(st);
    boxExtensions(st);
}

}  // namespace

ExtentField buildEACD(const Regions& regions, const std::vector<uint8_t>& acd, int octant) {
    if (octant < 0 || octant >= kOctants) throw std::invalid_argument("buildEACD: no octant " + std::to_string(octant));
    AxialRuns runs(regions);
    checkACD(runs, octant, acd);
    OctantState state(runs, 1u << octant);
    extendOctant(state, octant, acd);
    ExtentField out(ExtentCode::Exact, acd.size());
    chooseBoxes(state, out);
    return out;
}

std::array<ExtentField, kOctants> buildEACD(const Regions& regions, const ACDFields& acd) {
    AxialRuns runs(regions);
    return buildEACD(runs, acd);
}

std::array<ExtentField, kOctants> buildEACD(AxialRuns& runs, const ACDFields& acd, ExtentCode code,
                                            unsigned octants, const Progress& progress) {
    for (int o = 0; o < kOctants; ++o)
        if (octants >> o & 1u) checkACD(runs, o, acd[o]);
    std::array<ExtentField, kOctants> out;
    // Each output is zeroed (and its pages mapped) by a task of its own, waited for just before its octant's boxes
    // are chosen: a thread done with its walks while the other still walks takes them (the three walks of a step
    // on two threads leave about a tenth of the time idle otherwise).
    std::array<tbb::task_group, kOctants> sizing;
    for (int o = 0; o < kOctants; ++o)
        if (octants >> o & 1u) sizing[o].run([&, o] { out[o] = ExtentField(code, acd[o].size()); });
    // One octant at a time: 7 bytes of working memory per voxel, 2 of them the runs along x copied for the walks
    // (0.9 GB at 512^3, where the footprint makes fresh pages dear; 6 and 1 for a single octant). (Batches of two
    // opposite octants took as long, with twice the memory; batches of four, sharing each table by two octants, too:
    // what the tables saved, mapping the memory cost.)
    OctantState state(runs, octants);
    // For the progress: the first octant takes as long as kFirstOctant others (a 512^3 CT's on 2 cores: 3.5 s, then
    // 0.5 to 1.1 s each), as the outputs are zeroed beside it.
    constexpr double kFirstOctant = 4;
    const double units = kFirstOctant + std::popcount(octants & kAllOctants) - 1;
    double done = 0;
    for (int o = 0; o < kOctants; ++o) {
        if (!(octants >> o & 1u)) continue;
        extendOctant(state, o, acd[o]);
        sizing[o].wait();
        chooseBoxes(state, out[o]);
        done += done == 0 ? kFirstOctant : 1;
        reportProgress(progress, done / units);
    }
    return out;
}

}  // namespace vr

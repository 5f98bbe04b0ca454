// EACD (ALGORITHMS.md section 4): the ACD cube of edge k, extended greedily along the axis giving the largest box
// (step 1, eacd_extensions.cpp), then along the better of the two others (step 2, ibid.; step 3 here picks it).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <bit>
#include <cstring>

#include "preprocess/fields/build_fields.h"
#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/eacd_batch.h"

namespace vr {

namespace {

// Between steps 1 and 2: the axis that step 1 extends (the first with the largest extent: ties go to x, then y,
// then z), and its extent, per voxel.
void findWidestAxes(OctantBatch& batch) {
    for (int o : batch.octants) {
        const uint8_t *ex = batch.ext[o][0].data(), *ey = batch.ext[o][1].data(), *ez = batch.ext[o][2].data();
        uint8_t *widest = batch.widest[o].data(), *longest = batch.longest[o].data();
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batch.acd[o]->size(), 1 << 16), [&](const auto& range) {
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
}

// Per axis a, every extent 0..255 rounded down to a code (the codes round each axis on its own, extent_code.h),
// placed in byte a of a word: a voxel's three extents are then one 4-byte store.
using Rounding = std::array<std::array<uint32_t, 256>, 3>;
Rounding roundingTables(ExtentCode code) {
    static_assert(std::endian::native == std::endian::little, "byte a of a word is its bits 8a..8a+7");
    Rounding r;
    for (int v = 0; v < 256; ++v) {
        const Extents e = quantiseExtents(code, {uint8_t(v), uint8_t(v), uint8_t(v)});
        for (int a = 0; a < 3; ++a) r[a][v] = uint32_t(e[a]) << (8 * a);
    }
    return r;
}

// Step 3: the box is k on every axis but the widest a (step 1's extension) and the better of the two others
// (ties to the lower axis). Computed in planar blocks, then interleaved and rounded down to the code.
void chooseBoxes(const OctantBatch& batch, int o, const Rounding& round, EACDField& out) {
    const uint8_t* acd = batch.acd[o]->data();
    const uint8_t *ex = batch.ext[o][0].data(), *ey = batch.ext[o][1].data(), *ez = batch.ext[o][2].data();
    const uint8_t* widest = batch.widest[o].data();
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
            // Each voxel's word overlaps the next voxel's first byte, rewritten next; the block's last voxel
            // takes 3 bytes, as the byte after it may be another thread's.
            static_assert(sizeof(Extents) == 3);
            uint8_t* bytes = out[at].data();
            auto word = [&](std::size_t i) { return round[0][box[0][i]] | round[1][box[1][i]] | round[2][box[2][i]]; };
            for (std::size_t i = 0; i + 1 < count; ++i) {
                const uint32_t w = word(i);
                std::memcpy(bytes + 3 * i, &w, 4);
            }
            const uint32_t last = word(count - 1);
            std::memcpy(bytes + 3 * (count - 1), &last, 3);
        }
    });
}

// EACD of `octants` into their outputs, already sized. The planar extents take 5 bytes per voxel and octant while
// the batch is built; a batch reuses the volumes the batch before it left in batch.spare.
void buildBatch(AxialRuns& runs, OctantBatch& batch, const std::vector<int>& octants,
                const std::array<const std::vector<uint8_t>*, kOctants>& acd,
                const std::array<EACDField*, kOctants>& out, ExtentCode code) {
    const std::size_t voxels = runs.regions().label.size();
    batch.octants = octants;
    for (int o : octants) {
        if (acd[o]->size() != voxels)
            throw std::invalid_argument("buildEACD: the ACD of octant " + std::to_string(o) +
                                        " does not match the regions");
        batch.acd[o] = acd[o];
        for (auto& slot : batch.ext[o]) slot = batch.take(voxels);
        batch.widest[o] = batch.take(voxels);
        batch.longest[o] = batch.take(voxels);
    }
    cubeExtensions(runs, batch);
    findWidestAxes(batch);
    boxExtensions(runs, batch);
    const Rounding round = roundingTables(code);
    for (int o : octants) {
        chooseBoxes(batch, o, round, *out[o]);
        for (auto& slot : batch.ext[o]) batch.spare.push_back(std::move(slot));
        batch.spare.push_back(std::move(batch.widest[o]));
        batch.spare.push_back(std::move(batch.longest[o]));
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
    AxialRuns runs(regions);
    OctantBatch batch;
    out.resize(acd.size());
    buildBatch(runs, batch, {octant}, acds, outs, ExtentCode::Exact);
    return out;
}

std::array<EACDField, kOctants> buildEACD(const Regions& regions, const ACDFields& acd) {
    AxialRuns runs(regions);
    return buildEACD(runs, acd);
}

std::array<EACDField, kOctants> buildEACD(AxialRuns& runs, const ACDFields& acd, ExtentCode code) {
    std::array<EACDField, kOctants> out;
    std::array<const std::vector<uint8_t>*, kOctants> acds{};
    std::array<EACDField*, kOctants> outs{};
    for (int o = 0; o < kOctants; ++o) {
        acds[o] = &acd[o];
        outs[o] = &out[o];
    }
    // The outputs are zeroed (and their pages mapped) first, on both threads: one at a time, that was serial.
    tbb::parallel_for(0, kOctants, [&](int o) { out[o].resize(acd[o].size()); });
    // One octant at a time: 5 bytes of working memory per voxel (0.7 GB at 512^3, where the footprint makes fresh
    // pages dear). The three walks of a step run at once and the x walk takes about as long as the y and z walks
    // together, so both threads stay busy. (Batches of two opposite octants took as long, with twice the memory;
    // batches of four, sharing each table by two octants, too: what the tables saved, mapping the memory cost.)
    OctantBatch batch;
    for (int o = 0; o < kOctants; ++o) buildBatch(runs, batch, {o}, acds, outs, code);
    return out;
}

}  // namespace vr

// PC from the ACDs, and the driver building the requested fields.
#include "preprocess/fields/build_fields.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "preprocess/fields/byte_rows.h"

namespace vr {

namespace {

// The centred cube of Chebyshev radius r is the union of the 8 octant cubes of edge r + 1 cornered at v,
// so pc = min over octants of acd - 1 exactly (capped at 254 because ACD caps at 255).
void lowerToACD(uint8_t* minACD, const uint8_t* acd, std::size_t n) {
    forEachLane(n, [&](std::size_t k, auto t) { store(minACD + k, minOf(load(minACD + k, t), load(acd + k, t))); });
}

void lowerToACDInParallel(std::vector<uint8_t>& minACD, const std::vector<uint8_t>& acd) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, acd.size(), 1 << 16), [&](const auto& r) {
        lowerToACD(minACD.data() + r.begin(), acd.data() + r.begin(), r.size());
    });
}

void toRadius(std::vector<uint8_t>& minACD) {
    for (uint8_t& m : minACD) m = uint8_t(m - 1);  // every ACD is >= 1
}

}  // namespace

std::vector<uint8_t> pcFromACD(const ACDFields& acd) {
    std::array<const uint8_t*, kOctants> from;
    for (int o = 0; o < kOctants; ++o) {
        if (acd[o].size() != acd[0].size()) throw std::invalid_argument("pcFromACD: the octants differ in size");
        from[o] = acd[o].data();
    }
    // One parallel pass over the eight: a copy, seven lowerings and a serial pass to the radius moved 2.7 times the
    // bytes.
    std::vector<uint8_t> pc(acd[0].size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pc.size(), 1 << 16), [&](const auto& r) {
        forEachLane(r.size(), [&, at = r.begin()](std::size_t i, auto t) {
            const std::size_t v = at + i;
            auto m = load(from[0] + v, t);
            for (int o = 1; o < kOctants; ++o) m = minOf(m, load(from[o] + v, t));
            store(pc.data() + v, decltype(m)(m - splat(1, t)));  // every ACD is >= 1
        });
    });
    return pc;
}

std::vector<uint8_t> buildPC(const Regions& regions) {
    AxialRuns runs(regions);
    const std::size_t voxels = regions.label.size();
    if (voxels == 0) return {};
    runs.computeAll();
    // One minimum per thread rather than all eight ACDs at once. Lowered serially: a thread waiting inside a
    // parallel loop may run another octant's task, which must not meet a half-lowered minimum.
    tbb::enumerable_thread_specific<std::vector<uint8_t>> minima(voxels, uint8_t(kDistanceCap));
    tbb::parallel_for(0, kOctants, [&](int o) {
        const std::vector<uint8_t> acd = buildACD(runs, o);
        lowerToACD(minima.local().data(), acd.data(), voxels);
    });
    auto first = minima.begin();
    std::vector<uint8_t> pc = std::move(*first);
    for (auto it = ++first; it != minima.end(); ++it) lowerToACDInParallel(pc, *it);
    toRadius(pc);
    return pc;
}

ACDFields buildACDs(const Regions& regions) {
    AxialRuns runs(regions);
    return buildACDs(runs);
}

DistanceFields buildFields(const Regions& regions, unsigned kinds) {
    return buildFields(regions, kinds, [](FieldKind) {});
}

DistanceFields buildFields(const Regions& regions, unsigned kinds, const std::function<void(FieldKind)>& done) {
    return buildFields(regions, kinds, ExtentCode::Exact, done);
}

namespace {

// The fields' shares of their time, as a 512^3 CT took them on 2 cores: the runs with the ACDs 3.3 s, PC from them
// 0.36 s, EACD 16.2 s (its octants alike).
constexpr double kAcdShare = 1, kPcShare = 0.1, kEacdShare = 5;

// `release` is called once every axial run the fields read is made: the labels are no longer read after it.
DistanceFields buildFieldsReleasing(const Regions& regions, unsigned kinds, ExtentCode eacdCode,
                                    const std::function<void(FieldKind)>& done, unsigned octants,
                                    const Progress& progress, const std::function<void()>& release) {
    DistanceFields f;
    f.dims = regions.dims;
    const bool pc = kinds & kFieldPC, acd = kinds & (kFieldACD | kFieldEACD), eacd = kinds & kFieldEACD;
    if (!acd) {
        if (pc) {
            f.pc = buildPC(regions);
            done(kFieldPC);
        }
        release();
        reportProgress(progress, 1);
        return f;
    }
    const double total = kAcdShare + (pc ? kPcShare : 0) + (eacd ? kEacdShare : 0);
    AxialRuns runs(regions);
    const unsigned acdOctants = pc ? kAllOctants : octants;
    runs.computeAll(acdOctants);  // every run the ACDs and the EACD read
    release();
    ACDFields acds = buildACDs(runs, acdOctants);
    done(kFieldACD);
    double reached = kAcdShare / total;
    reportProgress(progress, reached);
    if (pc) {
        f.pc = pcFromACD(acds);
        done(kFieldPC);
        reportProgress(progress, reached += kPcShare / total);
    }
    if (eacd) {
        f.eacd = buildEACD(runs, acds, eacdCode, octants, progressPart(progress, reached, 1));
        done(kFieldEACD);
    }
    if (kinds & kFieldACD) {
        f.acd = std::move(acds);
        for (int o = 0; o < kOctants; ++o)
            if (!(octants >> o & 1u)) f.acd[o] = {};
    }
    return f;
}

}  // namespace

DistanceFields buildFields(const Regions& regions, unsigned kinds, ExtentCode eacdCode,
                           const std::function<void(FieldKind)>& done, unsigned octants, const Progress& progress) {
    return buildFieldsReleasing(regions, kinds, eacdCode, done, octants, progress, [] {});
}

DistanceFields buildFields(Regions&& regions, unsigned kinds, ExtentCode eacdCode,
                           const std::function<void(FieldKind)>& done, unsigned octants, const Progress& progress) {
    Regions consumed = std::move(regions);
    return buildFieldsReleasing(consumed, kinds, eacdCode, done, octants, progress,
                                [&] { std::vector<uint32_t>().swap(consumed.label); });
}

}  // namespace vr

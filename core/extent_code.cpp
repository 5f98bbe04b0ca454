#include "extent_code.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <string>

#include "distance_fields.h"
#include "enum_names.h"
#include "errors.h"
#include "extent_field.h"

namespace vr {
namespace {

// Log16: the 32 values of a 5-bit index. 1..16 exactly (short leaps are common and every voxel lost there is
// a large fraction of the leap), then round(16 * (255/16)^(k/16)), k = 1..16: at most 16 % of a long leap is lost.
constexpr std::array<uint8_t, 32> kLog16Values = {
    1,  2,  3,  4,  5,  6,  7,  8,  9,  10, 11,  12,  13,  14,  15,  16,
    19, 23, 27, 32, 38, 45, 54, 64, 76, 90, 107, 128, 152, 180, 214, 255};
// Joint8: the levels of each axis; the table holds every (x, y, z) of levels, x fastest (6^3 = 216 boxes). Level
// sets topping out at 32, 48, 50 and 64 came within 2 % of each other in iterations per ray on the teapot and the
// cranium (bench/extent_code_bench); this one was best on the cranium.
constexpr std::array<uint8_t, 6> kJoint8Levels = {1, 2, 4, 8, 20, 50};
constexpr int kJoint8Side = int(kJoint8Levels.size());
static_assert(kJoint8Side * kJoint8Side * kJoint8Side <= kExtentTableEntries);

template <std::size_t N>
constexpr bool increasingFromOne(const std::array<uint8_t, N>& values) {
    for (std::size_t i = 1; i < N; ++i)
        if (values[i] <= values[i - 1]) return false;
    return values[0] == 1;
}
static_assert(increasingFromOne(kLog16Values) && kLog16Values.back() == 255, "log16 must reach the 255 cap");
static_assert(increasingFromOne(kJoint8Levels));

// For every extent 0..255, the index of the largest value not above it (0 for the invalid extent 0).
template <std::size_t N>
constexpr std::array<uint8_t, 256> floorIndex(const std::array<uint8_t, N>& values) {
    std::array<uint8_t, 256> index{};
    std::size_t i = 0;
    for (int v = 0; v < 256; ++v) {
        while (i + 1 < N && values[i + 1] <= v) ++i;
        index[std::size_t(v)] = uint8_t(i);
    }
    return index;
}
constexpr std::array<uint8_t, 256> kLog16Index = floorIndex(kLog16Values);
constexpr std::array<uint8_t, 256> kJoint8Index = floorIndex(kJoint8Levels);

// Runs f(i) for i in [0, n) on all threads.
template <typename F>
void forEachVoxel(std::size_t n, F f) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) f(i);
    });
}

ExtentTable makeTable(ExtentCode code) {
    ExtentTable t;
    t.fill({1, 1, 1, 0});
    if (code == ExtentCode::Log16)
        for (std::size_t i = 0; i < kLog16Values.size(); ++i)
            t[i] = {kLog16Values[i], kLog16Values[i], kLog16Values[i], 0};
    if (code == ExtentCode::Joint8)
        for (int i = 0; i < kJoint8Side * kJoint8Side * kJoint8Side; ++i)
            t[std::size_t(i)] = {kJoint8Levels[std::size_t(i % kJoint8Side)],
                                 kJoint8Levels[std::size_t(i / kJoint8Side % kJoint8Side)],
                                 kJoint8Levels[std::size_t(i / (kJoint8Side * kJoint8Side))], 0};
    return t;
}

}  // namespace

constexpr EnumName<ExtentCode> kExtentCodeNames[] = {
    {ExtentCode::Exact, "exact"}, {ExtentCode::Log16, "log16"}, {ExtentCode::Joint8, "joint8"}};

std::string_view extentCodeName(ExtentCode code) { return nameOf(kExtentCodeNames, code); }

ExtentCode parseExtentCode(std::string_view name, std::string_view what) {
    try {
        return valueNamed(kExtentCodeNames, name, "EACD code");
    } catch (const InputError& e) {
        throw InputError(std::string(what) + ": " + e.what());
    }
}

const ExtentCodeTerms& extentCodeTerms(ExtentCode code) {
    // The tables of both compact codes are products of per-axis values, so the largest box inside e takes the
    // largest value not above e on each axis.
    static const std::array<ExtentCodeTerms, 3> terms = [] {
        std::array<ExtentCodeTerms, 3> t{};
        for (std::size_t v = 0; v < 256; ++v)
            for (std::size_t a = 0; a < 3; ++a) {
                t[int(ExtentCode::Exact)][a][v] = uint32_t(v) << (8 * a);
                t[int(ExtentCode::Log16)][a][v] = uint32_t(kLog16Index[v]) << (5 * a);
                t[int(ExtentCode::Joint8)][a][v] = kJoint8Index[v] * uint32_t(a == 0 ? 1 : a == 1 ? kJoint8Side
                                                                                          : kJoint8Side * kJoint8Side);
            }
        return t;
    }();
    return terms[int(code)];
}

uint32_t encodeExtents(ExtentCode code, const Extents& e) {
    const ExtentCodeTerms& t = extentCodeTerms(code);
    return t[0][e[0]] + t[1][e[1]] + t[2][e[2]];
}

Extents decodeExtents(ExtentCode code, uint16_t coded) {
    const ExtentTable& t = extentDecodeTable(code);
    if (code == ExtentCode::Log16)
        return {uint8_t(t[coded & 31][0]), uint8_t(t[(coded >> 5) & 31][1]), uint8_t(t[(coded >> 10) & 31][2])};
    const ExtentTableEntry& box = t[coded & 255];
    return {uint8_t(box[0]), uint8_t(box[1]), uint8_t(box[2])};
}

Extents quantiseExtents(ExtentCode code, const Extents& e) {
    return code == ExtentCode::Exact ? e : decodeExtents(code, encodeExtents(code, e));
}

const ExtentTable& extentDecodeTable(ExtentCode code) {
    static const ExtentTable tables[3] = {makeTable(ExtentCode::Exact), makeTable(ExtentCode::Log16),
                                          makeTable(ExtentCode::Joint8)};
    return tables[int(code)];
}

void quantiseEACD(DistanceFields& fields, ExtentCode code) {
    for (ExtentField& octant : fields.eacd) {
        if (octant.empty() || octant.code() == code) continue;
        std::vector<Extents> boxes(octant.size());
        forEachVoxel(boxes.size(), [&](std::size_t i) { boxes[i] = octant[i]; });
        octant = ExtentField(code, boxes);
    }
}

}  // namespace vr

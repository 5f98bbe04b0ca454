// EACD extent codes (core/extent_code.h): every code rounds down and never up, keeps what it claims to keep exactly,
// is monotone, keeps the largest box it can, reaches the 255 cap (log16), and its table is what decoding uses.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/distance_fields.h"
#include "core/errors.h"
#include "core/extent_code.h"

namespace vr {
namespace {

constexpr ExtentCode kCoded[] = {ExtentCode::Log16, ExtentCode::Joint8};

// Every triple of extents 1..255 (16.6 million), calling f(extents).
template <typename F>
void forEveryTriple(F f) {
    for (int z = 1; z <= 255; ++z)
        for (int y = 1; y <= 255; ++y)
            for (int x = 1; x <= 255; ++x) f(Extents{uint8_t(x), uint8_t(y), uint8_t(z)});
}

// The values one axis of a code can hold, from the decode table.
std::vector<int> axisValues(ExtentCode code) {
    std::vector<int> values;
    for (int e = 1; e <= 255; ++e) {
        const Extents q = quantiseExtents(code, {uint8_t(e), 1, 1});
        if (q[0] == e) values.push_back(e);
    }
    return values;
}

TEST(CoreExtentCode, NeverRoundsUpAndIsMonotoneOverEveryTriple) {
    for (ExtentCode code : kCoded) {
        SCOPED_TRACE(extentCodeName(code));
        std::size_t up = 0, zero = 0, notMonotone = 0, notIdempotent = 0;
        forEveryTriple([&](const Extents& e) {
            const Extents q = quantiseExtents(code, e);
            for (int a = 0; a < 3; ++a) {
                up += q[a] > e[a];
                zero += q[a] == 0;
                if (e[a] < 255) {
                    Extents bigger = e;
                    ++bigger[a];
                    const Extents qb = quantiseExtents(code, bigger);
                    for (int b = 0; b < 3; ++b) notMonotone += qb[b] < q[b];
                }
            }
            notIdempotent += quantiseExtents(code, q) != q;
        });
        EXPECT_EQ(up, 0u);
        EXPECT_EQ(zero, 0u);
        EXPECT_EQ(notMonotone, 0u);
        EXPECT_EQ(notIdempotent, 0u);
    }
}

TEST(CoreExtentCode, Log16IsExactTo16ReachesTheCapAndLosesAtMost16PercentBeyond) {
    const std::vector<int> values = axisValues(ExtentCode::Log16);
    EXPECT_EQ(values.size(), 32u);  // 5 bits per axis, all used
    for (int e = 1; e <= 16; ++e) EXPECT_EQ(quantiseExtents(ExtentCode::Log16, {uint8_t(e), 3, 200})[0], e);
    EXPECT_EQ(quantiseExtents(ExtentCode::Log16, {255, 255, 255}), (Extents{255, 255, 255}));
    EXPECT_GE(values.back(), 255);
    for (int e = 17; e <= 255; ++e) {
        const int q = quantiseExtents(ExtentCode::Log16, {1, uint8_t(e), 1})[1];
        EXPECT_LT(double(e - q) / e, 0.16) << "extent " << e << " -> " << q;
    }
    EXPECT_EQ(extentCodeBytes(ExtentCode::Log16), 2u);
}

TEST(CoreExtentCode, Joint8KeepsItsLevelsAndTheLargestBoxOfItsTable) {
    const std::vector<int> levels = axisValues(ExtentCode::Joint8);
    EXPECT_EQ(levels.size(), 6u);
    EXPECT_EQ(levels.front(), 1);
    for (int l : levels) EXPECT_EQ(quantiseExtents(ExtentCode::Joint8, {uint8_t(l), uint8_t(l), uint8_t(l)})[2], l);
    EXPECT_EQ(extentCodeBytes(ExtentCode::Joint8), 1u);

    // The boxes of the table (the indices encoding produces), distinct.
    std::vector<Extents> boxes;
    for (int i = 0; i < kExtentTableEntries; ++i) {
        const Extents e = decodeExtents(ExtentCode::Joint8, uint16_t(i));
        if (encodeExtents(ExtentCode::Joint8, e) == uint32_t(i)) boxes.push_back(e);
    }
    EXPECT_EQ(boxes.size(), 216u);
    // Against a search of the whole table: the chosen box fits and no fitting box is larger.
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> extent(1, 255);
    for (int trial = 0; trial < 20000; ++trial) {
        const Extents e{uint8_t(extent(rng)), uint8_t(extent(rng) % (trial % 3 ? 40 : 255) + 1), uint8_t(extent(rng))};
        const Extents q = quantiseExtents(ExtentCode::Joint8, e);
        const int volume = q[0] * q[1] * q[2];
        for (const Extents& b : boxes) {
            if (b[0] <= e[0] && b[1] <= e[1] && b[2] <= e[2]) {
                ASSERT_LE(b[0] * b[1] * b[2], volume);
            }
        }
    }
}

TEST(CoreExtentCode, EveryCodeDecodesThroughTheTableAndEncodesBack) {
    const ExtentTable& log16 = extentDecodeTable(ExtentCode::Log16);
    for (uint32_t c = 0; c < (1u << 15); ++c) {
        const Extents e = decodeExtents(ExtentCode::Log16, uint16_t(c));
        ASSERT_EQ(e, (Extents{uint8_t(log16[c & 31][0]), uint8_t(log16[(c >> 5) & 31][1]),
                              uint8_t(log16[(c >> 10) & 31][2])}));
        ASSERT_EQ(encodeExtents(ExtentCode::Log16, e), c);
    }
    const ExtentTable& joint8 = extentDecodeTable(ExtentCode::Joint8);
    for (int i = 0; i < kExtentTableEntries; ++i) {
        const Extents e = decodeExtents(ExtentCode::Joint8, uint16_t(i));
        EXPECT_EQ(e, (Extents{uint8_t(joint8[i][0]), uint8_t(joint8[i][1]), uint8_t(joint8[i][2])}));
        for (int a = 0; a < 3; ++a) EXPECT_GE(e[a], 1);  // unused entries are the 1-voxel box
    }
}

TEST(CoreExtentCode, FieldsHoldEachBoxRoundedDownInTheCodesBytes) {
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> extent(1, 255);
    std::vector<Extents> boxes;
    for (int i = 0; i < 17 * 9 * 5; ++i) boxes.push_back({uint8_t(extent(rng)), uint8_t(extent(rng) / 16 + 1), 2});
    DistanceFields exact;
    exact.dims = {17, 9, 5};
    exact.eacd.fill(ExtentField(ExtentCode::Exact, boxes));

    for (ExtentCode code : {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8}) {
        SCOPED_TRACE(extentCodeName(code));
        const ExtentField field(code, boxes);
        const std::size_t bytes = extentCodeBytes(code);
        EXPECT_EQ(field.code(), code);
        ASSERT_EQ(field.size(), boxes.size());
        EXPECT_EQ(field.bytes(), boxes.size() * bytes);
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            ASSERT_EQ(field[i], quantiseExtents(code, boxes[i]));
            uint32_t stored = 0;  // little-endian, as the file and the device read it
            std::memcpy(&stored, field.data() + i * bytes, bytes);
            ASSERT_EQ(stored, encodeExtents(code, boxes[i]));
        }
        DistanceFields q = exact;
        quantiseEACD(q, code);
        EXPECT_EQ(q.eacdCode(), code);
        for (int o = 0; o < kOctants; ++o) EXPECT_EQ(q.eacd[o], field);
    }
    EXPECT_EQ(extentCodeBytes(ExtentCode::Exact), 3u);
}

TEST(CoreExtentCode, NamesParseAndAnUnknownNameIsAnInputError) {
    for (ExtentCode code : {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8})
        EXPECT_EQ(parseExtentCode(extentCodeName(code), "--eacd-code"), code);
    try {
        parseExtentCode("log8", "--eacd-code");
        ADD_FAILURE() << "log8 parsed";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "--eacd-code: unknown EACD code 'log8' (expected exact, log16 or joint8)");
    }
}

}  // namespace
}  // namespace vr

// Where a transfer table stops changing what MIP and MinIP show (render/flat_table_ends.h): every scalar beyond each
// end classifies as the table's end entry, in double as the CPU reference looks it up and in float as the casters do;
// entries of extinction 0 show alike whatever their colour, unless the values show opaque.
#include <gtest/gtest.h>

#include "render/flat_table_ends.h"
#include "shaders/transfer_lookup.h"

namespace vr {
namespace {

TransferTable table(std::vector<float> sigma, double lo, double step) {
    TransferTable t;
    t.lo = lo;
    t.step = step;
    t.sigma = sigma;
    for (float s : sigma) t.colour.push_back({s / 8, 0.5f, 1 - s / 8});
    return t;
}

// The caster's float lookup (caster.comp classify): the table coordinate in float, then the two entries around it.
float floatSigma(const TransferTable& t, float f) {
    const float c = device::tableCoordinate(f, float(t.lo), float(1 / t.step), float(t.size() - 1));
    const std::size_t i = std::size_t(c), j = std::min(i + 1, t.size() - 1);
    return device::interpolate(t.sigma[i], t.sigma[j], c - float(i));
}

void expectFlatBeyondEnds(const TransferTable& t) {
    const FlatTableEnds ends = flatTableEnds(t, false);
    const double span = t.step * double(t.size());
    for (int i = 0; i <= 400; ++i) {
        const double above = ends.above + span * i / 100, below = ends.below - span * i / 100;
        EXPECT_EQ(device::lookUpTable(t, above).sigma, t.sigma.back()) << above;
        EXPECT_EQ(device::lookUpTable(t, above).colour[0], t.colour.back()[0]) << above;
        EXPECT_EQ(device::lookUpTable(t, below).sigma, t.sigma.front()) << below;
        EXPECT_EQ(floatSigma(t, float(above)), t.sigma.back()) << above;
        EXPECT_EQ(floatSigma(t, float(below)), t.sigma.front()) << below;
    }
}

TEST(RenderFlatTableEnds, AStepInsideTheRunsThatEndTheTable) {
    const TransferTable t = table({1, 1, 1, 2, 3, 5, 5, 5, 5}, -1024, 3);
    const FlatTableEnds ends = flatTableEnds(t, false);
    EXPECT_EQ(ends.above, -1024 + 6 * 3.0);  // the run 5, 5, 5, 5 starts at entry 5
    EXPECT_EQ(ends.below, -1024 + 1 * 3.0);  // the run 1, 1, 1 ends at entry 2
    expectFlatBeyondEnds(t);
}

TEST(RenderFlatTableEnds, ATableThatChangesAtBothEndsIsFlatOnlyBeyondIt) {
    const TransferTable t = table({0, 1, 2, 3}, 0.25, 0.1);
    const FlatTableEnds ends = flatTableEnds(t, false);
    EXPECT_DOUBLE_EQ(ends.above, 0.25 + 4 * 0.1);
    EXPECT_DOUBLE_EQ(ends.below, 0.25 - 0.1);
    expectFlatBeyondEnds(t);
    // Entries that differ in colour alone are not alike.
    TransferTable coloured = table({2, 2, 2}, 0, 1);
    coloured.colour[2][1] = 0.75f;
    EXPECT_EQ(flatTableEnds(coloured, false).above, 3.0);
    EXPECT_EQ(flatTableEnds(coloured, false).below, 0.0);
}

TEST(RenderFlatTableEnds, TransparentEntriesShowAlikeUnlessTheValuesShowOpaque) {
    // A CT preset: transparent air whose colour still ramps, then tissue, then bone.
    TransferTable t = table({0, 0, 0, 0, 1, 2, 2}, -1000, 100);
    for (std::size_t i = 0; i < 4; ++i) t.colour[i] = {0.1f * float(i), 0.1f * float(i), 0.1f * float(i)};
    const FlatTableEnds shown = flatTableEnds(t, false);
    EXPECT_EQ(shown.below, -1000 + 2 * 100.0);  // the run of extinction 0 ends at entry 3
    EXPECT_EQ(shown.above, -1000 + 6 * 100.0);
    for (int i = 0; i <= 100; ++i) EXPECT_EQ(floatSigma(t, float(shown.below - 30.0 * i)), 0.0f);
    // Opaque, the values show their colour: the ramp is not alike.
    const FlatTableEnds opaque = flatTableEnds(t, true);
    EXPECT_EQ(opaque.below, -1000 - 100.0);
    EXPECT_EQ(opaque.above, -1000 + 6 * 100.0);
    // Opaque, entries alike in colour show alike whatever their extinction.
    TransferTable window = table({0, 1, 2, 3}, 0, 1);
    for (auto& c : window.colour) c = {0, 0, 0};
    EXPECT_EQ(flatTableEnds(window, true).above, 1.0);
    EXPECT_EQ(flatTableEnds(window, false).above, 4.0);
}

TEST(RenderFlatTableEnds, AConstantTableIsFlatEverywhereButItsEdges) {
    const TransferTable t = table({4, 4, 4, 4, 4}, 10, 2);
    EXPECT_EQ(flatTableEnds(t, false).above, 12.0);
    EXPECT_EQ(flatTableEnds(t, false).below, 16.0);
    expectFlatBeyondEnds(t);
}

}  // namespace
}  // namespace vr

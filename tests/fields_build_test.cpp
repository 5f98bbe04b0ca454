// Distance fields (docs/ALGORITHMS.md section 4): the fast builders equal brute force written straight from the
// definitions, exhaustively on small random volumes in all 8 octants; invariants (inside, homogeneous, maximal)
// exhaustively there and on sampled real datasets; values above the cap are capped and still valid.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "preprocess/fields/axial_runs.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/load/load_volume.h"
#include "support/load_dataset.h"

namespace vr {
namespace {

using Box = std::array<int, 3>;

// ---- Test volumes -------------------------------------------------------------------------------------------

Regions regionsOf(Vec3i dims, std::vector<uint32_t> label) {
    Regions r;
    r.dims = dims;
    r.label = std::move(label);
    r.count = r.label.empty() ? 0 : *std::max_element(r.label.begin(), r.label.end()) + 1;
    return r;
}

Regions constantRegions(Vec3i dims) { return regionsOf(dims, std::vector<uint32_t>(voxelCount(dims), 0)); }

// Independent labels in [0, labels): small regions when labels is large, a few big ones when it is 2.
Regions noiseRegions(Vec3i dims, uint32_t labels, std::mt19937& rng) {
    std::vector<uint32_t> l(voxelCount(dims));
    for (auto& x : l) x = std::uniform_int_distribution<uint32_t>(0, labels - 1)(rng);
    return regionsOf(dims, std::move(l));
}

// Random boxes painted over a constant background with a few labels: large blocky regions of any shape.
Regions blockyRegions(Vec3i dims, int boxes, uint32_t labels, std::mt19937& rng) {
    std::vector<uint32_t> l(voxelCount(dims), 0);
    for (int b = 0; b < boxes; ++b) {
        Vec3i lo, hi;
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::uniform_int_distribution<int>(0, dims[a] - 1)(rng);
            hi[a] = std::uniform_int_distribution<int>(lo[a], std::min(dims[a] - 1, lo[a] + dims[a] / 2 + 1))(rng);
        }
        const uint32_t label = std::uniform_int_distribution<uint32_t>(0, labels - 1)(rng);
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) l[linearIndex(dims, x, y, z)] = label;
    }
    return regionsOf(dims, std::move(l));
}

// A named family of random volumes over many shapes, including degenerate 1-voxel-thick ones and ones longer
// than the builder's slabs of 32 slices across x.
std::vector<std::pair<std::string, Regions>> smallVolumes() {
    const Vec3i shapes[] = {{1, 1, 1}, {1, 1, 7}, {5, 1, 1}, {1, 6, 1}, {2, 2, 2}, {3, 1, 4}, {7, 5, 3},
                            {4, 11, 6}, {9, 9, 9}, {12, 3, 10}, {6, 13, 2}, {70, 5, 4}, {37, 8, 3}};
    std::mt19937 rng(12345);
    std::vector<std::pair<std::string, Regions>> out;
    for (const Vec3i& d : shapes) {
        const std::string name = std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
        out.emplace_back(name + " constant", constantRegions(d));
        out.emplace_back(name + " 2 labels", noiseRegions(d, 2, rng));
        out.emplace_back(name + " 1000 labels", noiseRegions(d, 1000, rng));
        for (int seed = 0; seed < 3; ++seed) {
            out.emplace_back(name + " blocky few", blockyRegions(d, 3, 3, rng));
            out.emplace_back(name + " blocky many", blockyRegions(d, 12, 6, rng));
        }
    }
    return out;
}

// ---- Brute force, straight from the definitions -------------------------------------------------------------

Vec3i coordOf(const Vec3i& n, std::size_t v) {
    return {int(v % n.x), int(v / n.x % n.y), int(v / (std::size_t(n.x) * n.y))};
}

// The box {v + s*e : 0 <= e_a < ext_a} is inside the volume and all in v's region.
bool boxHomogeneous(const Regions& r, Vec3i v, int octant, const Box& ext) {
    const uint32_t l = r.label[linearIndex(r.dims, v.x, v.y, v.z)];
    for (int ez = 0; ez < ext[2]; ++ez)
        for (int ey = 0; ey < ext[1]; ++ey)
            for (int ex = 0; ex < ext[0]; ++ex) {
                const Vec3i u{v.x + octantSign(octant, 0) * ex, v.y + octantSign(octant, 1) * ey,
                              v.z + octantSign(octant, 2) * ez};
                if (!inside(r.dims, u.x, u.y, u.z) || r.label[linearIndex(r.dims, u.x, u.y, u.z)] != l) return false;
            }
    return true;
}

// Every u with max_a |u_a - v_a| <= radius is inside the volume and in v's region.
bool centredCubeHomogeneous(const Regions& r, Vec3i v, int radius) {
    const uint32_t l = r.label[linearIndex(r.dims, v.x, v.y, v.z)];
    for (int z = v.z - radius; z <= v.z + radius; ++z)
        for (int y = v.y - radius; y <= v.y + radius; ++y)
            for (int x = v.x - radius; x <= v.x + radius; ++x)
                if (!inside(r.dims, x, y, z) || r.label[linearIndex(r.dims, x, y, z)] != l) return false;
    return true;
}

int bruteACD(const Regions& r, Vec3i v, int octant) {
    int k = 1;
    while (k < kDistanceCap && boxHomogeneous(r, v, octant, {k + 1, k + 1, k + 1})) ++k;
    return k;
}

int brutePC(const Regions& r, Vec3i v) {
    int radius = 0;
    while (radius < kDistanceCap - 1 && centredCubeHomogeneous(r, v, radius + 1)) ++radius;
    return radius;
}

// Same-region voxels walking from u by `sign` along `axis`, u included, capped.
int bruteRun(const Regions& r, Vec3i u, int axis, int sign) {
    const uint32_t l = r.label[linearIndex(r.dims, u.x, u.y, u.z)];
    int run = 0;
    for (Vec3i p = u; inside(r.dims, p.x, p.y, p.z) && r.label[linearIndex(r.dims, p.x, p.y, p.z)] == l;
         p[axis] += sign)
        ++run;
    return std::min(run, kDistanceCap);
}

// The extension along `axis` of the box: the minimum run over its near face, walked voxel by voxel.
int bruteExtension(const Regions& r, Vec3i v, int octant, const Box& ext, int axis) {
    int smallest = kDistanceCap;
    Box face = ext;
    face[axis] = 1;
    for (int ez = 0; ez < face[2]; ++ez)
        for (int ey = 0; ey < face[1]; ++ey)
            for (int ex = 0; ex < face[0]; ++ex) {
                const Vec3i u{v.x + octantSign(octant, 0) * ex, v.y + octantSign(octant, 1) * ey,
                              v.z + octantSign(octant, 2) * ez};
                smallest = std::min(smallest, bruteRun(r, u, axis, octantSign(octant, axis)));
            }
    return smallest;
}

// The greedy of docs/ALGORITHMS.md: from the ACD cube, extend the axis giving the largest volume, then the better of
// the two others; ties go to x, then y, then z.
Box bruteEACD(const Regions& r, Vec3i v, int octant) {
    const int k = bruteACD(r, v, octant);
    Box box{k, k, k};
    auto extendBest = [&](std::initializer_list<int> axes) {
        int best = -1;
        long bestVolume = -1;
        Box bestBox{};
        for (int a : axes) {
            Box b = box;
            b[a] = bruteExtension(r, v, octant, box, a);
            const long volume = long(b[0]) * b[1] * b[2];
            if (volume > bestVolume) {
                bestVolume = volume;
                bestBox = b;
                best = a;
            }
        }
        box = bestBox;
        return best;
    };
    const int first = extendBest({0, 1, 2});
    if (first == 0) extendBest({1, 2});
    if (first == 1) extendBest({0, 2});
    if (first == 2) extendBest({0, 1});
    return box;
}

// ---- Brute-force equality, exhaustive -----------------------------------------------------------------------

TEST(FieldsBuildBruteForce, ACDAndPCEqualTheDefinitionsEverywhere) {
    for (const auto& [name, r] : smallVolumes()) {
        SCOPED_TRACE(name);
        const std::vector<uint8_t> pc = buildPC(r);
        ASSERT_EQ(pc.size(), r.label.size());
        for (int o = 0; o < kOctants; ++o) {
            const std::vector<uint8_t> acd = buildACD(r, o);
            ASSERT_EQ(acd.size(), r.label.size());
            for (std::size_t v = 0; v < acd.size(); ++v)
                ASSERT_EQ(acd[v], bruteACD(r, coordOf(r.dims, v), o)) << "octant " << o << " voxel " << v;
        }
        for (std::size_t v = 0; v < pc.size(); ++v) ASSERT_EQ(pc[v], brutePC(r, coordOf(r.dims, v))) << "voxel " << v;
    }
}

TEST(FieldsBuildBruteForce, AxialRunsEqualTheWalk) {
    for (const auto& [name, r] : smallVolumes()) {
        SCOPED_TRACE(name);
        for (int axis = 0; axis < 3; ++axis)
            for (int sign : {1, -1}) {
                const std::vector<uint8_t> run = axialRuns(r, axis, sign);
                for (std::size_t v = 0; v < run.size(); ++v)
                    ASSERT_EQ(run[v], bruteRun(r, coordOf(r.dims, v), axis, sign))
                        << "axis " << axis << " sign " << sign << " voxel " << v;
            }
    }
}

TEST(FieldsBuildBruteForce, EACDEqualsTheNaiveGreedyEverywhere) {
    for (const auto& [name, r] : smallVolumes()) {
        SCOPED_TRACE(name);
        std::array<std::vector<uint8_t>, kOctants> acd;
        for (int o = 0; o < kOctants; ++o) acd[o] = buildACD(r, o);
        const std::array<ExtentField, kOctants> all = buildEACD(r, acd);
        for (int o = 0; o < kOctants; ++o) {
            const ExtentField one = buildEACD(r, acd[o], o);  // one octant alone gives the same field
            ASSERT_EQ(one, all[o]) << "octant " << o;
            for (std::size_t v = 0; v < one.size(); ++v) {
                const Box expected = bruteEACD(r, coordOf(r.dims, v), o);
                ASSERT_EQ(Box({one[v][0], one[v][1], one[v][2]}), expected) << "octant " << o << " voxel " << v;
            }
        }
    }
}

TEST(FieldsBuild, BuildFieldsFillsWhatIsAskedAndAgreesWithTheSingleBuilders) {
    std::mt19937 rng(7);
    const Regions r = blockyRegions({10, 8, 9}, 10, 4, rng);
    const DistanceFields pcOnly = buildFields(r, kFieldPC);
    EXPECT_TRUE(pcOnly.hasPC());
    EXPECT_FALSE(pcOnly.hasACD());
    EXPECT_FALSE(pcOnly.hasEACD());
    EXPECT_EQ(pcOnly.pc, buildPC(r));
    const DistanceFields eacdOnly = buildFields(r, kFieldEACD);
    EXPECT_FALSE(eacdOnly.hasPC());
    EXPECT_FALSE(eacdOnly.hasACD());  // ACD was needed but not asked for
    ASSERT_TRUE(eacdOnly.hasEACD());
    const DistanceFields all = buildFields(r, kFieldPC | kFieldACD | kFieldEACD);
    EXPECT_EQ(all.dims, r.dims);
    EXPECT_EQ(all.pc, pcOnly.pc);
    for (int o = 0; o < kOctants; ++o) {
        EXPECT_EQ(all.acd[o], buildACD(r, o));
        EXPECT_EQ(all.eacd[o], eacdOnly.eacd[o]);
        EXPECT_EQ(all.eacd[o], buildEACD(r, all.acd[o], o));
    }
    const DistanceFields none = buildFields(r, 0);
    EXPECT_FALSE(none.hasPC() || none.hasACD() || none.hasEACD());
}

// A render's views need only some octants (volrender's one-command path): those are built as in a full build, the
// others are left empty; PC, a minimum over all eight, is unchanged.
TEST(FieldsBuild, AnOctantMaskBuildsThoseOctantsOnly) {
    std::mt19937 rng(11);
    const Regions r = blockyRegions({12, 9, 10}, 8, 4, rng);
    const DistanceFields all = buildFields(r, kFieldPC | kFieldACD | kFieldEACD, ExtentCode::Log16, [](FieldKind) {});
    for (unsigned mask : {0x01u, 0x81u, 0x5au}) {
        SCOPED_TRACE(mask);
        const DistanceFields some = buildFields(r, kFieldACD | kFieldEACD, ExtentCode::Log16, [](FieldKind) {}, mask);
        EXPECT_EQ(some.acdOctants(), mask);
        EXPECT_EQ(some.eacdOctants(), mask);
        EXPECT_EQ(some.eacdCode(), ExtentCode::Log16);
        for (int o = 0; o < kOctants; ++o) {
            if (mask >> o & 1u) {
                EXPECT_EQ(some.acd[o], all.acd[o]) << o;
                EXPECT_EQ(some.eacd[o], all.eacd[o]) << o;
            } else {
                EXPECT_TRUE(some.acd[o].empty() && some.eacd[o].empty()) << o;
            }
        }
        const DistanceFields withPC = buildFields(r, kFieldPC | kFieldEACD, ExtentCode::Log16, [](FieldKind) {}, mask);
        EXPECT_EQ(withPC.pc, all.pc);
        EXPECT_EQ(withPC.eacdOctants(), mask);
        // Consuming the regions (their labels freed once the runs are made) builds the same fields: every run the
        // octants read was made before the labels went.
        for (unsigned kinds :
             {unsigned(kFieldEACD), kFieldACD | kFieldEACD, kFieldPC | kFieldEACD, unsigned(kFieldPC)}) {
            Regions copy = r;
            const DistanceFields consumed =
                buildFields(std::move(copy), kinds, ExtentCode::Log16, [](FieldKind) {}, mask);
            const DistanceFields kept = buildFields(r, kinds, ExtentCode::Log16, [](FieldKind) {}, mask);
            EXPECT_EQ(consumed.pc, kept.pc) << kinds;
            for (int o = 0; o < kOctants; ++o) {
                EXPECT_EQ(consumed.acd[o], kept.acd[o]) << kinds << " " << o;
                EXPECT_EQ(consumed.eacd[o], kept.eacd[o]) << kinds << " " << o;
            }
        }
    }
}

TEST(FieldsBuildBruteForce, EACDEqualsTheNaiveGreedyOnLargerRegionsSampled) {
    // Regions tens of voxels wide, so that extensions follow their neighbours' across many slices and slabs.
    std::mt19937 rng(99);
    const Regions r = blockyRegions({75, 40, 34}, 8, 3, rng);
    const DistanceFields f = buildFields(r, kFieldACD | kFieldEACD);
    for (std::size_t v = 0; v < r.label.size(); v += 53)
        for (int o = 0; o < kOctants; ++o) {
            const Box e{f.eacd[o][v][0], f.eacd[o][v][1], f.eacd[o][v][2]};
            ASSERT_EQ(e, bruteEACD(r, coordOf(r.dims, v), o)) << "octant " << o << " voxel " << v;
        }
}

TEST(FieldsBuild, BuildFieldsReportsEachFieldOnceInOrder) {
    std::mt19937 rng(8);
    const Regions r = blockyRegions({9, 7, 6}, 6, 3, rng);
    auto order = [&](unsigned kinds) {
        std::vector<FieldKind> done;
        const DistanceFields f = buildFields(r, kinds, [&](FieldKind k) { done.push_back(k); });
        EXPECT_EQ(f.pc, buildFields(r, kinds).pc);
        return done;
    };
    using V = std::vector<FieldKind>;
    EXPECT_EQ(order(kFieldPC | kFieldACD | kFieldEACD), V({kFieldACD, kFieldPC, kFieldEACD}));
    EXPECT_EQ(order(kFieldEACD), V({kFieldACD, kFieldEACD}));  // ACD built for EACD, reported, not kept
    EXPECT_EQ(order(kFieldPC), V({kFieldPC}));
    EXPECT_EQ(order(0), V());
}

// What the field builders tell a progress bar: fractions in [0, 1] that never fall, after the ACDs, PC and each
// EACD octant, ending at 1.
TEST(FieldsBuild, ReportsTheirProgress) {
    std::mt19937 rng(3);
    const Regions r = blockyRegions({40, 30, 20}, 6, 3, rng);
    for (unsigned kinds : {unsigned(kFieldPC | kFieldEACD), unsigned(kFieldACD), unsigned(kFieldPC)}) {
        SCOPED_TRACE(kinds);
        std::vector<double> heard;
        buildFields(r, kinds, ExtentCode::Log16, [](FieldKind) {}, kAllOctants,
                    [&](double f) { heard.push_back(f); });
        ASSERT_FALSE(heard.empty());
        EXPECT_TRUE(std::is_sorted(heard.begin(), heard.end()));
        EXPECT_GE(heard.front(), 0.0);
        EXPECT_EQ(heard.back(), 1.0);
        if (kinds & kFieldEACD) EXPECT_GE(heard.size(), 2u + kOctants);  // ACD, PC, the octants
    }
}

TEST(FieldsBuild, CodedEACDIsTheExactOneQuantised) {
    // Large regions, so that extents reach past the codes' exact values (Log16 above 16, Joint8 above 2).
    std::mt19937 rng(17);
    const Regions r = blockyRegions({70, 45, 38}, 6, 3, rng);
    const DistanceFields exact = buildFields(r, kFieldPC | kFieldEACD);
    for (ExtentCode code : {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8}) {
        SCOPED_TRACE(std::string(extentCodeName(code)));
        DistanceFields rounded = exact;
        quantiseEACD(rounded, code);
        const DistanceFields coded = buildFields(r, kFieldPC | kFieldEACD, code, [](FieldKind) {});
        EXPECT_EQ(coded.eacdCode(), code);
        EXPECT_EQ(coded.pc, exact.pc);
        for (int o = 0; o < kOctants; ++o) ASSERT_EQ(coded.eacd[o], rounded.eacd[o]) << "octant " << o;
    }
}

TEST(FieldsBuild, SharedRunsGiveTheSameFieldsAsTheStandAloneBuilders) {
    for (const auto& [name, r] : smallVolumes()) {
        SCOPED_TRACE(name);
        AxialRuns runs(r);
        for (int axis = 0; axis < 3; ++axis)
            for (int sign : {1, -1}) ASSERT_EQ(runs.get(axis, sign), axialRuns(r, axis, sign));
        const ACDFields acd = buildACDs(runs);
        for (int o = 0; o < kOctants; ++o) ASSERT_EQ(acd[o], buildACD(r, o)) << "octant " << o;
        EXPECT_EQ(buildACDs(r), acd);
        EXPECT_EQ(pcFromACD(acd), buildPC(r));
        EXPECT_EQ(buildEACD(runs, acd), buildEACD(r, acd));
    }
}

TEST(FieldsBuild, EmptyVolumeGivesEmptyFieldsAndBadArgumentsThrow) {
    const DistanceFields f = buildFields(constantRegions({0, 0, 0}), kFieldPC | kFieldACD | kFieldEACD);
    EXPECT_TRUE(f.pc.empty());
    Regions bad = constantRegions({3, 3, 3});
    bad.label.pop_back();
    EXPECT_THROW(buildACD(bad, 0), std::invalid_argument);
    EXPECT_THROW(buildPC(bad), std::invalid_argument);
    const std::vector<uint8_t> shortACD(5, 1);
    EXPECT_THROW(buildEACD(constantRegions({3, 3, 3}), shortACD, 0), std::invalid_argument);
    EXPECT_THROW(buildACD(constantRegions({3, 3, 3}), 8), std::invalid_argument);
    EXPECT_THROW(buildEACD(constantRegions({3, 3, 3}), std::vector<uint8_t>(27, 1), -1), std::invalid_argument);
    EXPECT_THROW(AxialRuns{bad}, std::invalid_argument);
    ACDFields uneven;
    uneven[3].resize(2);
    EXPECT_THROW(pcFromACD(uneven), std::invalid_argument);
}

// ---- Invariants, with an independent O(1) homogeneity test --------------------------------------------------

// Summed-area tables of the region borders along each axis: a box is homogeneous when no two neighbours inside
// it differ, i.e. when the count of differing neighbour pairs inside it is 0 on every axis.
class BorderCounts {
public:
    explicit BorderCounts(const Regions& r) : n_(r.dims) {
        const std::size_t m = std::size_t(n_.x + 1) * (n_.y + 1) * (n_.z + 1);
        for (int a = 0; a < 3; ++a) {
            sat_[a].assign(m, 0);
            const std::ptrdiff_t step = a == 0 ? 1 : a == 1 ? n_.x : std::ptrdiff_t(n_.x) * n_.y;
            for (int z = 0; z < n_.z; ++z)
                for (int y = 0; y < n_.y; ++y)
                    for (int x = 0; x < n_.x; ++x) {
                        Vec3i p{x, y, z};
                        const std::size_t v = linearIndex(n_, x, y, z);
                        const uint32_t differs = p[a] + 1 < n_[a] && r.label[v] != r.label[v + step];
                        sat_[a][at(x + 1, y + 1, z + 1)] = differs + sat_[a][at(x, y + 1, z + 1)] +
                                                           sat_[a][at(x + 1, y, z + 1)] + sat_[a][at(x + 1, y + 1, z)] -
                                                           sat_[a][at(x, y, z + 1)] - sat_[a][at(x, y + 1, z)] -
                                                           sat_[a][at(x + 1, y, z)] + sat_[a][at(x, y, z)];
                    }
        }
    }
    // The box {v + s*e : 0 <= e_a < ext_a} is inside the volume and homogeneous.
    bool homogeneous(Vec3i v, int octant, const Box& ext) const {
        Vec3i lo, hi;  // inclusive
        for (int a = 0; a < 3; ++a) {
            const int far = v[a] + octantSign(octant, a) * (ext[a] - 1);
            lo[a] = std::min(v[a], far);
            hi[a] = std::max(v[a], far);
            if (lo[a] < 0 || hi[a] >= n_[a]) return false;
        }
        for (int a = 0; a < 3; ++a) {
            Vec3i h = hi;
            h[a] -= 1;  // pairs (u, u + e_a) with both ends in the box
            if (h[a] >= lo[a] && sum(a, lo, h) != 0) return false;
        }
        return true;
    }
    bool centredCube(Vec3i v, int radius) const {
        const Vec3i corner{v.x - radius, v.y - radius, v.z - radius};
        return homogeneous(corner, 0, {2 * radius + 1, 2 * radius + 1, 2 * radius + 1});
    }

private:
    std::size_t at(int x, int y, int z) const {
        return (std::size_t(z) * (n_.y + 1) + y) * std::size_t(n_.x + 1) + x;
    }
    int64_t sum(int a, Vec3i lo, Vec3i hi) const {
        const auto& s = sat_[a];
        const int x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x + 1, y1 = hi.y + 1, z1 = hi.z + 1;
        return int64_t(s[at(x1, y1, z1)]) - s[at(x0, y1, z1)] - s[at(x1, y0, z1)] - s[at(x1, y1, z0)] +
               s[at(x0, y0, z1)] + s[at(x0, y1, z0)] + s[at(x1, y0, z0)] - s[at(x0, y0, z0)];
    }
    Vec3i n_;
    std::array<std::vector<uint32_t>, 3> sat_;
};

// Checks every field at voxel v: inside and homogeneous, PC and ACD maximal unless capped, EACD >= ACD.
void expectFieldInvariants(const Regions& r, const BorderCounts& borders, const DistanceFields& f, std::size_t v) {
    const Vec3i p = coordOf(r.dims, v);
    const int pc = f.pc[v];
    ASSERT_TRUE(borders.centredCube(p, pc)) << "pc " << pc << " at voxel " << v;
    if (pc < kDistanceCap - 1) {
        ASSERT_FALSE(borders.centredCube(p, pc + 1)) << "pc not maximal at voxel " << v;
    }
    for (int o = 0; o < kOctants; ++o) {
        const int k = f.acd[o][v];
        ASSERT_GE(k, 1);
        ASSERT_TRUE(borders.homogeneous(p, o, {k, k, k})) << "acd " << k << " octant " << o << " voxel " << v;
        if (k < kDistanceCap) {
            ASSERT_FALSE(borders.homogeneous(p, o, {k + 1, k + 1, k + 1})) << "acd not maximal, voxel " << v;
        }
        const Box e{f.eacd[o][v][0], f.eacd[o][v][1], f.eacd[o][v][2]};
        for (int a = 0; a < 3; ++a) ASSERT_GE(e[a], k) << "eacd below acd, octant " << o << " voxel " << v;
        ASSERT_TRUE(borders.homogeneous(p, o, e)) << "eacd box octant " << o << " voxel " << v;
    }
}

TEST(FieldsBuildInvariants, SmallRandomVolumesExhaustively) {
    for (const auto& [name, r] : smallVolumes()) {
        SCOPED_TRACE(name);
        const BorderCounts borders(r);
        const DistanceFields f = buildFields(r, kFieldPC | kFieldACD | kFieldEACD);
        for (std::size_t v = 0; v < r.label.size(); ++v) {
            expectFieldInvariants(r, borders, f, v);
            if (HasFatalFailure()) return;
        }
    }
}

TEST(FieldsBuildInvariants, TheIndependentBoxTestAgreesWithTheWalk) {
    std::mt19937 rng(99);
    const Regions r = blockyRegions({7, 6, 5}, 6, 3, rng);
    const BorderCounts borders(r);
    for (std::size_t v = 0; v < r.label.size(); ++v)
        for (int o = 0; o < kOctants; ++o)
            for (int ex = 1; ex <= 3; ++ex)
                for (int ey = 1; ey <= 4; ++ey)
                    for (int ez = 1; ez <= 2; ++ez) {
                        const Vec3i p = coordOf(r.dims, v);
                        ASSERT_EQ(borders.homogeneous(p, o, {ex, ey, ez}), boxHomogeneous(r, p, o, {ex, ey, ez}));
                    }
}

// Real data: labels are the raw value (any labelling is a partition), checked at 20000 random voxels.
void checkDataset(const std::string& file, uint32_t (*labelOf)(float)) {
    SCOPED_TRACE(file);
    const Volume vol = test::loadDataset(file);
    std::vector<uint32_t> labels(vol.values.size());
    std::transform(vol.values.begin(), vol.values.end(), labels.begin(), labelOf);
    const Regions r = regionsOf(vol.grid.dims, std::move(labels));
    const DistanceFields f = buildFields(r, kFieldPC | kFieldACD | kFieldEACD);
    const BorderCounts borders(r);
    std::mt19937 rng(2024);
    std::uniform_int_distribution<std::size_t> pick(0, r.label.size() - 1);
    uint64_t eacdVolume = 0, acdVolume = 0;
    for (int i = 0; i < 20000; ++i) {
        const std::size_t v = pick(rng);
        expectFieldInvariants(r, borders, f, v);
        if (testing::Test::HasFatalFailure()) return;
        acdVolume += uint64_t(f.acd[0][v]) * f.acd[0][v] * f.acd[0][v];
        eacdVolume += uint64_t(f.eacd[0][v][0]) * f.eacd[0][v][1] * f.eacd[0][v][2];
    }
    EXPECT_GT(eacdVolume, acdVolume);  // real data has long thin regions that the extension finds
}

TEST(FieldsBuildInvariants, HeadCTSampled) {
    checkDataset("vtk_headsq_ct_64x64x93_uint16.raw.gz", [](float x) { return uint32_t(x) / 64; });
}

TEST(FieldsBuildInvariants, TeapotSampled) {
    checkDataset("boston_teapot_256x256x178_uint8.raw.gz", [](float x) { return uint32_t(x); });
}

// ---- Caps ---------------------------------------------------------------------------------------------------

TEST(FieldsBuildCaps, RunsLongerThanTheCapAreCappedAndStillValid) {
    const Regions r = constantRegions({300, 2, 2});
    const std::vector<uint8_t> run = axialRuns(r, 0, 1);
    EXPECT_EQ(run[linearIndex(r.dims, 0, 0, 0)], kDistanceCap);      // true run 300
    EXPECT_EQ(run[linearIndex(r.dims, 100, 1, 1)], 200);             // true run 200
    EXPECT_EQ(run[linearIndex(r.dims, 299, 0, 1)], 1);
    const DistanceFields f = buildFields(r, kFieldPC | kFieldACD | kFieldEACD);
    const BorderCounts borders(r);
    for (std::size_t v = 0; v < r.label.size(); ++v) expectFieldInvariants(r, borders, f, v);
    using E = std::array<uint8_t, 3>;
    EXPECT_EQ(f.eacd[0][linearIndex(r.dims, 0, 0, 0)], E({255, 2, 2}));
    EXPECT_EQ(f.eacd[0][linearIndex(r.dims, 100, 0, 0)], E({200, 2, 2}));
    EXPECT_EQ(f.eacd[1][linearIndex(r.dims, 299, 0, 0)], E({255, 2, 2}));  // toward -x
    EXPECT_EQ(f.eacd[7][linearIndex(r.dims, 50, 1, 1)], E({51, 2, 2}));
}

TEST(FieldsBuildCaps, CubesLargerThanTheCapAreCapped) {
    const Regions r = constantRegions({260, 258, 257});
    const std::vector<uint8_t> acd = buildACD(r, 0);
    EXPECT_EQ(acd[linearIndex(r.dims, 0, 0, 0)], kDistanceCap);  // true edge 257
    EXPECT_EQ(acd[linearIndex(r.dims, 1, 1, 1)], kDistanceCap);  // true edge 256
    EXPECT_EQ(acd[linearIndex(r.dims, 2, 2, 2)], 255);           // true edge 255
    EXPECT_EQ(acd[linearIndex(r.dims, 3, 2, 2)], 255);
    EXPECT_EQ(acd[linearIndex(r.dims, 3, 3, 3)], 254);
    EXPECT_EQ(acd[linearIndex(r.dims, 200, 10, 100)], 60);
    const std::vector<uint8_t> pc = buildPC(constantRegions({64, 64, 64}));
    EXPECT_EQ(pc[linearIndex({64, 64, 64}, 31, 32, 33)], 30);
    EXPECT_EQ(pc[linearIndex({64, 64, 64}, 0, 32, 33)], 0);
}

}  // namespace
}  // namespace vr

// Headerless raw volumes: every real .raw.gz of the manifest, and small synthetic files of every type and order.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <vector>

#include "preprocess/load/load_volume.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

// min/max from the notes column of MANIFEST.tsv ("values min=-1024 max=2986").
std::map<std::string, std::pair<float, float>> manifestValueRanges() {
    std::ifstream in(test::datasetsDir() / "MANIFEST.tsv");
    std::map<std::string, std::pair<float, float>> ranges;
    static const std::regex range(R"(values min=(-?\d+) max=(-?\d+))");
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_search(line, m, range))
            ranges[line.substr(0, line.find('\t'))] = {std::stof(m[1].str()), std::stof(m[2].str())};
    }
    return ranges;
}

TEST(LoadRaw, EveryManifestRawLoadsWithItsDimsTypeRangeAndSpacing) {
    const auto ranges = manifestValueRanges();
    const auto raws = test::rawManifest();
    ASSERT_GE(raws.size(), 10u);
    for (const auto& e : raws) {
        SCOPED_TRACE(e.file);
        RawOptions options;
        options.spacing = e.spacing;
        const fs::path path = test::datasetsDir() / e.file;
        const Volume v = loadVolume(path, options);  // dims and type come from the name
        EXPECT_EQ(v.grid.dims, e.dims);
        EXPECT_EQ(v.sourceType, e.type);
        EXPECT_EQ(v.grid.spacing, e.spacing);
        EXPECT_EQ(v.grid.origin, Vec3d(0, 0, 0));
        EXPECT_EQ(v.source, path.string());
        ASSERT_EQ(v.values.size(), v.grid.voxels());
        const auto [lo, hi] = std::minmax_element(v.values.begin(), v.values.end());
        ASSERT_TRUE(ranges.contains(e.file));
        EXPECT_EQ(*lo, ranges.at(e.file).first);
        EXPECT_EQ(*hi, ranges.at(e.file).second);
    }
}

TEST(LoadRaw, SpacingDefaultsToOne) {
    const Volume v = loadVolume(test::datasetsDir() / "vtk_headmr_48x62x42_uint8.raw.gz");
    EXPECT_EQ(v.grid.spacing, Vec3d(1, 1, 1));
}

// Known voxels of the cranium CT (x fastest): air in the corner, and the extremes somewhere inside.
TEST(LoadRaw, CraniumVoxelsAreInFileOrder) {
    const Volume v = loadVolume(test::datasetsDir() / "cranium_ct_256x256x108_int16.raw.gz");
    gzFile f = gzopen((test::datasetsDir() / "cranium_ct_256x256x108_int16.raw.gz").c_str(), "rb");
    std::vector<std::int16_t> stored(v.grid.voxels());
    ASSERT_EQ(gzread(f, stored.data(), unsigned(stored.size() * 2)), int(stored.size() * 2));
    gzclose(f);
    for (std::size_t i = 0; i < stored.size(); i += 997) ASSERT_EQ(v.values[i], float(stored[i])) << i;
    EXPECT_EQ(v.at(255, 0, 0), float(stored[255]));
    EXPECT_EQ(v.at(0, 1, 0), float(stored[256]));
    EXPECT_EQ(v.at(0, 0, 1), float(stored[256 * 256]));
}

template <typename T>
std::vector<unsigned char> bytesOf(const std::vector<T>& values, bool bigEndian) {
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    if (bigEndian)
        for (std::size_t i = 0; i < bytes.size(); i += sizeof(T)) std::reverse(&bytes[i], &bytes[i] + sizeof(T));
    return bytes;
}

void writeFile(const fs::path& path, const std::vector<unsigned char>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void writeGzip(const fs::path& path, const std::vector<unsigned char>& bytes) {
    gzFile f = gzopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(gzwrite(f, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
    ASSERT_EQ(gzclose(f), Z_OK);
}

// Values spanning each type's whole range, at distinct voxels of a 5x4x3 grid.
template <typename T>
std::vector<T> pattern() {
    std::vector<T> v(60);
    for (std::size_t i = 0; i < v.size(); ++i) {
        if constexpr (std::is_floating_point_v<T>)
            v[i] = T(i) * 1.25f - 30.5f;
        else
            v[i] = T(double(std::numeric_limits<T>::min()) +
                     double(i) / 59.0 *
                         (double(std::numeric_limits<T>::max()) - double(std::numeric_limits<T>::min())));
    }
    return v;
}

template <typename T>
void checkRoundTrip(ScalarType type, bool bigEndian, bool gzip) {
    SCOPED_TRACE(std::string(scalarTypeName(type)) + (bigEndian ? " big" : " little") + (gzip ? " gz" : ""));
    const fs::path dir = test::scratchDir("load_raw_types");
    const auto values = pattern<T>();
    const fs::path path = dir / (std::string("v.") + (gzip ? "raw.gz" : "raw"));
    gzip ? writeGzip(path, bytesOf(values, bigEndian)) : writeFile(path, bytesOf(values, bigEndian));
    RawOptions o;
    o.dims = Vec3i{5, 4, 3};
    o.type = type;
    o.spacing = Vec3d{0.5, 0.25, 3};
    o.bigEndian = bigEndian;
    const Volume v = loadVolume(path, o);
    EXPECT_EQ(v.grid.dims, Vec3i(5, 4, 3));
    EXPECT_EQ(v.grid.spacing, Vec3d(0.5, 0.25, 3));
    EXPECT_EQ(v.sourceType, type);
    ASSERT_EQ(v.values.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(v.values[i], float(values[i])) << i;
}

TEST(LoadRaw, EveryTypeInBothByteOrdersPlainAndGzip) {
    for (bool big : {false, true})
        for (bool gz : {false, true}) {
            checkRoundTrip<std::uint8_t>(ScalarType::UInt8, big, gz);
            checkRoundTrip<std::int16_t>(ScalarType::Int16, big, gz);
            checkRoundTrip<std::uint16_t>(ScalarType::UInt16, big, gz);
            checkRoundTrip<float>(ScalarType::Float32, big, gz);
        }
}

TEST(LoadRaw, NameGivesDimsAndTypeAndFlagsOverrideIt) {
    const fs::path dir = test::scratchDir("load_raw_names");
    const auto values = pattern<std::uint16_t>();
    const fs::path path = dir / "Scan_5x4x3_UINT16.RAW.GZ";  // extensions and type names in any case
    writeGzip(path, bytesOf(values, false));
    const Volume named = loadVolume(path);
    EXPECT_EQ(named.grid.dims, Vec3i(5, 4, 3));
    EXPECT_EQ(named.sourceType, ScalarType::UInt16);
    EXPECT_EQ(named.values[59], 65535.0f);

    RawOptions o;  // the same 120 bytes read as 10x6x1 int16
    o.dims = Vec3i{10, 6, 1};
    o.type = ScalarType::Int16;
    const Volume flagged = loadVolume(path, o);
    EXPECT_EQ(flagged.grid.dims, Vec3i(10, 6, 1));
    EXPECT_EQ(flagged.sourceType, ScalarType::Int16);
    EXPECT_EQ(flagged.values[59], -1.0f);
}

// Stages compare the options a volume was loaded with to decide whether to load it again.
TEST(LoadRaw, OptionsCompareByEveryField) {
    const RawOptions options{Vec3i{4, 4, 2}, ScalarType::UInt16, Vec3d{1, 1, 2}, false, ""};
    EXPECT_TRUE(options == options);
    EXPECT_TRUE(RawOptions{} == RawOptions{});
    RawOptions other = options;
    other.dims = Vec3i{4, 4, 3};
    EXPECT_FALSE(other == options);
    other = options;
    other.type.reset();
    EXPECT_FALSE(other == options);
    other = options;
    other.spacing = Vec3d{1, 1, 1};
    EXPECT_FALSE(other == options);
    other = options;
    other.bigEndian = true;
    EXPECT_FALSE(other == options);
}

}  // namespace
}  // namespace vr

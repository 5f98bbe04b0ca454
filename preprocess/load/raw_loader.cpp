// Headerless raw volumes (.raw, .raw.gz): dims and type from flags or from the file name, x fastest.
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <climits>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/lower_case.h"
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/voxel_budget.h"
#include "preprocess/load/voxel_conversion.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

std::string dimsText(const Vec3i& d) {
    return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

// Names like engine_256x256x128_uint8.raw or cranium_ct_256x256x108_int16.raw.gz carry dims and type.
void fillFromName(const fs::path& path, RawOptions& options) {
    static const std::regex pattern(R"((?:^|[_.-])(\d+)x(\d+)x(\d+)(?:_([a-z0-9]+))?\.raw(?:\.gz)?$)",
                                    std::regex::icase);
    std::smatch m;
    const std::string name = path.filename().string();
    if (!std::regex_search(name, m, pattern)) return;
    if (!options.dims) {
        Vec3i dims;
        for (int a = 0; a < 3; ++a) {
            const std::string digits = m[a + 1].str();
            if (digits.size() > 10 || std::stoll(digits) > INT_MAX)
                throw fileError(path.string(), "dimension " + digits + " in the file name is too large");
            dims[a] = std::stoi(digits);
        }
        options.dims = dims;
    }
    if (!options.type && m[4].matched) {
        try {
            options.type = parseScalarType(lowerCase(m[4].str()));
        } catch (const InputError&) {
            // Not a type name (e.g. a version suffix): the type must then come from the flag.
        }
    }
}

std::string sizeMismatch(std::size_t expected, std::size_t actual, const Vec3i& dims, ScalarType type) {
    return "holds " + std::to_string(actual) + " bytes of voxel data but dims " + dimsText(dims) + " of " +
           std::string(scalarTypeName(type)) + " need " + std::to_string(expected) + " bytes";
}

// A plain file's size against its dims, before anything is allocated for them: a small file must not get the
// memory its name claims.
void checkPlainSize(const fs::path& path, std::size_t expected, const Vec3i& dims, ScalarType type) {
    std::error_code ec;
    const std::uintmax_t actual = fs::file_size(path, ec);
    if (ec) throw fileError(path.string(), "cannot read: " + ec.message());
    if (actual != expected) throw fileError(path.string(), sizeMismatch(expected, actual, dims, type));
}

// A plain file (checkPlainSize) is read in chunks, each widened into `out` as it arrives: no second copy of the
// volume's bytes, and none of the fresh pages it would take (clearing them was a large part of loading a
// clinical-size CT).
void readPlainWidened(const fs::path& path, std::size_t expected, ScalarType type, bool swap, float* out) {
    std::ifstream in(path, std::ios::binary);
    const std::size_t voxelBytes = scalarBytes(type);
    std::vector<unsigned char> chunk((std::size_t(16) << 20) / voxelBytes * voxelBytes);
    for (std::size_t done = 0; done < expected;) {
        const std::size_t n = std::min(chunk.size(), expected - done);
        if (!in.read(reinterpret_cast<char*>(chunk.data()), std::streamsize(n)))
            throw fileError(path.string(), "read failed after " + std::to_string(done + std::size_t(in.gcount())) +
                                               " of " + std::to_string(expected) + " bytes");
        widenVoxels(type, chunk.data(), n / voxelBytes, swap, out + done / voxelBytes);
        done += n;
    }
}

// The decompressed size is only known by decompressing, so the buffer grows with the data actually there (a tiny
// file must not get the memory its name claims) and one more read looks for data beyond `expected`.
std::vector<unsigned char> readGzip(const fs::path& path, std::size_t expected, const Vec3i& dims,
                                    ScalarType type) {
    gzFile file = gzopen(path.c_str(), "rb");
    if (!file) throw fileError(path.string(), "cannot open");
    struct Closer {
        gzFile f;
        ~Closer() { gzclose(f); }
    } closer{file};
    gzbuffer(file, 1 << 20);

    // Reads up to n bytes; fewer only at the end of the data.
    const auto readInto = [&](unsigned char* dst, std::size_t n) {
        std::size_t done = 0;
        while (done < n) {
            const unsigned chunk = unsigned(std::min<std::size_t>(n - done, 1u << 30));
            const int got = gzread(file, dst + done, chunk);
            if (got < 0) {
                int code;
                const char* message = gzerror(file, &code);
                throw fileError(path.string(), std::string("corrupt gzip data: ") + message);
            }
            if (got == 0) break;
            done += std::size_t(got);
        }
        int code;
        gzerror(file, &code);
        if (code == Z_BUF_ERROR)  // the input ended inside a gzip stream
            throw fileError(path.string(), "truncated gzip data: it ends after " + std::to_string(done) +
                                               " decompressed bytes; dims " + dimsText(dims) + " of " +
                                               std::string(scalarTypeName(type)) + " need " +
                                               std::to_string(expected) + " bytes");
        return done;
    };

    std::vector<unsigned char> bytes;
    std::size_t got = 0;
    for (std::size_t size = std::min<std::size_t>(expected, 1 << 20); got == bytes.size() && got < expected;
         size = std::min(expected, 2 * size)) {
        bytes.resize(size);
        got += readInto(bytes.data() + got, size - got);
    }
    if (got < expected) throw fileError(path.string(), sizeMismatch(expected, got, dims, type));
    std::size_t extra = 0;
    for (std::vector<unsigned char> rest(1 << 16);;) {
        const std::size_t n = readInto(rest.data(), rest.size());
        if (n == 0) break;
        extra += n;
    }
    if (extra > 0) throw fileError(path.string(), sizeMismatch(expected, expected + extra, dims, type));
    return bytes;
}

}  // namespace

Volume loadRaw(const fs::path& path, const RawOptions& flags) {
    RawOptions options = flags;
    fillFromName(path, options);
    if (!options.dims)
        throw fileError(path.string(), "raw file without dims: give --dims X Y Z or name it NAME_XxYxZ_TYPE.raw");
    if (!options.type)
        throw fileError(path.string(),
                        "raw file without voxel type: give --type (uint8, int16, uint16, float32) or name it "
                        "NAME_XxYxZ_TYPE.raw");
    const Vec3i dims = *options.dims;
    const ScalarType type = *options.type;
    // A gzip file's bytes and the float values are held together while converting; a plain file's only a chunk
    // at a time.
    const bool gzip = lowerCase(path.extension().string()) == ".gz";
    checkVoxelBudget(path, dims.x, dims.y, dims.z, (gzip ? scalarBytes(type) : 0) + sizeof(float));
    const std::size_t expected = voxelCount(dims) * scalarBytes(type);
    const bool swap = options.bigEndian != (std::endian::native == std::endian::big);
    if (!gzip) checkPlainSize(path, expected, dims, type);
    const std::vector<unsigned char> bytes = gzip ? readGzip(path, expected, dims, type) : std::vector<unsigned char>();

    Volume v;
    v.grid.dims = dims;
    v.grid.spacing = options.spacing.value_or(Vec3d{1, 1, 1});
    v.sourceType = type;
    v.values.resize(v.grid.voxels());
    if (gzip)
        widenVoxels(type, bytes.data(), v.values.size(), swap, v.values.data());
    else
        readPlainWidened(path, expected, type, swap, v.values.data());
    return v;
}

}  // namespace vr

// MetaImage header checks before vtkMetaImageReader: metaio allocates from what the header says (the image, and
// the compressed data's buffer), and a garbled compressed header made it ask for (size_t)-1 bytes.
#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

std::string trim(const std::string& s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// Whitespace-separated integers, all of them, or nothing.
std::vector<long long> integers(const std::string& text) {
    std::istringstream in(text);
    std::vector<long long> values;
    for (long long v; in >> v;) values.push_back(v);
    if (!in.eof()) return {};
    return values;
}

}  // namespace

void checkMetaImageHeader(const fs::path& path) {
    const auto fail = [&](const std::string& problem) {
        return fileError(path.string(), "invalid MetaImage header: " + problem);
    };
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fileError(path.string(), "cannot open");
    // "Key = Value" lines (metaio takes ':' for '=' too) up to ElementDataFile, which ends the header.
    std::map<std::string, std::string> fields;
    std::size_t read = 0;
    for (std::string line; !fields.contains("ElementDataFile");) {
        if (!std::getline(in, line)) throw fail("it ends before an ElementDataFile line");
        if ((read += line.size() + 1) > (1 << 16)) throw fail("no ElementDataFile line in its first 64 KiB");
        if (trim(line).empty()) continue;
        const auto equals = line.find_first_of(":=");
        if (equals == std::string::npos) throw fail("a line without \"=\": \"" + trim(line).substr(0, 40) + "\"");
        const std::string key = trim(line.substr(0, equals));
        if (!fields.emplace(key, trim(line.substr(equals + 1))).second)
            throw fail("the field " + key.substr(0, 40) + " appears twice");
    }
    const auto value = [&](const std::string& key) -> const std::string& {
        const auto it = fields.find(key);
        if (it == fields.end()) throw fail("no " + key);
        return it->second;
    };

    const std::vector<long long> ndims = integers(value("NDims"));
    if (ndims.size() != 1 || ndims[0] < 1 || ndims[0] > 3)
        throw fail("NDims \"" + value("NDims") + "\" is not 1, 2 or 3");
    const std::vector<long long> dims = integers(value("DimSize"));
    if (dims.size() != std::size_t(ndims[0]))
        throw fail("DimSize \"" + value("DimSize") + "\" does not hold NDims integers");
    for (long long d : dims)
        if (d < 1) throw fail("DimSize \"" + value("DimSize") + "\" holds a size that is not positive");

    // metaio's ElementType names with their sizes in bytes (MET_LONG is 4 bytes there).
    static const std::map<std::string, int> types{
        {"MET_CHAR", 1}, {"MET_UCHAR", 1},     {"MET_SHORT", 2},      {"MET_USHORT", 2}, {"MET_INT", 4},
        {"MET_UINT", 4}, {"MET_LONG", 4},      {"MET_ULONG", 4},      {"MET_LONG_LONG", 8},
        {"MET_ULONG_LONG", 8}, {"MET_FLOAT", 4}, {"MET_DOUBLE", 8}};
    const auto type = types.find(value("ElementType"));
    if (type == types.end()) throw fail("ElementType \"" + value("ElementType") + "\" is not a scalar MET_ type");
    long long channels = 1;
    if (fields.contains("ElementNumberOfChannels")) {
        const std::vector<long long> n = integers(fields["ElementNumberOfChannels"]);
        if (n.size() != 1 || n[0] < 1 || n[0] > 1024)
            throw fail("ElementNumberOfChannels \"" + fields["ElementNumberOfChannels"] + "\" is not in 1..1024");
        channels = n[0];
    }
    // metaio allocates the image from the header before reading, so the size must fit in memory and the data must
    // be there first.
    const Vec3i d = checkVoxelBudget(path, dims[0], dims.size() > 1 ? dims[1] : 1, dims.size() > 2 ? dims[2] : 1,
                                     std::size_t(channels) * (std::size_t(type->second) + sizeof(float)));
    const std::uintmax_t needed = std::uintmax_t(d.x) * std::uintmax_t(d.y) * std::uintmax_t(d.z) *
                                  std::uintmax_t(channels) * std::uintmax_t(type->second);

    // metaio reads compressed data into a buffer of CompressedDataSize bytes (of (size_t)-1 when it is missing)
    // and takes any value beginning with T, t or 1 for true.
    const bool compressed = fields.contains("CompressedData") && !fields["CompressedData"].empty() &&
                            std::string("Tt1").find(fields["CompressedData"][0]) != std::string::npos;
    long long compressedSize = 0;
    if (compressed) {
        if (!fields.contains("CompressedDataSize")) throw fail("compressed data without a CompressedDataSize");
        const std::vector<long long> size = integers(fields["CompressedDataSize"]);
        if (size.size() != 1 || size[0] < 1)
            throw fail("CompressedDataSize \"" + fields["CompressedDataSize"] + "\" is not a positive integer");
        compressedSize = size[0];
    }

    // The data follow the header (LOCAL) or fill one file beside it. Lists and patterns of files are refused:
    // metaio overran a buffer on a garbled pattern (found by fuzz_metaimage).
    const std::string& dataFile = value("ElementDataFile");
    if (dataFile.empty()) throw fail("ElementDataFile is empty");
    if (dataFile.starts_with("LIST") || dataFile.find('%') != std::string::npos)
        throw fail("ElementDataFile \"" + dataFile.substr(0, 40) +
                   "\": lists and patterns of data files are not supported");
    const bool local = dataFile == "LOCAL" || dataFile == "Local" || dataFile == "local";
    const fs::path data = local ? path : path.parent_path() / dataFile;
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(data, ec);
    if (ec) return;  // metaio names the missing data file
    std::uintmax_t start = !local ? 0 : in.eof() ? size : std::uintmax_t(in.tellg());
    if (!local && fields.contains("HeaderSize")) {
        const std::vector<long long> skip = integers(fields["HeaderSize"]);
        if (skip.size() == 1 && skip[0] > 0) start = std::uintmax_t(skip[0]);  // -1: the data end the file
    }
    const std::uintmax_t held = size - std::min(size, start);
    if (!compressed) {
        if (held < needed)
            throw fail("its data hold " + std::to_string(held) + " bytes but DimSize \"" + value("DimSize") +
                       "\" of " + type->first + " needs " + std::to_string(needed));
        return;
    }
    if (std::uintmax_t(compressedSize) > held)
        throw fail("CompressedDataSize " + std::to_string(compressedSize) + " is more than the " +
                   std::to_string(held) + " bytes of data the file holds");
    if (const std::uintmax_t got =
            decompressedBytes(data, start, needed, Compression::ZlibOrGzip, std::uintmax_t(compressedSize));
        got < needed)
        throw fail("its compressed data decompress to " + std::to_string(got) + " bytes but DimSize \"" +
                   value("DimSize") + "\" of " + type->first + " needs " + std::to_string(needed));
}

}  // namespace vr

// MetaImage header checks before vtkMetaImageReader: metaio allocates from what the header says (the image, and
// the compressed data's buffer), and a garbled compressed header made it ask for (size_t)-1 bytes.
#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "preprocess/load/bounded_reader.h"
#include "preprocess/load/compressed_data.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/header_text.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {
namespace fs = std::filesystem;

void checkMetaImageHeader(const fs::path& path) {
    BoundedReader file(path, "invalid MetaImage header");
    // "Key = Value" lines (metaio takes ':' for '=' too) up to ElementDataFile, which ends the header.
    std::map<std::string, std::string> fields;
    while (!fields.contains("ElementDataFile")) {
        const std::optional<std::string> line = file.line(1 << 16, "no ElementDataFile line in its first 64 KiB");
        if (!line) throw file.fail("it ends before an ElementDataFile line");
        if (trimmed(*line).empty()) continue;
        const auto equals = line->find_first_of(":=");
        if (equals == std::string::npos)
            throw file.fail("a line without \"=\": \"" + trimmed(*line).substr(0, 40) + "\"");
        const std::string key = trimmed(line->substr(0, equals));
        if (!fields.emplace(key, trimmed(line->substr(equals + 1))).second)
            throw file.fail("the field " + key.substr(0, 40) + " appears twice");
    }
    const auto value = [&](const std::string& key) -> const std::string& {
        const auto it = fields.find(key);
        if (it == fields.end()) throw file.fail("no " + key);
        return it->second;
    };

    const std::vector<long long> ndims = integers(value("NDims"));
    if (ndims.size() != 1 || ndims[0] < 1 || ndims[0] > 3)
        throw file.fail("NDims \"" + value("NDims") + "\" is not 1, 2 or 3");
    const std::vector<long long> dims = integers(value("DimSize"));
    if (dims.size() != std::size_t(ndims[0]))
        throw file.fail("DimSize \"" + value("DimSize") + "\" does not hold NDims integers");
    for (long long d : dims)
        if (d < 1) throw file.fail("DimSize \"" + value("DimSize") + "\" holds a size that is not positive");

    // metaio's ElementType names with their sizes in bytes (MET_LONG is 4 bytes there).
    static const std::map<std::string, int> types{
        {"MET_CHAR", 1}, {"MET_UCHAR", 1},     {"MET_SHORT", 2},      {"MET_USHORT", 2}, {"MET_INT", 4},
        {"MET_UINT", 4}, {"MET_LONG", 4},      {"MET_ULONG", 4},      {"MET_LONG_LONG", 8},
        {"MET_ULONG_LONG", 8}, {"MET_FLOAT", 4}, {"MET_DOUBLE", 8}};
    const auto type = types.find(value("ElementType"));
    if (type == types.end()) throw file.fail("ElementType \"" + value("ElementType") + "\" is not a scalar MET_ type");
    long long channels = 1;
    if (fields.contains("ElementNumberOfChannels")) {
        const std::vector<long long> n = integers(fields["ElementNumberOfChannels"]);
        if (n.size() != 1 || n[0] < 1 || n[0] > 1024)
            throw file.fail("ElementNumberOfChannels \"" + fields["ElementNumberOfChannels"] + "\" is not in 1..1024");
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
        if (!fields.contains("CompressedDataSize")) throw file.fail("compressed data without a CompressedDataSize");
        const std::vector<long long> size = integers(fields["CompressedDataSize"]);
        if (size.size() != 1 || size[0] < 1)
            throw file.fail("CompressedDataSize \"" + fields["CompressedDataSize"] + "\" is not a positive integer");
        compressedSize = size[0];
    }

    // The data follow the header (LOCAL) or fill one file beside it. Lists and patterns of files are refused:
    // metaio overran a buffer on a garbled pattern (found by fuzz_metaimage).
    const std::string& dataFile = value("ElementDataFile");
    if (dataFile.empty()) throw file.fail("ElementDataFile is empty");
    if (dataFile.starts_with("LIST") || dataFile.find('%') != std::string::npos)
        throw file.fail("ElementDataFile \"" + dataFile.substr(0, 40) +
                        "\": lists and patterns of data files are not supported");
    const bool local = dataFile == "LOCAL" || dataFile == "Local" || dataFile == "local";
    std::optional<BoundedReader> detached;
    if (!local) {
        std::error_code ec;
        const fs::path other = path.parent_path() / dataFile;
        if (!fs::is_regular_file(other, ec)) return;  // metaio names the missing data file
        detached.emplace(file.dataFile(other));
    }
    BoundedReader& data = local ? file : *detached;
    std::uintmax_t start = local ? file.position() : 0;
    if (!local && fields.contains("HeaderSize")) {
        const std::vector<long long> skip = integers(fields["HeaderSize"]);
        if (skip.size() == 1 && skip[0] > 0) start = std::uintmax_t(skip[0]);  // -1: the data end the file
    }
    const std::uintmax_t held = data.size() - std::min<std::uintmax_t>(data.size(), start);
    if (!compressed) {
        if (held < needed)
            throw file.fail("its data hold " + std::to_string(held) + " bytes but DimSize \"" + value("DimSize") +
                            "\" of " + type->first + " needs " + std::to_string(needed));
        return;
    }
    if (std::uintmax_t(compressedSize) > held)
        throw file.fail("CompressedDataSize " + std::to_string(compressedSize) + " is more than the " +
                        std::to_string(held) + " bytes of data the file holds");
    if (const std::uintmax_t got =
            decompressedBytes(data, start, needed, Compression::ZlibOrGzip, std::uintmax_t(compressedSize));
        got < needed)
        throw file.fail("its compressed data decompress to " + std::to_string(got) + " bytes but DimSize \"" +
                        value("DimSize") + "\" of " + type->first + " needs " + std::to_string(needed));
}

}  // namespace vr

// MetaImage header checks before vtkMetaImageReader: metaio allocates from what the header says, and a garbled
// compressed header made it ask for (size_t)-1 bytes.
#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "preprocess/load/header_checks.h"

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
    // "Key = Value" lines up to ElementDataFile, which ends the header.
    std::map<std::string, std::string> fields;
    std::size_t read = 0;
    for (std::string line; !fields.contains("ElementDataFile");) {
        if (!std::getline(in, line)) throw fail("it ends before an ElementDataFile line");
        if ((read += line.size() + 1) > (1 << 16)) throw fail("no ElementDataFile line in its first 64 KiB");
        if (trim(line).empty()) continue;
        const auto equals = line.find('=');
        if (equals == std::string::npos) throw fail("a line without \"=\": \"" + trim(line).substr(0, 40) + "\"");
        fields[trim(line.substr(0, equals))] = trim(line.substr(equals + 1));
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

    static const char* const types[] = {"MET_CHAR",      "MET_UCHAR",      "MET_SHORT", "MET_USHORT",
                                        "MET_INT",       "MET_UINT",       "MET_LONG",  "MET_ULONG",
                                        "MET_LONG_LONG", "MET_ULONG_LONG", "MET_FLOAT", "MET_DOUBLE"};
    if (std::find(std::begin(types), std::end(types), value("ElementType")) == std::end(types))
        throw fail("ElementType \"" + value("ElementType") + "\" is not a scalar MET_ type");

    if (fields.contains("CompressedData") && fields["CompressedData"] == "True") {
        if (!fields.contains("CompressedDataSize")) throw fail("compressed data without a CompressedDataSize");
        const std::vector<long long> size = integers(fields["CompressedDataSize"]);
        if (size.size() != 1 || size[0] < 1)
            throw fail("CompressedDataSize \"" + fields["CompressedDataSize"] + "\" is not a positive integer");
    }
}

}  // namespace vr

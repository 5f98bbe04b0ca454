// NRRD checks before vtkNrrdReader, which loops forever on control bytes in a header line and reads short data
// without a word (the missing voxels stay uninitialised).
#include <algorithm>
#include <cctype>
#include <cstdint>
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

// Bytes per value of a NRRD type name (its spellings: "uchar", "unsigned char", "uint8_t", ...); 0 if unknown.
int typeBytes(const std::string& type) {
    const auto has = [&](const char* part) { return type.find(part) != std::string::npos; };
    if (type == "float") return 4;
    if (type == "double") return 8;
    if (has("char") || has("int8")) return 1;
    if (has("short") || has("int16")) return 2;
    if (has("long") || has("int64")) return 8;
    if (has("int")) return 4;
    return 0;
}

}  // namespace

void checkNrrdFile(const fs::path& path) {
    const auto fail = [&](const std::string& problem) {
        return fileError(path.string(), "invalid NRRD file: " + problem);
    };
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fileError(path.string(), "cannot open");

    // "key: value" lines up to a blank line (attached data) or the end of the file (a detached header).
    std::map<std::string, std::string> fields;
    int lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) break;
        for (char c : line)
            if (std::iscntrl(static_cast<unsigned char>(c)) && c != '\t')
                throw fail("header line " + std::to_string(lineNumber) + " holds control byte " +
                           std::to_string(int(static_cast<unsigned char>(c))));
        if (lineNumber == 1 || line[0] == '#') continue;
        if (const auto colon = line.find(": "); colon != std::string::npos && line.find(":=") != colon)
            fields[trim(line.substr(0, colon))] = trim(line.substr(colon + 2));
    }
    const std::streamoff headerEnd = in.eof() ? -1 : std::streamoff(in.tellg());

    const auto it = fields.find("sizes");
    const int bytes = typeBytes(fields["type"]);
    if (it == fields.end() || bytes == 0) return;  // VTK's reader names what is missing
    std::istringstream sizesText(it->second);
    std::vector<std::int64_t> sizes;
    for (std::int64_t n; sizesText >> n;) sizes.push_back(n);
    if (sizes.empty()) return;
    // A size no machine can hold is told as such, before the data are looked at.
    const std::size_t loading = std::size_t(bytes) + sizeof(float);
    std::uintmax_t values = 1;
    if (sizes.size() == 3) {
        const Vec3i dims = checkVoxelBudget(path, sizes[0], sizes[1], sizes[2], loading);
        values = std::uintmax_t(dims.x) * std::uintmax_t(dims.y) * std::uintmax_t(dims.z);
    } else {
        for (std::int64_t n : sizes) {
            if (n < 1 || values > (std::uintmax_t(1) << 40) / std::uintmax_t(n)) return;  // left to VTK's reader
            values *= std::uintmax_t(n);
        }
        checkVoxelBudget(path, std::int64_t(values), 1, 1, loading);
    }

    const std::string dataFile = fields.contains("data file") ? fields["data file"] : fields["datafile"];
    if (dataFile.starts_with("LIST") || dataFile.find('%') != std::string::npos) return;  // several data files
    const fs::path data = dataFile.empty() ? path : path.parent_path() / dataFile;
    if (dataFile.empty() && headerEnd < 0) throw fail("the header has no blank line before the data and no data file");
    const std::streamoff start = dataFile.empty() ? headerEnd : 0;

    const std::string encoding = fields["encoding"];
    if (encoding == "raw") {
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(data, ec);
        if (ec) throw fail("cannot read data file " + data.string() + ": " + ec.message());
        const std::uintmax_t available = size - std::min<std::uintmax_t>(size, std::uintmax_t(start));
        if (available < values * std::uintmax_t(bytes))
            throw fail("it holds " + std::to_string(available) + " bytes of raw data but sizes \"" + it->second +
                       "\" of type " + fields["type"] + " need " + std::to_string(values * std::uintmax_t(bytes)));
    } else if (encoding == "ascii" || encoding == "text" || encoding == "txt") {
        std::ifstream text(data, std::ios::binary);
        if (!text || !text.seekg(start)) throw fail("cannot read data file " + data.string());
        std::uintmax_t count = 0;
        for (std::string token; count < values && text >> token;) ++count;
        if (count < values)
            throw fail("it holds " + std::to_string(count) + " ASCII values but sizes \"" + it->second + "\" need " +
                       std::to_string(values));
    }
}

}  // namespace vr

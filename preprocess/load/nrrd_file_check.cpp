// NRRD checks before vtkNrrdReader, which loops forever on control bytes in a header line, reads short data
// without a word (the missing voxels stay uninitialised) and allocates the image before it inflates gzip data.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/lower_case.h"
#include "preprocess/load/bounded_reader.h"
#include "preprocess/load/compressed_data.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/header_text.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

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
    BoundedReader file(path, "invalid NRRD file");
    // "key: value" lines up to a blank line (attached data) or the end of the file (a detached header).
    // vtkNrrdReader parses the first 4 MiB - 1 bytes up to their first blank line, else all of them: a longer
    // header is refused.
    constexpr std::uint64_t kVtkHeaderBytes = 0x400000 - 1;
    std::map<std::string, std::string> fields;
    int lineNumber = 0;
    std::optional<std::uint64_t> headerEnd;  // where attached data start
    while (std::optional<std::string> read =
               file.line(kVtkHeaderBytes, "the header is longer than the 4 MiB VTK's reader reads")) {
        std::string& line = *read;
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) {
            if (file.lineEnded()) headerEnd = file.position();
            break;
        }
        if (lineNumber == 1 && !line.starts_with("NRRD000"))
            throw file.fail("not a NRRD file: its first line is not the magic \"NRRD000N\"");
        for (char c : line)
            if (std::iscntrl(static_cast<unsigned char>(c)) && c != '\t')
                throw file.fail("header line " + std::to_string(lineNumber) + " holds control byte " +
                                std::to_string(int(static_cast<unsigned char>(c))));
        if (lineNumber == 1 || line[0] == '#') continue;
        const auto colon = line.find(": ");
        if (colon == std::string::npos || line.find(":=") == colon) continue;  // not a field ("key:=value" pairs)
        // Keys exactly as vtkNrrdReader matches them, untrimmed: a space before or after a key makes another key
        // (" type" left it without a type, on which it looped forever; "sizes :" without sizes, on which it read
        // through a null stream: both found by fuzz_nrrd).
        const std::string key = line.substr(0, colon);
        if (!fields.emplace(key, trimmed(line.substr(colon + 2))).second)
            throw file.fail("the field \"" + key + "\" appears twice (header line " + std::to_string(lineNumber) + ")");
        // vtkNrrdReader reads per-axis fields with the dimension it has seen so far (a sizes line before the
        // dimension one made it read through a null stream, SEGV); the format puts dimension first, too.
        static const std::set<std::string> perAxis{"sizes",     "spacings", "thicknesses", "axis mins",
                                                   "axismins",  "axis maxs", "axismaxs",   "centers",
                                                   "centerings", "labels",  "units",       "kinds",
                                                   "space directions"};
        if (perAxis.contains(key) && !fields.contains("dimension"))
            throw file.fail("the field \"" + key + "\" comes before the dimension field (header line " +
                            std::to_string(lineNumber) + ")");
    }
    if (lineNumber == 0) throw file.fail("the file is empty");
    // A last line without a line break vtkNrrdReader rereads forever (std::getline leaves the line as it was once
    // the stream has ended: found by fuzz_nrrd).
    if (!headerEnd && !file.lineEnded()) throw file.fail("the header's last line has no line break");
    // vtkNrrdReader reads through a null stream (SEGV) when dimension or sizes are missing; the format requires
    // these four fields.
    for (const char* key : {"type", "dimension", "sizes", "encoding"})
        if (!fields.contains(key))
            throw file.fail(std::string("no \"") + key +
                            "\" field (a NRRD header needs type, dimension, sizes and encoding)");
    const std::vector<long long> dimensionField = integers(fields["dimension"]);
    if (dimensionField.size() != 1 || dimensionField[0] < 1 || dimensionField[0] > 16)
        throw file.fail("dimension \"" + fields["dimension"] + "\" is not an integer in 1..16");
    const int dimension = int(dimensionField[0]);
    const auto it = fields.find("sizes");
    const std::vector<long long> sizes = integers(it->second);
    if (sizes.size() != std::size_t(dimension))
        throw file.fail("sizes \"" + it->second + "\" are not " + std::to_string(dimension) +
                        " integers (the dimension)");
    // vtkNrrdReader takes the first axis for components when the dimension is 4 or that axis has 9 samples or
    // fewer, and reads through a null stream (SEGV) when that leaves fewer than 2 or more than 3 image axes.
    const bool componentAxis = dimension == 4 || sizes[0] <= 9;
    if (const int axes = dimension - componentAxis; axes < 2 || axes > 3)
        throw file.fail("dimension " + std::to_string(dimension) + " and sizes \"" + it->second +
                        "\" leave VTK's reader " + std::to_string(axes) + " image axes" +
                        (componentAxis ? " (it takes the first axis for components)" : "") + "; it reads 2 or 3");

    // The data file field, as vtkNrrdReader splits it into words: one file (a name, spaces and all, unless it is of 4
    // words or more), "LIST [SUBDIM]" with the files on the lines after it, or "FORMAT MIN MAX STEP [SUBDIM]", which
    // it expands by snprintf(FORMAT, i) for i from MIN to MAX by STEP. It parses this field before it checks the type:
    // without a value it takes a first word it does not have (SEGV in a string comparison); with a step of 0 from
    // words that are not numbers it loops until memory runs out; a format of other conversions than one integer's
    // writes where they point. All found by fuzz_nrrd. Data in several files is refused: one data file holds it all.
    if (fields.contains("data file") && fields.contains("datafile"))
        throw file.fail("the header has both a \"data file\" and a \"datafile\" field (VTK's reader would take two "
                        "data files)");
    for (const char* key : {"data file", "datafile"}) {
        if (!fields.contains(key)) continue;
        const std::vector<std::string> named = words(fields[key]);
        if (named.empty()) throw file.fail(std::string("the \"") + key + "\" field names no file");
        if (named[0] == "LIST" || named.size() >= 4)
            throw file.fail(std::string("the \"") + key + "\" field \"" + fields[key] +
                            "\" splits the data into several files, which are not read: write them as one data file");
    }

    // vtkNrrdReader takes the type and the encoding in any case ("ascIi" read as ASCII, after it allocated what the
    // sizes claim: found by fuzz_nrrd), so they are checked so.
    const int bytes = typeBytes(lowerCase(fields["type"]));
    if (bytes == 0) return;  // VTK's reader names the type it does not know
    // A size no machine can hold is told as such, before the data are looked at.
    const std::size_t loading = std::size_t(bytes) + sizeof(float);
    std::uintmax_t values = 1;
    if (sizes.size() == 3) {
        const Vec3i dims = checkVoxelBudget(path, sizes[0], sizes[1], sizes[2], loading);
        values = std::uintmax_t(dims.x) * std::uintmax_t(dims.y) * std::uintmax_t(dims.z);
    } else {
        for (long long n : sizes) {
            if (n < 1) throw file.fail("sizes \"" + it->second + "\" hold one below 1");
            if (values > (std::uintmax_t(1) << 40) / std::uintmax_t(n))
                throw file.fail("sizes \"" + it->second + "\" claim more than 2^40 values");
            values *= std::uintmax_t(n);
        }
        checkVoxelBudget(path, std::int64_t(values), 1, 1, loading);
    }

    const std::string dataFile = fields.contains("data file") ? fields["data file"] : fields["datafile"];
    if (dataFile.empty() && !headerEnd)
        throw file.fail("the header has no blank line before the data and no data file");
    const std::uint64_t start = dataFile.empty() ? *headerEnd : 0;

    const std::string encoding = lowerCase(fields["encoding"]);
    const bool raw = encoding == "raw", ascii = encoding == "ascii" || encoding == "text" || encoding == "txt",
               gzip = encoding == "gzip" || encoding == "gz";
    if (!raw && !ascii && !gzip) return;  // left to VTK's reader
    std::optional<BoundedReader> detached;
    BoundedReader& data = dataFile.empty() ? file : detached.emplace(file.dataFile(path.parent_path() / dataFile));
    if (raw) {
        const std::uintmax_t available = data.size() - std::min(data.size(), start);
        if (available < values * std::uintmax_t(bytes))
            throw file.fail("it holds " + std::to_string(available) + " bytes of raw data but sizes \"" + it->second +
                            "\" of type " + fields["type"] + " need " + std::to_string(values * std::uintmax_t(bytes)));
    } else if (ascii) {
        data.seek(start, "its data");
        if (const std::uint64_t count = data.countWords(values); count < values)
            throw file.fail("it holds " + std::to_string(count) + " ASCII values but sizes \"" + it->second +
                            "\" need " + std::to_string(values));
    } else {
        // Counted by decompressing (up to what is needed): the reader allocates the image before it inflates.
        const std::uintmax_t needed = values * std::uintmax_t(bytes);
        if (const std::uintmax_t got = decompressedBytes(data, start, needed, Compression::GzipOrPlain); got < needed)
            throw file.fail("its gzip data decompress to " + std::to_string(got) + " bytes but sizes \"" + it->second +
                            "\" of type " + fields["type"] + " need " + std::to_string(needed));
    }
}

}  // namespace vr

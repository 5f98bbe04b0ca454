// Legacy VTK structured points checks before vtkStructuredPointsReader, which dereferences null on garbage among
// its header keywords and reads short ASCII or binary data without a word.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/lower_case.h"
#include "preprocess/load/bounded_reader.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

// The line's words, keywords upper-cased: VTK's reader takes them in any case.
std::vector<std::string> words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    if (!out.empty())
        for (char& c : out[0]) c = char(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

// The whole word as a number, or nothing.
bool number(const std::string& word, double& value) {
    std::istringstream in(word);
    return (in >> value) && in.eof();
}

int typeBytes(const std::string& type) {
    static const std::map<std::string, int> sizes = {{"char", 1},           {"unsigned_char", 1}, {"short", 2},
                                                     {"unsigned_short", 2}, {"int", 4},           {"unsigned_int", 4},
                                                     {"long", 8},           {"unsigned_long", 8}, {"vtktypeint64", 8},
                                                     {"vtktypeuint64", 8},  {"float", 4},         {"double", 8}};
    const auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

}  // namespace

void checkVtkLegacyFile(const fs::path& path) {
    BoundedReader file(path, "invalid VTK structured points file");
    const std::string version = file.line().value_or(""), title = file.line().value_or(""),
                      format = file.line().value_or(""), dataset = file.line().value_or("");
    if (!version.starts_with("# vtk DataFile")) throw file.fail("the first line is not \"# vtk DataFile Version ...\"");
    const std::vector<std::string> formatWords = words(format);
    if (formatWords.size() != 1 || (formatWords[0] != "ASCII" && formatWords[0] != "BINARY"))
        throw file.fail("the third line is not ASCII or BINARY");
    const bool binary = formatWords[0] == "BINARY";
    std::vector<std::string> datasetWords = words(dataset);
    for (std::string& w : datasetWords)
        for (char& c : w) c = char(std::toupper(static_cast<unsigned char>(c)));
    if (datasetWords != std::vector<std::string>{"DATASET", "STRUCTURED_POINTS"})
        throw file.fail("the fourth line is not \"DATASET STRUCTURED_POINTS\"");

    // Keyword lines, each with its numbers, up to SCALARS.
    std::map<std::string, std::vector<double>> numbers;
    std::vector<std::string> scalars;
    while (scalars.empty()) {
        const std::optional<std::string> line = file.line();
        if (!line) throw file.fail("it ends before its SCALARS line");
        std::vector<std::string> w = words(*line);
        if (w.empty()) continue;
        if (w[0] == "SCALARS") {
            if (w.size() < 3 || w.size() > 4)
                throw file.fail("the SCALARS line is not \"SCALARS NAME TYPE [COMPONENTS]\"");
            scalars = w;
            break;
        }
        static const std::map<std::string, std::size_t> counts = {
            {"DIMENSIONS", 3}, {"SPACING", 3}, {"ASPECT_RATIO", 3}, {"ORIGIN", 3}, {"POINT_DATA", 1}};
        const auto count = counts.find(w[0]);
        if (count == counts.end())
            throw file.fail("unexpected \"" + w[0].substr(0, 40) +
                            "\" before SCALARS (only scalar point data is supported)");
        if (w.size() != count->second + 1)
            throw file.fail(w[0] + " is not followed by " + std::to_string(count->second) + " numbers");
        std::vector<double>& values = numbers[w[0]];
        for (std::size_t i = 1; i < w.size(); ++i)
            if (double v; number(w[i], v))
                values.push_back(v);
            else
                throw file.fail(w[0] + " is followed by \"" + w[i].substr(0, 40) + "\", not a number");
    }
    if (!numbers.contains("DIMENSIONS") || !numbers.contains("POINT_DATA"))
        throw file.fail("no DIMENSIONS or POINT_DATA");
    const std::vector<double>& d = numbers["DIMENSIONS"];
    for (double n : d)
        if (!(n >= 1 && n <= 1e15 && n == std::floor(n))) throw file.fail("DIMENSIONS must be positive integers");
    scalars[2] = lowerCase(scalars[2]);
    const int bytes = typeBytes(scalars[2]);
    if (bytes == 0) throw file.fail("SCALARS type \"" + scalars[2].substr(0, 40) + "\" is not supported");
    checkVoxelBudget(path, std::int64_t(d[0]), std::int64_t(d[1]), std::int64_t(d[2]),
                     std::size_t(bytes) + sizeof(float));
    const double points = d[0] * d[1] * d[2];
    if (numbers["POINT_DATA"][0] != points) throw file.fail("POINT_DATA does not equal the product of DIMENSIONS");

    double components = 1;
    if (scalars.size() == 4 && (!number(scalars[3], components) || components < 1 || components > 4))
        throw file.fail("SCALARS components \"" + scalars[3].substr(0, 40) + "\" is not 1 to 4");
    const double values = points * components;

    // The data follow an optional LOOKUP_TABLE line.
    std::uint64_t dataStart = file.position();
    if (const std::optional<std::string> line = file.line();
        line && words(*line).size() == 2 && words(*line)[0] == "LOOKUP_TABLE")
        dataStart = file.position();
    file.seek(dataStart, "its data");
    if (binary) {
        const double available = double(file.size() - dataStart);
        if (available < values * bytes)
            throw file.fail("it holds " + std::to_string(std::int64_t(available)) +
                            " bytes of binary data but POINT_DATA " + "needs " +
                            std::to_string(std::int64_t(values * bytes)));
    } else {
        const double count = double(file.countWords(std::uint64_t(std::ceil(values))));
        if (count < values)
            throw file.fail("it holds " + std::to_string(std::int64_t(count)) + " ASCII values but POINT_DATA needs " +
                            std::to_string(std::int64_t(values)));
    }
}

}  // namespace vr

// VTK XML image data checks before vtkXMLImageDataReader, which allocates every array the extent claims before it
// decodes the data: a few hundred bytes claiming 1024^3 floats made it allocate 4 GiB (found by fuzz_vti).
#include <cctype>
#include <climits>
#include <map>
#include <sstream>
#include <string>

#include "preprocess/load/bounded_reader.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

// The value of attribute `name` in the tag that starts at `tag` (up to its '>'), or "" when it has none.
std::string attribute(const std::string& text, std::size_t tag, const std::string& name) {
    const std::size_t end = text.find('>', tag);
    const std::string key = name + "=\"";
    for (std::size_t at = text.find(key, tag); at < end; at = text.find(key, at + 1)) {
        const std::size_t open = at + key.size(), close = text.find('"', open);
        if (std::isspace(static_cast<unsigned char>(text[at - 1])) && close < end)
            return text.substr(open, close - open);
    }
    return {};
}

}  // namespace

void checkVtkXmlImageFile(const fs::path& path) {
    BoundedReader file(path, "invalid VTK XML image data");
    // The header: the tags up to the first array's data (inline data and appended data come after).
    const std::string text = file.bytesUpTo(1 << 16);
    const std::size_t root = text.find("<VTKFile"), image = text.find("<ImageData");
    const std::size_t points = text.find("<PointData", text.find("<Piece", image));
    const std::size_t array = text.find("<DataArray", points);
    if (root == std::string::npos || image == std::string::npos || array == std::string::npos)
        return;  // VTK's reader names what is missing

    std::istringstream extentText(attribute(text, image, "WholeExtent"));
    long long e[6];
    for (long long& v : e) {
        if (!(extentText >> v)) return;  // likewise
        if (v < INT_MIN || v > INT_MAX)
            throw file.fail("WholeExtent \"" + attribute(text, image, "WholeExtent") + "\" is beyond the int range");
    }
    static const std::map<std::string, int> typeBytes{{"Int8", 1},   {"UInt8", 1},   {"Int16", 2},   {"UInt16", 2},
                                                      {"Int32", 4},  {"UInt32", 4},  {"Int64", 8},   {"UInt64", 8},
                                                      {"Float32", 4}, {"Float64", 8}};
    const auto type = typeBytes.find(attribute(text, array, "type"));
    if (type == typeBytes.end()) return;  // likewise
    long long components = 1;
    if (const std::string n = attribute(text, array, "NumberOfComponents"); !n.empty()) {
        std::istringstream nText(n);
        if (!(nText >> components) || components < 1 || components > 1024)
            throw file.fail("NumberOfComponents \"" + n + "\" is not in 1..1024");
    }
    const Vec3i dims = checkVoxelBudget(path, e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1,
                                        std::size_t(components * type->second) + sizeof(float));

    // No encoding packs values denser than raw bytes (base64 and ASCII take more), and none of VTK's compressors
    // inflates beyond its format's limit (deflate: 1032 to 1), so a file cannot hold more than this.
    const std::string compressor = attribute(text, root, "compressor");
    const double ratio = compressor.empty()                          ? 1
                         : compressor == "vtkZLibDataCompressor"     ? 1032
                         : compressor == "vtkLZ4DataCompressor"      ? 256
                                                                     : 1e5;  // LZMA: no tight limit
    const double size = double(file.size());
    const double claimed = double(dims.x) * dims.y * dims.z * double(components) * type->second;
    if (claimed > size * ratio)
        throw file.fail("WholeExtent \"" + attribute(text, image, "WholeExtent") + "\" claims " +
                        std::to_string(std::uint64_t(claimed)) + " bytes of " + type->first +
                        " values but the file of " + std::to_string(std::uint64_t(size)) + " bytes holds at most " +
                        std::to_string(std::uint64_t(size * ratio)) +
                        (compressor.empty() ? std::string(" (uncompressed)") : " (" + compressor + ")"));
}

}  // namespace vr

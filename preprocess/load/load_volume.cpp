// Picks the loader by file name (or folder), then applies the checks every format shares.
#include "preprocess/load/load_volume.h"

#include <cmath>
#include <string>

#include "core/errors.h"
#include "core/lower_case.h"
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/format_module.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

template <ModuleFormat format>
Volume throughModule(const fs::path& path, const RawOptions& raw) {
    return loadThroughModule(format, path, raw);
}

struct Format {
    const char* suffix;  // lower case, matched against the end of the lower-cased file name
    FormatLoader load;
};

// Raw files are read here; the other formats by the modules of the libraries that read them (format_module.h).
constexpr Format formats[] = {
    {".raw", loadRaw},
    {".raw.gz", loadRaw},
    {".nrrd", throughModule<ModuleFormat::Nrrd>},
    {".nhdr", throughModule<ModuleFormat::Nrrd>},
    {".mhd", throughModule<ModuleFormat::MetaImage>},
    {".mha", throughModule<ModuleFormat::MetaImage>},
    {".nii", throughModule<ModuleFormat::Nifti>},
    {".nii.gz", throughModule<ModuleFormat::Nifti>},
    {".vti", throughModule<ModuleFormat::VtkXmlImage>},
    {".vtk", throughModule<ModuleFormat::VtkLegacy>},
    {".vdb", throughModule<ModuleFormat::Vdb>},
};

std::string supportedFormats() {
    std::string list;
    for (const Format& f : formats) list += std::string(f.suffix) + ", ";
    return list + "or a folder holding a DICOM series";
}

const Format* formatOf(const fs::path& path) {
    const std::string name = lowerCase(path.filename().string());
    for (const Format& f : formats)
        if (name.ends_with(f.suffix)) return &f;
    return nullptr;
}

FormatLoader loaderFor(const fs::path& path) {
    if (const Format* f = formatOf(path)) return f->load;
    throw fileError(path.string(), "unknown volume format; supported: " + supportedFormats());
}

std::string voxelText(const Vec3i& dims, std::size_t index) {
    const std::size_t row = std::size_t(dims.x), slice = row * std::size_t(dims.y);
    return "(" + std::to_string(index % row) + ", " + std::to_string(index % slice / row) + ", " +
           std::to_string(index / slice) + ")";
}

// NaN or Inf would poison every later stage (gradients, classification, min/max), so they are rejected here.
void requireFinite(const Volume& v, const fs::path& path) {
    std::size_t count = 0, first = 0;
    for (std::size_t i = 0; i < v.values.size(); ++i)
        if (!std::isfinite(v.values[i]) && count++ == 0) first = i;
    if (count > 0)
        throw fileError(path.string(), std::to_string(count) + (count == 1 ? " voxel is" : " voxels are") +
                                           " not finite (NaN or Inf); the first is voxel " +
                                           voxelText(v.grid.dims, first) + " = " + std::to_string(v.values[first]));
}

// Spacing and origin come from headers (or flags), so they are as untrusted as the voxels.
void requireValidGeometry(const GridGeometry& g, const fs::path& path) {
    for (int a = 0; a < 3; ++a) {
        if (!(std::isfinite(g.spacing[a]) && g.spacing[a] > 0))
            throw fileError(path.string(), std::string("spacing along ") + "xyz"[a] + " is " +
                                               std::to_string(g.spacing[a]) + "; it must be positive and finite");
        if (!std::isfinite(g.origin[a]))
            throw fileError(path.string(), std::string("origin along ") + "xyz"[a] + " is not finite");
    }
    // Cameras and rays use the extent's length: it must not overflow.
    if (!std::isfinite(length(g.extent())))
        throw fileError(path.string(), "spacing x dims overflows: the volume's extent is not finite");
}

}  // namespace

Volume loadVolume(const fs::path& path, const RawOptions& raw) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw fileError(path.string(), "no such file or folder");
    if (!raw.series.empty() && !fs::is_directory(status))
        throw fileError(path.string(), "--series chooses a series of a DICOM folder; this is a file");
    // The raw options would be ignored by every other format, whose header (or DICOM files) give what they say.
    const bool folder = fs::is_directory(status);
    const Format* format = folder ? nullptr : formatOf(path);
    if (folder || (format && format->load != loadRaw)) {
        std::string given;
        for (const auto& [set, flag] : {std::pair{raw.dims.has_value(), "--dims"}, {raw.type.has_value(), "--type"},
                                        {raw.spacing.has_value(), "--spacing"}, {raw.bigEndian, "--big-endian"}})
            if (set) given += (given.empty() ? "" : ", ") + std::string(flag);
        if (!given.empty())
            throw fileError(path.string(), given + ": for headerless raw files (.raw, .raw.gz) only; this " +
                                               (folder ? "DICOM series" : "file's header") +
                                               " gives the grid, type and byte order itself");
    }
    Volume v = folder ? loadThroughModule(ModuleFormat::DicomSeries, path, raw) : loaderFor(path)(path, raw);
    requireValidGeometry(v.grid, path);
    requireFinite(v, path);
    v.source = path.string();
    return v;
}

bool isVolumeFileName(const fs::path& path) { return formatOf(path) != nullptr; }

bool isRawFileName(const fs::path& path) {
    const Format* format = formatOf(path);
    return format && format->load == loadRaw;
}

}  // namespace vr

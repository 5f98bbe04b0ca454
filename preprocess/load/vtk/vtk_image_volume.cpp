#include "preprocess/load/vtk/vtk_image_volume.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkType.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "preprocess/load/voxel_conversion.h"

namespace vr {

Volume volumeFromVtkImage(vtkImageData* image, const std::filesystem::path& path) {
    const auto fail = [&](const std::string& problem) { return fileError(path.string(), problem); };
    int dims[3];
    image->GetDimensions(dims);
    if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0)
        throw fail("image has no voxels (dims " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
                   std::to_string(dims[2]) + ")");
    vtkDataArray* scalars = image->GetPointData()->GetScalars();
    if (!scalars) throw fail("image has no scalar values");
    if (scalars->GetNumberOfComponents() != 1)
        throw fail("image has " + std::to_string(scalars->GetNumberOfComponents()) +
                   " components per voxel; only scalar (1-component) volumes are supported");

    Volume v;
    v.grid.dims = {dims[0], dims[1], dims[2]};
    if (std::size_t(scalars->GetNumberOfTuples()) != v.grid.voxels())
        throw fail("image holds " + std::to_string(scalars->GetNumberOfTuples()) + " values for " +
                   std::to_string(v.grid.voxels()) + " voxels");

    double spacing[3], origin[3];
    int extent[6];
    image->GetSpacing(spacing);
    image->GetOrigin(origin);
    image->GetExtent(extent);
    for (int a = 0; a < 3; ++a) {
        v.grid.spacing[a] = spacing[a];
        // The first voxel's centre is at origin + extent_min * spacing (extents need not start at 0).
        v.grid.origin[a] = origin[a] + (extent[2 * a] - 0.5) * spacing[a];
    }

    v.values.resize(v.grid.voxels());
    const auto* bytes = static_cast<const unsigned char*>(scalars->GetVoidPointer(0));
    const auto widen = [&](ScalarType t) {
        v.sourceType = t;
        widenVoxels(t, bytes, v.values.size(), false, v.values.data());
    };
    switch (scalars->GetDataType()) {
        case VTK_UNSIGNED_CHAR: widen(ScalarType::UInt8); break;
        case VTK_SHORT: widen(ScalarType::Int16); break;
        case VTK_UNSIGNED_SHORT: widen(ScalarType::UInt16); break;
        case VTK_FLOAT: widen(ScalarType::Float32); break;
        default:
            v.sourceType = ScalarType::Float32;
            for (std::size_t i = 0; i < v.values.size(); ++i)
                v.values[i] = static_cast<float>(scalars->GetComponent(vtkIdType(i), 0));
    }
    return v;
}

void applyRescale(Volume& volume, double slope, double intercept) {
    if (!std::isfinite(intercept)) intercept = 0;
    if (!std::isfinite(slope) || slope == 0 || (slope == 1 && intercept == 0)) return;
    for (float& f : volume.values) f = float(f * slope + intercept);
    volume.sourceType = ScalarType::Float32;
}

void flipAxis(Volume& volume, int axis) {
    const Vec3i d = volume.grid.dims;
    auto& f = volume.values;
    const std::size_t row = std::size_t(d.x), slice = row * std::size_t(d.y);
    if (axis == 0) {
        for (std::size_t r = 0; r < f.size(); r += row) std::reverse(f.begin() + r, f.begin() + r + row);
    } else if (axis == 1) {
        for (int z = 0; z < d.z; ++z)
            for (int y = 0; y < d.y / 2; ++y)
                std::swap_ranges(f.begin() + linearIndex(d, 0, y, z), f.begin() + linearIndex(d, 0, y, z) + row,
                                 f.begin() + linearIndex(d, 0, d.y - 1 - y, z));
    } else {
        for (int z = 0; z < d.z / 2; ++z)
            std::swap_ranges(f.begin() + linearIndex(d, 0, 0, z), f.begin() + linearIndex(d, 0, 0, z) + slice,
                             f.begin() + linearIndex(d, 0, 0, d.z - 1 - z));
    }
}

}  // namespace vr

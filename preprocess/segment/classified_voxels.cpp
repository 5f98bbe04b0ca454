#include "preprocess/segment/classified_voxels.h"

#include <algorithm>

#include "core/errors.h"

namespace vr {

ClassifiedVoxels::ClassifiedVoxels(const Volume& scalars, const ScalarClassification& classification, bool normals,
                                   const LabelMap* labels)
    : grid_(&scalars.grid),
      scalars_(&scalars),
      table_(&classification.table),
      labels_(labels),
      referenceStep_(classification.referenceStep),
      flatGradient_(classification.flatGradient),
      normals_(normals) {
    const TransferTable& table = classification.table;
    if (scalars.grid.voxels() == 0 || scalars.values.size() != scalars.grid.voxels())
        throw InputError("segmentation: the scalars are empty or do not match their dimensions");
    if (table.size() == 0 || table.colour.size() != table.size() || !(table.step > 0))
        throw InputError("segmentation: the transfer table is empty or inconsistent");
    if (labels && (labels->label.size() != scalars.values.size() || labels->classes.size() == 0 ||
                   labels->classes.sigma.size() != labels->classes.size() ||
                   labels->classes.colour.size() != labels->classes.size()))
        throw InputError("segmentation: the label map does not match the scalars or its classes are not classified");
}

ClassifiedVoxels::ClassifiedVoxels(const ClassifiedVolume& stored)
    : grid_(&stored.grid), stored_(&stored), referenceStep_(stored.referenceStep), normals_(stored.hasNormals()) {
    const std::size_t n = stored.grid.voxels();
    if (n == 0 || stored.sigma.size() != n || stored.colour.size() != n ||
        (stored.hasNormals() && stored.normal.size() != n))
        throw InputError("segmentation: the classified volume is empty or its arrays do not match its dimensions");
}

std::array<float, 3> ClassifiedVoxels::normal(std::size_t i) const {
    if (stored_) return stored_->normal[i];
    const Vec3i& d = grid_->dims;
    const std::size_t nx = std::size_t(d.x), ny = std::size_t(d.y);
    const Vec3i v{int(i % nx), int(i / nx % ny), int(i / (nx * ny))};
    if (labels_ && device::labelShapesNormal(device::labelSigmaOf(*labels_, i)))
        return unitNormal(device::indicatorGradient(labels_->label, d, grid_->spacing, v, labels_->label[i]), 0);
    return unitNormal(centralGradient(*scalars_, v.x, v.y, v.z), flatGradient_);
}

void ClassifiedVoxels::normals(std::size_t first, int count, std::array<float, 3>* out) const {
    if (stored_ || labels_) {  // a label's normal comes from its indicator, voxel by voxel
        for (int i = 0; i < count; ++i) out[i] = normal(first + std::size_t(i));
        return;
    }
    const Vec3i& d = grid_->dims;
    const std::size_t nx = std::size_t(d.x), ny = std::size_t(d.y);
    const int x0 = int(first % nx), y = int(first / nx % ny), z = int(first / (nx * ny));
    constexpr int kRun = 256;
    double gx[kRun], gy[kRun], gz[kRun];
    for (int done = 0; done < count; done += kRun) {
        const int n = std::min(kRun, count - done);
        centralGradientRun(*scalars_, x0 + done, n, y, z, gx, gy, gz);
        for (int i = 0; i < n; ++i) out[done + i] = unitNormal(Vec3d{gx[i], gy[i], gz[i]}, flatGradient_);
    }
}

}  // namespace vr

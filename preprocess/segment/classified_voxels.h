// What segmentation reads of each voxel (docs/ALGORITHMS.md sections 2 and 3): its extinction, colour and normal as a
// nearest sample classifies them. Looked up on demand from the scalars and the transfer table, so that preparing a
// volume never holds a classified copy of it (28 bytes per voxel with normals); or read from a classified volume
// (preprocess/classify: classify()) where one exists.
#pragma once
#include <array>
#include <cstddef>

#include "core/classified_volume.h"
#include "core/gradient.h"
#include "core/label_map.h"
#include "core/scalar_classification.h"
#include "core/volume.h"
#include "shaders/label_lookup.h"
#include "shaders/transfer_lookup.h"

namespace vr {

struct VoxelOptics {
    float sigma;                  // extinction per world unit
    std::array<float, 3> colour;  // linear RGB
};

class ClassifiedVoxels {
public:
    // Voxels of `scalars` classified by `classification` (and `labels`, where given, mixed in as
    // shaders/label_lookup.h mixes them) as they are asked for; normals only when `normals`. All must outlive this
    // object. Throws InputError where the table, the scalars or the labels are inconsistent.
    ClassifiedVoxels(const Volume& scalars, const ScalarClassification& classification, bool normals,
                     const LabelMap* labels = nullptr);
    // The voxels of a classified volume, which must outlive this object. Throws InputError where its arrays do not
    // match its dimensions.
    ClassifiedVoxels(const ClassifiedVolume& stored);  // NOLINT: a classified volume is classified voxels

    const GridGeometry& grid() const { return *grid_; }
    bool hasNormals() const { return normals_; }
    double opacity(float sigma) const { return opacityFromExtinction(sigma, referenceStep_); }

    // What classify() stores for voxel i, bit for bit; with labels, the voxel's label mixed in.
    VoxelOptics optics(std::size_t i) const {
        if (stored_) return {stored_->sigma[i], stored_->colour[i]};
        const device::TableSample s = device::lookUpTable(*table_, scalars_->values[i]);
        if (!labels_) return {float(s.sigma), {float(s.colour[0]), float(s.colour[1]), float(s.colour[2])}};
        const std::size_t l = device::labelClassOf(*labels_, i);
        const double ls = labels_->classes.sigma[l];
        const std::array<float, 3>& lc = labels_->classes.colour[l];
        VoxelOptics o{float(device::labelledSigma(s.sigma, ls)), {}};
        for (int c = 0; c < 3; ++c) o.colour[c] = float(device::labelledChannel(s.sigma, s.colour[c], ls, lc[c]));
        return o;
    }
    // The voxel's label (0 without a label map): regions never hold two.
    uint16_t label(std::size_t i) const { return labels_ ? labels_->label[i] : 0; }
    bool labelled() const { return labels_ != nullptr; }
    float sigma(std::size_t i) const {
        if (stored_) return stored_->sigma[i];
        return labels_ ? optics(i).sigma : float(device::lookUpSigma(*table_, scalars_->values[i]));
    }
    // The unit normal, or (0,0,0) where the gradient is flat; only where hasNormals().
    std::array<float, 3> normal(std::size_t i) const;
    // normal() of voxels first .. first + count - 1, which lie in one row along x, into out: their gradients taken a
    // row at a time (centralGradientRun), bit for bit as normal() takes each.
    void normals(std::size_t first, int count, std::array<float, 3>* out) const;

private:
    const GridGeometry* grid_;
    const ClassifiedVolume* stored_ = nullptr;
    const Volume* scalars_ = nullptr;
    const TransferTable* table_ = nullptr;
    const LabelMap* labels_ = nullptr;
    double referenceStep_ = 1, flatGradient_ = 0;
    bool normals_ = false;
};

}  // namespace vr

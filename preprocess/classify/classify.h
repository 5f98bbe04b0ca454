// Classification (docs/ALGORITHMS.md section 2): the transfer function tabulated for a volume, which the renderers
// look each sample up in, and the classified volume that segmentation keys its regions on.
#pragma once
#include <array>
#include <optional>
#include <vector>

#include "core/classified_volume.h"
#include "core/scalar_classification.h"
#include "core/volume.h"
#include "preprocess/classify/transfer_function.h"

namespace vr {

struct ClassifyParams {
    std::optional<TransferFunction> transferFunction;  // required
    bool normals = true;              // normals in the classified volume (segmentation's T_a)
    double referenceStep = 0;         // dt0 in world units; 0 = the smallest spacing (one voxel)
    // |grad| at or below flatGradientFloor * (value range) / (smallest spacing) is flat: the normal is (0,0,0).
    double flatGradientFloor = 1e-6;
    bool operator==(const ClassifyParams&) const = default;
};

// The TF tabulated for `volume` (an entry at every integer value for integer volumes, else 65536 entries over the
// volume's range), sigma = -ln(1 - alpha) / dt0 at each entry, and the flat-gradient length. Throws InputError for
// bad parameters (no TF, a bad TF, dt0 < 0, bad spacing) or a volume with non-finite values.
ScalarClassification scalarClassification(const Volume& volume, const ClassifyParams& params);

// Every voxel as a nearest sample of it classifies (the renderers' rule, docs/ALGORITHMS.md section 2): sigma and
// colour looked up in the table, the normal from the gradient (flat at or below the flat length), normals only
// when `normals`. Reuses the memory of `out`'s arrays: a classification of the same size then takes no fresh
// pages. Throws InputError where the table or the volume is inconsistent.
void classify(const Volume& volume, const ScalarClassification& classification, bool normals, ClassifiedVolume& out);
// Both steps at once. Throws as scalarClassification does.
ClassifiedVolume classify(const Volume& volume, const ClassifyParams& params);
// The opacity and colour of `tf` at the entries of `volume`'s table (scalarClassification's, before the opacity
// becomes extinction): what TfRangeTable answers range queries over. Throws InputError for a volume with
// non-finite values.
SampledTransferFunction sampleForVolume(const Volume& volume, const TransferFunction& tf);

}  // namespace vr

// Classification (docs/ALGORITHMS.md section 2): scalar volume -> extinction, colour and normals.
#pragma once
#include <array>
#include <optional>
#include <vector>

#include "core/classified_volume.h"
#include "core/volume.h"
#include "preprocess/classify/iso_contour.h"
#include "preprocess/classify/transfer_function.h"

namespace vr {

struct ClassifyParams {
    std::optional<TransferFunction> transferFunction;  // exactly one of these two
    std::vector<IsoContour> isoContours;
    std::array<double, 3> isoColour{1, 1, 1};
    bool normals = true;              // compute gradients / normals (needed for shading and T_a)
    double referenceStep = 0;         // dt0 in world units; 0 = the smallest spacing (one voxel)
    // |grad| at or below flatGradientFloor * (value range) / (smallest spacing) is flat: the normal is (0,0,0).
    double flatGradientFloor = 1e-6;
    bool operator==(const ClassifyParams&) const = default;
};

// Opacity from the TF (sampled exactly at every integer value for integer volumes, else at 65536 values over the
// volume's range with linear interpolation) or from the iso-contours; sigma = -ln(1 - alpha) / dt0.
// Throws InputError for bad parameters (no or two classifications, bad TF or iso-contours, dt0 <= 0).
ClassifiedVolume classify(const Volume& volume, const ClassifyParams& params);
// The same into `out`, reusing the memory of its arrays: a classification of the same size then takes no fresh
// pages (about half the cost of a first one). On a throw `out` is left in an unspecified state.
void classify(const Volume& volume, const ClassifyParams& params, ClassifiedVolume& out);

// The table of `tf` that classify() samples for `volume` (exactly its entries). Throws InputError for a volume with
// non-finite values.
SampledTransferFunction transferTable(const Volume& volume, const TransferFunction& tf);

}  // namespace vr

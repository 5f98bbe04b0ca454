// Classification (ALGORITHMS.md section 2): scalar volume -> extinction, colour and normals.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/classified_volume.h"
#include "core/volume.h"

namespace vr {

// A 1D transfer function: piecewise-linear opacity and colour over the scalar value.
struct TransferFunction {
    struct OpacityPoint { double x, opacity; };
    struct ColourPoint { double x, r, g, b; };
    std::vector<OpacityPoint> opacity;  // sorted by x
    std::vector<ColourPoint> colour;    // sorted by x; empty -> white
    std::string name;
    std::string json;                   // the source text, kept for the prepared file's metadata

    double opacityAt(double f) const;
    std::array<double, 3> colourAt(double f) const;
};

// Reads ParaView's preset JSON ("Points": x, opacity, mid, sharp; "RGBPoints": x, r, g, b; a list or one object).
// Throws InputError naming the file and the problem.
TransferFunction loadTransferFunction(const std::filesystem::path& path);
TransferFunction parseTransferFunction(const std::string& jsonText, const std::string& sourceName);

// Levoy (1988) iso-contour classification, one term per iso-value.
struct IsoContour { double value, width, strength; };

struct ClassifyParams {
    std::optional<TransferFunction> transferFunction;  // one of these two
    std::vector<IsoContour> isoContours;
    std::array<double, 3> isoColour{1, 1, 1};
    bool normals = true;              // compute gradients / normals (needed for shading and T_a)
    double referenceStep = 0;         // dt0 in world units; 0 = the smallest spacing (one voxel)
    double flatGradientFloor = 1e-6;  // |grad| below this (relative to the value range per world unit) is flat
};

ClassifiedVolume classify(const Volume& volume, const ClassifyParams& params);

}  // namespace vr

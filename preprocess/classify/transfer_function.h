// A 1D transfer function read from ParaView's preset JSON (docs/ALGORITHMS.md section 2).
#pragma once
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace vr {

// Opacity and colour over the scalar value with ParaView's semantics: the opacity segment that starts at a point
// is shaped by that point's midpoint and sharpness (vtkPiecewiseFunction), colour is interpolated in `colourSpace`
// (vtkColorTransferFunction), and values outside the points' range take the end values (clamping).
struct TransferFunction {
    struct OpacityPoint {
        double x, opacity;
        double midpoint = 0.5;   // where in the segment the value is halfway, in [0,1]
        double sharpness = 0.0;  // 0 = linear, 1 = a step at the midpoint
        bool operator==(const OpacityPoint&) const = default;
    };
    struct ColourPoint {
        double x, r, g, b;
        bool operator==(const ColourPoint&) const = default;
    };
    std::vector<OpacityPoint> opacity;  // strictly increasing x
    std::vector<ColourPoint> colour;    // strictly increasing x; empty -> white
    std::string colourSpace = "RGB";    // ParaView's name: RGB, HSV, Lab, Lab/CIEDE2000, Diverging, Step
    std::string name;
    std::string units;                  // of the x values, e.g. HU (the preset's "Units"); empty: not stated
    std::string description;            // what it shows (the preset's "Description")
    std::string json;                   // the source text, kept for the prepared file's metadata
    bool operator==(const TransferFunction&) const = default;

    // Single evaluations (each builds the VTK functions: use sample() for volumes).
    double opacityAt(double f) const;
    std::array<double, 3> colourAt(double f) const;

    // Throws InputError naming `source` when the points are empty, not finite, unsorted or out of [0,1].
    void validate(const std::string& source) const;
};

// The transfer function sampled at `count` evenly spaced values from `lo` to `hi` (inclusive; count >= 1).
struct SampledTransferFunction {
    double lo = 0, step = 1;
    std::vector<double> opacity;
    std::vector<std::array<float, 3>> colour;

    // Linear interpolation between samples, clamped at both ends (exact at the sample values).
    double opacityAt(double f) const;
    std::array<float, 3> colourAt(double f) const;
    // Index of the sample at or below f, and the weight of the next one (inline: classification calls it per voxel).
    void locate(double f, std::size_t& i, double& w) const {
        const double t = step == 1 ? f - lo : (f - lo) / step;  // the same value: integer volumes skip a division
        const std::size_t last = opacity.size() - 1;
        if (!(t > 0)) {  // also NaN
            i = 0, w = 0;
        } else if (t >= double(last)) {
            i = last, w = 0;
        } else {
            i = std::size_t(t);
            w = t - double(i);
        }
    }
};

SampledTransferFunction sampleTransferFunction(const TransferFunction& tf, double lo, double hi, std::size_t count);

// Reads ParaView's preset JSON ("Points": x, opacity, mid, sharp; "RGBPoints": x, r, g, b; a list of presets, of
// which the first is used, or one object; optional "Units" and "Description", which ParaView ignores). Throws
// InputError naming the file and the problem.
TransferFunction loadTransferFunction(const std::filesystem::path& path);
TransferFunction parseTransferFunction(const std::string& jsonText, const std::string& sourceName);
// x as printf's %g writes it (641.385, -3024, 1e+20): the transfer functions' values in names and messages.
std::string shortNumber(double x);

// `tf` as ParaView's preset JSON (a list of one preset), which parseTransferFunction reads back to the same points.
std::string paraViewJson(const TransferFunction& tf);

}  // namespace vr

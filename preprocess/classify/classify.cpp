#include "preprocess/classify/classify.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/errors.h"
#include "preprocess/classify/gradient.h"

namespace vr {
namespace {

// Smallest and largest value; NaN or infinity are an InputError naming `source`.
std::pair<float, float> valueRange(const std::vector<float>& values, const std::string& source) {
    struct Range {
        float lo = std::numeric_limits<float>::infinity(), hi = -std::numeric_limits<float>::infinity();
        bool finite = true;
    };
    const Range range = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, values.size()), Range{},
        [&](const tbb::blocked_range<std::size_t>& r, Range acc) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const float v = values[i];
                acc.finite = acc.finite && std::isfinite(v);
                acc.lo = std::min(acc.lo, v);
                acc.hi = std::max(acc.hi, v);
            }
            return acc;
        },
        [](Range a, Range b) { return Range{std::min(a.lo, b.lo), std::max(a.hi, b.hi), a.finite && b.finite}; });
    if (!range.finite) throw fileError(source, "the volume has non-finite values");
    return {range.lo, range.hi};
}

// Integer volumes get one exact sample per integer value (at most 65536 for 16-bit types);
// float volumes 65536 samples over their range, interpolated linearly.
SampledTransferFunction sampleForVolume(const TransferFunction& tf, const Volume& volume,
                                        std::pair<float, float> range) {
    constexpr std::size_t kFloatSamples = 65536;
    if (volume.sourceType == ScalarType::Float32) {
        const std::size_t count = range.first == range.second ? 1 : kFloatSamples;
        return sampleTransferFunction(tf, range.first, range.second, count);
    }
    const double lo = std::floor(range.first), hi = std::ceil(range.second);
    return sampleTransferFunction(tf, lo, hi, std::size_t(hi - lo) + 1);
}

void checkParams(const Volume& volume, const ClassifyParams& params, const std::string& source) {
    if (params.transferFunction.has_value() == !params.isoContours.empty())
        throw fileError(source, "classification needs either a transfer function or iso-contours (exactly one)");
    if (volume.grid.voxels() == 0 || volume.values.size() != volume.grid.voxels())
        throw fileError(source, "the volume is empty or its values do not match its dimensions");
    if (!(params.referenceStep >= 0) || !std::isfinite(params.referenceStep))
        throw fileError(source, "the reference step must be a finite number >= 0");
    if (!(params.flatGradientFloor >= 0)) throw fileError(source, "the flat-gradient floor must be >= 0");
    for (int a = 0; a < 3; ++a)
        if (!(volume.grid.spacing[a] > 0) || !std::isfinite(volume.grid.spacing[a]))
            throw fileError(source, "voxel spacing must be finite and > 0");
    if (params.transferFunction) {
        const TransferFunction& tf = *params.transferFunction;
        tf.validate(tf.name.empty() ? std::string("transfer function") : "transfer function " + tf.name);
    } else {
        validateIsoContours(params.isoContours, source);
        for (double c : params.isoColour)
            if (!(c >= 0 && c <= 1)) throw fileError(source, "iso-contour colour outside [0,1]");
    }
}

}  // namespace

ClassifiedVolume classify(const Volume& volume, const ClassifyParams& params) {
    const std::string source = volume.source.empty() ? std::string("classification") : volume.source;
    checkParams(volume, params, source);
    const bool useTF = params.transferFunction.has_value();

    ClassifiedVolume out;
    out.grid = volume.grid;
    out.referenceStep = params.referenceStep > 0 ? params.referenceStep : volume.grid.smallestSpacing();
    const std::size_t n = volume.grid.voxels();
    out.sigma.resize(n);
    out.colour.resize(n);
    if (params.normals) out.normal.resize(n);

    const auto range = valueRange(volume.values, source);
    const SampledTransferFunction table =
        useTF ? sampleForVolume(*params.transferFunction, volume, range) : SampledTransferFunction{};
    // At the table's samples (every voxel of an integer volume) sigma is looked up rather than recomputed.
    std::vector<float> sigmaAtSample(table.opacity.size());
    for (std::size_t k = 0; k < sigmaAtSample.size(); ++k)
        sigmaAtSample[k] = float(extinctionFromOpacity(table.opacity[k], out.referenceStep));
    const bool needGradient = params.normals || !useTF;
    const double flatFloor =
        params.flatGradientFloor * (double(range.second) - range.first) / volume.grid.smallestSpacing();
    const std::array<float, 3> isoColour{float(params.isoColour[0]), float(params.isoColour[1]),
                                         float(params.isoColour[2])};
    const Vec3i dims = volume.grid.dims;

    tbb::parallel_for(tbb::blocked_range<int>(0, dims.z), [&](const tbb::blocked_range<int>& zs) {
        for (int z = zs.begin(); z != zs.end(); ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) {
                    const std::size_t i = linearIndex(dims, x, y, z);
                    const double f = volume.values[i];
                    const Vec3d g = needGradient ? centralGradient(volume, x, y, z) : Vec3d{};
                    const double magnitude = length(g);
                    if (useTF) {
                        std::size_t k;
                        double w;
                        table.locate(f, k, w);
                        out.sigma[i] = w == 0 ? sigmaAtSample[k]
                                              : float(extinctionFromOpacity(table.opacityAt(f), out.referenceStep));
                        out.colour[i] = w == 0 ? table.colour[k] : table.colourAt(f);
                    } else {
                        const double alpha = levoyOpacity(params.isoContours, f, magnitude);
                        out.sigma[i] = float(extinctionFromOpacity(alpha, out.referenceStep));
                        out.colour[i] = isoColour;
                    }
                    if (params.normals) {
                        const bool flat = !(magnitude > flatFloor);
                        out.normal[i] = flat ? std::array<float, 3>{0, 0, 0}
                                             : std::array<float, 3>{float(g.x / magnitude), float(g.y / magnitude),
                                                                    float(g.z / magnitude)};
                    }
                }
    });
    return out;
}

}  // namespace vr

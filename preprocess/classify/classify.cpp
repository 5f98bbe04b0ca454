#include "preprocess/classify/classify.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "core/errors.h"
#include "core/gradient.h"
#include "shaders/transfer_lookup.h"

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

void checkVolume(const Volume& volume, const std::string& source) {
    if (volume.grid.voxels() == 0 || volume.values.size() != volume.grid.voxels())
        throw fileError(source, "the volume is empty or its values do not match its dimensions");
    for (int a = 0; a < 3; ++a)
        if (!(volume.grid.spacing[a] > 0) || !std::isfinite(volume.grid.spacing[a]))
            throw fileError(source, "voxel spacing must be finite and > 0");
}

// Integer volumes get one exact sample per integer value (at most 65536 for 16-bit types);
// float volumes 65536 samples over their range, interpolated linearly.
SampledTransferFunction sampleForRange(const TransferFunction& tf, const Volume& volume,
                                       std::pair<float, float> range) {
    constexpr std::size_t kFloatSamples = 65536;
    if (volume.sourceType == ScalarType::Float32) {
        const std::size_t count = range.first == range.second ? 1 : kFloatSamples;
        return sampleTransferFunction(tf, range.first, range.second, count);
    }
    const double lo = std::floor(range.first), hi = std::ceil(range.second);
    return sampleTransferFunction(tf, lo, hi, std::size_t(hi - lo) + 1);
}

std::string sourceName(const Volume& volume) {
    return volume.source.empty() ? std::string("classification") : volume.source;
}

void checkParams(const Volume& volume, const ClassifyParams& params, const std::string& source) {
    if (!params.transferFunction) throw fileError(source, "classification needs a transfer function");
    checkVolume(volume, source);
    if (!(params.referenceStep >= 0) || !std::isfinite(params.referenceStep))
        throw fileError(source, "the reference step must be a finite number >= 0");
    if (!(params.flatGradientFloor >= 0)) throw fileError(source, "the flat-gradient floor must be >= 0");
    const TransferFunction& tf = *params.transferFunction;
    tf.validate(tf.name.empty() ? std::string("transfer function") : "transfer function " + tf.name);
}

// One row of voxels (fixed y, z) at a time: the gradient of the whole row first (differences of whole rows, no
// per-voxel neighbour arithmetic), then the per-voxel lookups and normals.
class RowClassifier {
public:
    RowClassifier(const Volume& volume, const ScalarClassification& classification, bool normals,
                  ClassifiedVolume& out)
        : volume_(volume), table_(classification.table), normals_(normals), out_(out), dims_(volume.grid.dims),
          flatGradient_(classification.flatGradient) {}

    // Rows [begin, end) of the dims.y * dims.z rows, row r = (y = r % dims.y, z = r / dims.y).
    void operator()(std::size_t begin, std::size_t end) const {
        normals_ ? rows<true>(begin, end) : rows<false>(begin, end);
    }

private:
    template <bool kNormals>
    void rows(std::size_t begin, std::size_t end) const {
        const std::size_t nx = std::size_t(dims_.x);
        std::vector<double> gx(kNormals ? nx : 0), gy(gx.size()), gz(gx.size());
        for (std::size_t r = begin; r < end; ++r) {
            const int y = int(r % std::size_t(dims_.y)), z = int(r / std::size_t(dims_.y));
            const std::size_t row = linearIndex(dims_, 0, y, z);
            if constexpr (kNormals) rowGradient(y, z, gx, gy, gz);
            for (std::size_t x = 0; x < nx; ++x) {
                const std::size_t i = row + x;
                lookUp(volume_.values[i], i);
                if constexpr (kNormals) out_.normal[i] = unitNormal({gx[x], gy[x], gz[x]}, flatGradient_);
            }
        }
    }

    // The gradient of core/gradient.h along one row.
    void rowGradient(int y, int z, std::vector<double>& gx, std::vector<double>& gy, std::vector<double>& gz) const {
        centralGradientRun(volume_, 0, dims_.x, y, z, gx.data(), gy.data(), gz.data());
    }

    // sigma and colour as a nearest sample of scalar f takes them (shaders/transfer_lookup.h): an entry exactly
    // where f lies on one (every voxel of an integer volume), else interpolated between two.
    void lookUp(double f, std::size_t i) const {
        const device::TableSample s = device::lookUpTable(table_, f);
        out_.sigma[i] = float(s.sigma);
        out_.colour[i] = {float(s.colour[0]), float(s.colour[1]), float(s.colour[2])};
    }

    const Volume& volume_;
    const TransferTable& table_;
    const bool normals_;
    ClassifiedVolume& out_;
    const Vec3i dims_;
    const double flatGradient_;
};

}  // namespace

ScalarClassification scalarClassification(const Volume& volume, const ClassifyParams& params) {
    const std::string source = sourceName(volume);
    checkParams(volume, params, source);
    const auto range = valueRange(volume.values, source);
    const SampledTransferFunction sampled = sampleForRange(*params.transferFunction, volume, range);

    ScalarClassification c;
    c.referenceStep = params.referenceStep > 0 ? params.referenceStep : volume.grid.smallestSpacing();
    c.flatGradient = params.flatGradientFloor * (double(range.second) - range.first) / volume.grid.smallestSpacing();
    c.table.lo = sampled.lo;
    c.table.step = sampled.step;
    c.table.colour = sampled.colour;
    c.table.sigma.resize(sampled.opacity.size());
    for (std::size_t k = 0; k < sampled.opacity.size(); ++k) {
        c.table.sigma[k] = float(extinctionFromOpacity(sampled.opacity[k], c.referenceStep));
        if (!std::isfinite(c.table.sigma[k])) {
            char text[200];
            std::snprintf(text, sizeof text,
                          "the reference step %g (default: the smallest spacing) is too small: the extinction per "
                          "unit length overflows; check the voxel spacing",
                          c.referenceStep);
            throw fileError(source, text);
        }
    }
    return c;
}

void classify(const Volume& volume, const ScalarClassification& classification, bool normals, ClassifiedVolume& out) {
    const std::string source = sourceName(volume);
    checkVolume(volume, source);
    const TransferTable& table = classification.table;
    if (table.size() == 0 || table.colour.size() != table.size() || !(table.step > 0))
        throw fileError(source, "the transfer table is empty or inconsistent");

    out.grid = volume.grid;
    out.referenceStep = classification.referenceStep;
    const std::size_t n = volume.grid.voxels();
    if (!normals) out.normal = {};
    // The arrays are large: size them (and take their pages) side by side. Every element is written below.
    tbb::parallel_invoke([&] { out.sigma.resize(n); }, [&] { out.colour.resize(n); },
                         [&] { out.normal.resize(normals ? n : 0); });

    const RowClassifier classifyRows(volume, classification, normals, out);
    const std::size_t rows = std::size_t(volume.grid.dims.y) * std::size_t(volume.grid.dims.z);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows), [&](const tbb::blocked_range<std::size_t>& r) {
        classifyRows(r.begin(), r.end());
    });
}

SampledTransferFunction sampleForVolume(const Volume& volume, const TransferFunction& tf) {
    const std::string source = volume.source.empty() ? std::string("transfer table") : volume.source;
    return sampleForRange(tf, volume, valueRange(volume.values, source));
}

ClassifiedVolume classify(const Volume& volume, const ClassifyParams& params) {
    ClassifiedVolume out;
    classify(volume, scalarClassification(volume, params), params.normals, out);
    return out;
}

}  // namespace vr

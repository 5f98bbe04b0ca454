#include "preprocess/classify/classify.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/errors.h"

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

// One row of voxels (fixed y, z) at a time: the gradient of the whole row first (differences of whole rows, no
// per-voxel neighbour arithmetic), then the per-voxel lookups and normals.
class RowClassifier {
public:
    RowClassifier(const Volume& volume, const ClassifyParams& params, std::pair<float, float> range,
                  ClassifiedVolume& out)
        : volume_(volume), params_(params), out_(out), dims_(volume.grid.dims),
          useTF_(params.transferFunction.has_value()), needGradient_(params.normals || !useTF_),
          flatFloor_(params.flatGradientFloor * (double(range.second) - range.first) / volume.grid.smallestSpacing()),
          isoColour_{float(params.isoColour[0]), float(params.isoColour[1]), float(params.isoColour[2])} {
        if (useTF_) table_ = sampleForVolume(*params.transferFunction, volume, range);
        // At the table's samples (every voxel of an integer volume) sigma is looked up rather than recomputed.
        sigmaAtSample_.resize(table_.opacity.size());
        for (std::size_t k = 0; k < sigmaAtSample_.size(); ++k)
            sigmaAtSample_[k] = float(extinctionFromOpacity(table_.opacity[k], out.referenceStep));
    }

    // Rows [begin, end) of the dims.y * dims.z rows, row r = (y = r % dims.y, z = r / dims.y).
    void operator()(std::size_t begin, std::size_t end) const {
        if (useTF_) {
            params_.normals ? rows<true, true>(begin, end) : rows<true, false>(begin, end);
        } else {
            params_.normals ? rows<false, true>(begin, end) : rows<false, false>(begin, end);
        }
    }

private:
    // The choices made once, not per voxel: transfer function or iso-contours, normals or none.
    template <bool kTF, bool kNormals>
    void rows(std::size_t begin, std::size_t end) const {
        const std::size_t nx = std::size_t(dims_.x);
        std::vector<double> gx(needGradient_ ? nx : 0), gy(gx.size()), gz(gx.size());
        for (std::size_t r = begin; r < end; ++r) {
            const int y = int(r % std::size_t(dims_.y)), z = int(r / std::size_t(dims_.y));
            const std::size_t row = linearIndex(dims_, 0, y, z);
            if (needGradient_) rowGradient(y, z, gx, gy, gz);
            for (std::size_t x = 0; x < nx; ++x) {
                const std::size_t i = row + x;
                const double f = volume_.values[i];
                if constexpr (kTF) {
                    lookUp(f, i);
                    if constexpr (!kNormals) continue;
                }
                const Vec3d g{gx[x], gy[x], gz[x]};
                const double magnitude = length(g);
                if constexpr (!kTF) {
                    const double alpha = levoyOpacity(params_.isoContours, f, magnitude);
                    out_.sigma[i] = float(extinctionFromOpacity(alpha, out_.referenceStep));
                    out_.colour[i] = isoColour_;
                }
                if constexpr (kNormals) {
                    const bool flat = !(magnitude > flatFloor_);
                    out_.normal[i] = flat ? std::array<float, 3>{0, 0, 0}
                                          : std::array<float, 3>{float(g.x / magnitude), float(g.y / magnitude),
                                                                 float(g.z / magnitude)};
                }
            }
        }
    }

    // The gradient of gradient.h (centralGradient) along one row: the same operations in the same order.
    void rowGradient(int y, int z, std::vector<double>& gx, std::vector<double>& gy, std::vector<double>& gz) const {
        const Vec3d& h = volume_.grid.spacing;
        const float* row = &volume_.values[linearIndex(dims_, 0, y, z)];
        const int nx = dims_.x;
        if (nx < 2) {
            gx[0] = 0;
        } else {
            const double inner = 2 * h.x, edge = 1 * h.x;
            gx[0] = (double(row[1]) - double(row[0])) / edge;
            for (int x = 1; x < nx - 1; ++x) gx[x] = (double(row[x + 1]) - double(row[x - 1])) / inner;
            gx[nx - 1] = (double(row[nx - 1]) - double(row[nx - 2])) / edge;
        }
        alongRows(gy, dims_.y, y, h.y, [&](int w) { return &volume_.values[linearIndex(dims_, 0, w, z)]; });
        alongRows(gz, dims_.z, z, h.z, [&](int w) { return &volume_.values[linearIndex(dims_, 0, y, w)]; });
    }

    // Derivative along y or z (axis length n, this row at v, spacing h): the difference of two whole rows.
    template <typename RowAt>
    void alongRows(std::vector<double>& g, int n, int v, double h, RowAt rowAt) const {
        if (n < 2) {
            std::fill(g.begin(), g.end(), 0.0);
            return;
        }
        const int lo = std::max(v - 1, 0), hi = std::min(v + 1, n - 1);
        const double span = (hi - lo) * h;
        const float *a = rowAt(lo), *b = rowAt(hi);
        for (std::size_t x = 0; x < g.size(); ++x) g[x] = (double(b[x]) - double(a[x])) / span;
    }

    // sigma and colour from the sampled TF: exact samples are looked up, values between them interpolated.
    void lookUp(double f, std::size_t i) const {
        std::size_t k;
        double w;
        table_.locate(f, k, w);
        if (w == 0) {
            out_.sigma[i] = sigmaAtSample_[k];
            out_.colour[i] = table_.colour[k];
        } else {
            out_.sigma[i] = float(extinctionFromOpacity(table_.opacityAt(f), out_.referenceStep));
            out_.colour[i] = table_.colourAt(f);
        }
    }

    const Volume& volume_;
    const ClassifyParams& params_;
    ClassifiedVolume& out_;
    const Vec3i dims_;
    const bool useTF_, needGradient_;
    const double flatFloor_;
    const std::array<float, 3> isoColour_;
    SampledTransferFunction table_;
    std::vector<float> sigmaAtSample_;
};

}  // namespace

void classify(const Volume& volume, const ClassifyParams& params, ClassifiedVolume& out) {
    const std::string source = volume.source.empty() ? std::string("classification") : volume.source;
    checkParams(volume, params, source);
    const auto range = valueRange(volume.values, source);

    out.grid = volume.grid;
    out.referenceStep = params.referenceStep > 0 ? params.referenceStep : volume.grid.smallestSpacing();
    const std::size_t n = volume.grid.voxels();
    if (!params.normals) out.normal = {};
    // The arrays are large: size them (and take their pages) side by side. Every element is written below.
    tbb::parallel_invoke([&] { out.sigma.resize(n); }, [&] { out.colour.resize(n); },
                         [&] { out.normal.resize(params.normals ? n : 0); });

    const RowClassifier classifyRows(volume, params, range, out);
    const std::size_t rows = std::size_t(volume.grid.dims.y) * std::size_t(volume.grid.dims.z);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows), [&](const tbb::blocked_range<std::size_t>& r) {
        classifyRows(r.begin(), r.end());
    });
}

SampledTransferFunction transferTable(const Volume& volume, const TransferFunction& tf) {
    const std::string source = volume.source.empty() ? std::string("transfer table") : volume.source;
    return sampleForVolume(tf, volume, valueRange(volume.values, source));
}

ClassifiedVolume classify(const Volume& volume, const ClassifyParams& params) {
    ClassifiedVolume out;
    classify(volume, params, out);
    return out;
}

}  // namespace vr

// How a label map joins the transfer function (docs/ALGORITHMS.md section 2, label maps), stated once: the CPU
// reference and segmentation read this file in double, the casters in float (shared_language.h). A sample takes
// the label of its own voxel, never one interpolated between labels; its label's entry (rgb colour, extinction
// sigma) adds to what the transfer function gives its scalar.
#ifndef VR_LABEL_LOOKUP_H
#define VR_LABEL_LOOKUP_H

#include "shared_language.h"

#ifdef __cplusplus
#include <algorithm>
#include <cstddef>

#include "core/vec3.h"
namespace vr::device {
#endif

// The two media mixed: extinctions add, and the colour is their colours weighted by extinction. Exactly the
// transfer function's where the label adds nothing, exactly the label's where the transfer function is clear.
VR_FUNCTION VR_REAL labelledSigma(VR_REAL sigma, VR_REAL labelSigma) { return sigma + labelSigma; }
VR_FUNCTION VR_REAL labelledChannel(VR_REAL sigma, VR_REAL channel, VR_REAL labelSigma, VR_REAL labelChannel) {
    if (!(labelSigma > VR_REAL(0))) return channel;
    if (!(sigma > VR_REAL(0))) return labelChannel;
    return (sigma * channel + labelSigma * labelChannel) / (sigma + labelSigma);
}

// Whether a label shapes its voxels' normals: one that shows (its extinction above 0) shades by the gradient of its
// smoothed indicator (1 on its voxels, 0 elsewhere), so that its surface shades smoothly and not as the staircase
// of its voxels; the other voxels shade by the scalars' gradient.
VR_FUNCTION bool labelShapesNormal(VR_REAL labelSigma) { return labelSigma > VR_REAL(0); }

// The indicator is smoothed across each derivative's axis by the binomial [1 2 1] / 4 along each of the other two
// axes (a Sobel-Feldman operator in 3D): the weight of the neighbour at offset -1, 0 or +1, and the weights' sum
// over the 3 x 3 neighbours of a row.
VR_FUNCTION VR_REAL indicatorWeight(int offset) { return offset == 0 ? VR_REAL(2) : VR_REAL(1); }
VR_CONSTANT int kIndicatorWeightSum = 16;

// The last entry of a label table of `entries` labels that a stored label looks up (a label past it, which a
// validated map never holds, takes the last).
VR_FUNCTION int labelEntry(int label, int lastEntry) { return label < lastEntry ? label : lastEntry; }

#ifdef __cplusplus
// The class entry (core/label_map.h LabelClasses) of voxel i of a label map, and that class's extinction, in double:
// what the CPU reference and segmentation read where the casters read the label table buffer.
template <typename Map>
std::size_t labelClassOf(const Map& map, std::size_t i) {
    return std::size_t(labelEntry(int(map.label[i]), map.lastEntry()));
}
template <typename Map>
double labelSigmaOf(const Map& map, std::size_t i) {
    return map.classes.sigma[labelClassOf(map, i)];
}

// The gradient of label l's smoothed indicator at voxel v of a grid of `dims` voxels spaced `spacing` (`labels` x
// fastest): central differences, one-sided at the border, 0 across an axis of one voxel, each of the differences
// across the axis weighted by indicatorWeight() over the 3 x 3 neighbours, clamped into the grid. In double; the
// casters' indicatorGradient in caster.comp.
template <typename Labels>
Vec3d indicatorGradient(const Labels& labels, const Vec3i& dims, const Vec3d& spacing, const Vec3i& v, int l) {
    Vec3d g;
    for (int a = 0; a < 3; ++a) {
        const int lo = std::max(v[a] - 1, 0), hi = std::min(v[a] + 1, dims[a] - 1);
        if (hi == lo) continue;
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        double sum = 0;
        for (int ob = -1; ob <= 1; ++ob)
            for (int oc = -1; oc <= 1; ++oc) {
                Vec3i p = v;
                p[b] = std::clamp(v[b] + ob, 0, dims[b] - 1);
                p[c] = std::clamp(v[c] + oc, 0, dims[c] - 1);
                Vec3i pl = p, ph = p;
                pl[a] = lo;
                ph[a] = hi;
                const double inHi = int(labels[linearIndex(dims, ph.x, ph.y, ph.z)]) == l ? 1 : 0;
                const double inLo = int(labels[linearIndex(dims, pl.x, pl.y, pl.z)]) == l ? 1 : 0;
                sum += indicatorWeight(ob) * indicatorWeight(oc) * (inHi - inLo);
            }
        g[a] = sum / (double(kIndicatorWeightSum) * double(hi - lo) * spacing[a]);
    }
    return g;
}
#endif

#ifdef __cplusplus
}  // namespace vr::device
#endif

#endif

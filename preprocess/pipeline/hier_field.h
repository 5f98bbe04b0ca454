// The hierarchical EACD (docs/ALGORITHMS.md section 10), built from the scalars and their classification alone: no
// per-voxel segmentation.
#pragma once
#include "core/prepared_volume.h"

namespace vr {

// The coarse level over blocks of 2^blockShift voxels (4 or 8 per axis) of a classified volume: each block's
// scalar range over its voxels and their trilinear footprints (render/block_extrema.h), the classification's spread
// over that range, the homogeneous blocks grown into regions and the EACD over them, in the octants of the mask.
// `params`: T_o and whether normals are in use. Throws InputError for a volume with a label map (its labels, not the
// scalars, would decide what a block holds) or a bad threshold.
BlockEACD buildHierarchicalEACD(const PreparedVolume& classified, const SegmentationParams& params,
                                unsigned octants = kAllOctants, int blockShift = kHierBlockShift);

}  // namespace vr

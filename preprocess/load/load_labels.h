// Loading a label map beside a volume (docs/ALGORITHMS.md section 2, label maps): any file loadVolume reads, with
// integer labels on the volume's grid.
#pragma once
#include <filesystem>

#include "core/label_map.h"

namespace vr {

// The largest label a map may hold: the device and the prepared file hold labels in 16 bits.
constexpr int kMaxLabel = 65535;

// The labels of `path` (loadVolume's formats; a headerless raw map takes the grid's spacing), type UInt8 where every
// label is below 256, else UInt16; colours and classes empty (label_colours.h gives them). Throws InputError naming
// `flag` and the file: a grid other than `grid` (its dims or spacing), a label that is not an integer in
// 0..kMaxLabel (the first such voxel named), or what loadVolume refuses.
LabelMap loadLabelMap(const std::filesystem::path& path, const GridGeometry& grid, const char* flag);

}  // namespace vr

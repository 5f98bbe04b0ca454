// A label map beside the scalars (docs/ALGORITHMS.md section 2, label maps): an integer label per voxel on the
// scalars' grid and what each label shows, mixed with the transfer function as shaders/label_lookup.h says.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "grid.h"
#include "scalar_classification.h"
#include "vec3.h"
#include "volume.h"

namespace vr {

// What each label 0 .. size()-1 shows, classified for a reference step: a transfer table over the label (lo 0,
// step 1), whose entry l holds label l's extinction and colour; a label is looked up at its entry, never between two.
using LabelClasses = TransferTable;

struct LabelMap {
    std::vector<uint16_t> label;  // per voxel, x fastest, as the scalars
    ScalarType type = ScalarType::UInt8;  // how the prepared file and the device hold them: UInt8 or UInt16
    // What each label up to the largest the map holds shows, as a colour table gives it: r, g, b and opacity per
    // reference step, 0..255 (empty once read back from a prepared file, which holds the classes).
    std::vector<std::array<uint8_t, 4>> rgba;
    LabelClasses classes;  // rgba classified for the transfer function's reference step
    std::string source;       // the label map's path
    std::string colourTable;  // the colour table's path; empty: the default palette

    int lastEntry() const { return int(classes.size()) - 1; }
};

}  // namespace vr

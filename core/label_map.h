// A label map beside the scalars (docs/ALGORITHMS.md section 2, label maps): an integer label per voxel on the
// scalars' grid and what each label shows, mixed with the transfer function as shaders/label_lookup.h says.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "grid.h"
#include "vec3.h"
#include "volume.h"

namespace vr {

// What each label 0 .. size()-1 shows, classified for a reference step: its extinction and its colour.
struct LabelClasses {
    std::vector<float> sigma;                  // extinction per world unit
    std::vector<std::array<float, 3>> colour;  // linear RGB in [0, 1]

    std::size_t size() const { return sigma.size(); }
    // The entries as four floats each, r, g, b, sigma: the prepared file's chunk and the device's buffer.
    std::vector<float> interleaved() const {
        std::vector<float> out;
        out.reserve(4 * size());
        for (std::size_t i = 0; i < size(); ++i)
            out.insert(out.end(), {colour[i][0], colour[i][1], colour[i][2], sigma[i]});
        return out;
    }
    bool operator==(const LabelClasses&) const = default;
};

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

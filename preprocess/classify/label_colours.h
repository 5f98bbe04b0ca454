// What each label of a label map shows (docs/ALGORITHMS.md section 2, label maps): a colour table in 3D Slicer's
// text format, or the default palette, and the labels' extinctions for a reference step.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/label_map.h"

namespace vr {

// 3D Slicer's colour table: a line `index name r g b a` per label, each of r, g, b, a 0..255 (a: opacity per
// reference step), '#' starting a comment line.
struct LabelColourTable {
    std::map<int, std::array<uint8_t, 4>> rgba;  // by label
    std::string source;
};

// Throws InputError naming `flag`, the file and the line: a line that is not `index name r g b a`, an index outside
// 0..65535 or given twice, a value outside 0..255, or a table without any entry.
LabelColourTable readLabelColourTable(const std::filesystem::path& path, const char* flag);

// The default palette: label 0 (background) clear, every other label a colour of a ten-colour cycle at opacity 204
// (0.8 per reference step).
std::array<uint8_t, 4> defaultLabelColour(int label);

// The colours of labels 0 .. the largest of `map`, from `table` (the default palette without one). Throws
// InputError naming `flag` and the table for labels the map holds that the table lacks (listed, the first few).
std::vector<std::array<uint8_t, 4>> labelColours(const LabelMap& map, const LabelColourTable* table, const char* flag);

// The classes of colours `rgba`: each label's extinction per world unit for its opacity per `referenceStep`, and its
// colour in [0, 1].
LabelClasses classifyLabels(const std::vector<std::array<uint8_t, 4>>& rgba, double referenceStep);

}  // namespace vr

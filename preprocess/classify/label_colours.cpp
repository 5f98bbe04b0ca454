#include "preprocess/classify/label_colours.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "core/errors.h"
#include "core/printable_text.h"
#include "core/scalar_classification.h"

namespace vr {

LabelColourTable readLabelColourTable(const std::filesystem::path& path, const char* flag) {
    const std::string where = std::string(flag) + " " + path.string();
    std::ifstream in(path);
    if (!in) throw InputError(where + ": cannot open the colour table");
    LabelColourTable table;
    table.source = path.string();
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        std::istringstream fields(line);
        long long index = 0, r = 0, g = 0, b = 0, a = 0;
        std::string name, extra;
        const std::string at = where + " line " + std::to_string(number);
        if (!(fields >> index >> name >> r >> g >> b >> a) || (fields >> extra))
            throw InputError(at + ": expected 'index name r g b a' (3D Slicer's colour table), got '" + printableText(line, 80) + "'");
        if (index < 0 || index > 65535)
            throw InputError(at + ": label " + std::to_string(index) + " is outside 0..65535");
        for (long long value : {r, g, b, a})
            if (value < 0 || value > 255)
                throw InputError(at + ": colour and opacity must be 0..255, got " + std::to_string(value));
        if (!table.rgba.emplace(int(index), std::array<uint8_t, 4>{uint8_t(r), uint8_t(g), uint8_t(b), uint8_t(a)})
                 .second)
            throw InputError(at + ": label " + std::to_string(index) + " is given twice");
    }
    if (table.rgba.empty()) throw InputError(where + ": the colour table holds no label");
    return table;
}

std::array<uint8_t, 4> defaultLabelColour(int label) {
    // Tableau's ten categorical colours: neighbours in the cycle stay apart.
    static constexpr std::array<std::array<uint8_t, 3>, 10> kCycle{{{31, 119, 180},
                                                                    {255, 127, 14},
                                                                    {44, 160, 44},
                                                                    {214, 39, 40},
                                                                    {148, 103, 189},
                                                                    {140, 86, 75},
                                                                    {227, 119, 194},
                                                                    {127, 127, 127},
                                                                    {188, 189, 34},
                                                                    {23, 190, 207}}};
    if (label == 0) return {0, 0, 0, 0};
    const auto& c = kCycle[std::size_t(label - 1) % kCycle.size()];
    return {c[0], c[1], c[2], 204};
}

std::vector<std::array<uint8_t, 4>> labelColours(const LabelMap& map, const LabelColourTable* table, const char* flag) {
    std::vector<bool> present(std::size_t(1) << 16, false);  // every uint16_t label
    int largest = 0;
    for (uint16_t l : map.label) {
        present[l] = true;
        largest = std::max<int>(largest, l);
    }
    std::vector<std::array<uint8_t, 4>> rgba;
    std::vector<int> missing;
    for (int l = 0; l <= largest; ++l) {
        if (!table) {
            rgba.push_back(defaultLabelColour(l));
            continue;
        }
        const auto it = table->rgba.find(l);
        if (it == table->rgba.end() && present[std::size_t(l)]) missing.push_back(l);
        rgba.push_back(it != table->rgba.end() ? it->second : std::array<uint8_t, 4>{0, 0, 0, 0});
    }
    if (!missing.empty()) {
        std::string list;
        for (std::size_t i = 0; i < missing.size() && i < 10; ++i) list += (i ? ", " : "") + std::to_string(missing[i]);
        if (missing.size() > 10) list += ", ... (" + std::to_string(missing.size()) + " in all)";
        throw InputError(std::string(flag) + " " + table->source + ": the label map " + map.source +
                         " holds labels the colour table lacks: " + list);
    }
    return rgba;
}

LabelClasses classifyLabels(const std::vector<std::array<uint8_t, 4>>& rgba, double referenceStep) {
    LabelClasses classes;
    for (const auto& c : rgba) {
        classes.sigma.push_back(float(extinctionFromOpacity(c[3] / 255.0, referenceStep)));
        classes.colour.push_back({float(c[0] / 255.0), float(c[1] / 255.0), float(c[2] / 255.0)});
    }
    return classes;
}

}  // namespace vr

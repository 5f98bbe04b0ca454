#include "preprocess/classify/transfer_presets.h"

#include <algorithm>
#include <cctype>

#include "preprocess/classify/embedded_presets.h"

namespace vr {
namespace {

bool sameIgnoringCase(const std::string& a, const std::string& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](unsigned char x, unsigned char y) { return std::tolower(x) == std::tolower(y); });
}

// Where the opacity is above 0, from the points (clamped beyond the ends): "above 150", "between -600 and -399".
std::string visibleValues(const TransferFunction& tf) {
    const auto& p = tf.opacity;
    const auto positive = [](const TransferFunction::OpacityPoint& q) { return q.opacity > 0; };
    const auto first = std::find_if(p.begin(), p.end(), positive);
    if (first == p.end()) return "nowhere";
    const auto last = std::find_if(p.rbegin(), p.rend(), positive).base() - 1;
    const bool boundedBelow = first != p.begin(), boundedAbove = last + 1 != p.end();
    if (boundedBelow && boundedAbove)
        return "between " + shortNumber((first - 1)->x) + " and " + shortNumber((last + 1)->x);
    if (boundedBelow) return "above " + shortNumber((first - 1)->x);
    if (boundedAbove) return "below " + shortNumber((last + 1)->x);
    return "everywhere";
}

// The values the points span, opacity and colour together.
std::pair<double, double> pointSpan(const TransferFunction& tf) {
    double lowest = tf.opacity.front().x, highest = tf.opacity.back().x;
    if (tf.colour.empty()) return {lowest, highest};
    return {std::min(lowest, tf.colour.front().x), std::max(highest, tf.colour.back().x)};
    return {lowest, highest};
}

}  // namespace

const std::vector<TransferFunction>& transferPresets() {
    static const std::vector<TransferFunction> presets = [] {
        std::vector<TransferFunction> parsed;
        for (const EmbeddedFile& file : embeddedPresetFiles())
            parsed.push_back(
                parseTransferFunction(std::string(file.text), "built-in preset " + std::string(file.name)));
        return parsed;
    }();
    return presets;
}

const TransferFunction* findTransferPreset(const std::string& name) {
    for (const TransferFunction& preset : transferPresets())
        if (sameIgnoringCase(preset.name, name)) return &preset;
    return nullptr;
}

std::string transferPresetNames() {
    std::string names;
    for (const TransferFunction& preset : transferPresets()) names += (names.empty() ? "" : ", ") + preset.name;
    return names;
}

std::string transferPresetListing() {
    std::size_t width = 0;
    for (const TransferFunction& preset : transferPresets()) width = std::max(width, preset.name.size());
    std::string listing;
    for (const TransferFunction& preset : transferPresets()) {
        const auto [lowest, highest] = pointSpan(preset);
        listing += preset.name + std::string(width + 2 - preset.name.size(), ' ') + shortNumber(lowest) + " .. " +
                   shortNumber(highest) + " " + preset.units + ", visible " + visibleValues(preset) + ": " +
                   preset.description + "\n";
    }
    return listing;
}

}  // namespace vr

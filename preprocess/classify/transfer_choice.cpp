#include "preprocess/classify/transfer_choice.h"

#include <cmath>
#include <filesystem>

#include "core/errors.h"
#include "preprocess/classify/transfer_presets.h"

namespace vr {
TransferFunction namedTransferFunction(const std::string& presetOrFile) {
    if (const TransferFunction* preset = findTransferPreset(presetOrFile)) return *preset;
    if (!std::filesystem::exists(presetOrFile))
        throw InputError("--tf " + presetOrFile + ": no such file, nor a built-in preset of that name (the presets: " +
                         transferPresetNames() + "; --list-presets describes them)");
    return loadTransferFunction(presetOrFile);
}

TransferFunction windowLevelTransferFunction(double window, double level, const TransferFunction* colours) {
    const double lowest = level - window / 2, highest = level + window / 2;
    TransferFunction tf;
    tf.opacity = {{lowest, 0.0}, {highest, 1.0}};
    if (colours) {
        tf.colour = colours->colour;
        tf.colourSpace = colours->colourSpace;
        tf.units = colours->units;
    } else {
        tf.colour = {{lowest, 0, 0, 0}, {highest, 1, 1, 1}};
    }
    tf.name = (colours && !colours->name.empty() ? colours->name + ", " : "") + "window " + shortNumber(window) +
              " level " + shortNumber(level);
    tf.description = "opacity rising linearly from " + shortNumber(lowest) + " to " + shortNumber(highest);
    tf.json = paraViewJson(tf);
    return tf;
}

TransferFunction chooseTransferFunction(const TransferChoice& choice) {
    if (choice.empty())
        throw InputError("no transfer function given: --tf PRESET or --tf FILE.json, or --window W --level L");
    if (choice.window.has_value() != choice.level.has_value())
        throw InputError(choice.window ? "--window needs --level (the value at the middle of the window)"
                                       : "--level needs --window (the width of the window)");
    if (!choice.window) return namedTransferFunction(choice.tf);
    const double window = *choice.window, level = *choice.level;
    if (!(window > 0) || !std::isfinite(window))
        throw InputError("--window " + shortNumber(window) + ": the window must be a finite number above 0");
    if (!std::isfinite(level))
        throw InputError("--level " + shortNumber(level) + ": the level must be a finite number");
    // Far from 0 a window below the spacing of doubles there, or one past the largest double, has no two ends.
    if (!(level - window / 2 < level + window / 2) || !std::isfinite(level + window / 2) ||
        !std::isfinite(level - window / 2))
        throw InputError("--window " + shortNumber(window) + " --level " + shortNumber(level) +
                         ": the window's ends are not two distinct finite numbers");
    if (choice.tf.empty()) return windowLevelTransferFunction(window, level, nullptr);
    const TransferFunction colours = namedTransferFunction(choice.tf);
    return windowLevelTransferFunction(window, level, &colours);
}

}  // namespace vr

// Checks on a prepared volume's classification and label classes, shared by the prepared file's writer and reader.
// Internal to io/.
#pragma once
#include <optional>
#include <string>

#include "core/prepared_volume.h"

namespace vr::prepared_detail {

// A stored value as the messages show it: every digit a float needs (core/number_text.h rounds a flag to 6).
std::string floatText(double v);

// What is wrong with a table's entries (a renderer takes exp(-sigma L) and blends the colours), if anything.
std::optional<std::string> tableEntryProblem(const TransferTable& t);

// What is wrong with a label map's classes (a renderer adds their sigma and blends their colours), if anything.
std::optional<std::string> labelClassProblem(const LabelClasses& c);

// What is wrong with the classification's numbers (the header's referenceStep, flatGradient and transferTable),
// if anything: the writer refuses what the reader would.
std::optional<std::string> classificationProblem(const ScalarClassification& c);

}  // namespace vr::prepared_detail

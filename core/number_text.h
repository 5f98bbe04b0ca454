// A number in a message as a user would type it: 0.5, not 0.500000; 0, not -0; six significant digits at most.
#pragma once
#include <cstdio>
#include <string>

namespace vr {

inline std::string numberText(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x + 0.0);
    return text;
}

}  // namespace vr

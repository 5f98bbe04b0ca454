// The CIEDE2000 colour difference, exactly as in Sharma, Wu and Dalal, "The CIEDE2000 Color-Difference Formula:
// Implementation Notes, Supplementary Test Data, and Mathematical Observations" (Color Res. Appl. 30, 2005).
#pragma once
#include "sweep/metrics/colour.h"

namespace vr {

// kL = kC = kH = 1 (the reference conditions).
double ciede2000(const Lab& lab1, const Lab& lab2);

}  // namespace vr

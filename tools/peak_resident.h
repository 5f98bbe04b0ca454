// The process's peak resident memory, as /proc reports it: what the tools' statistics and the benchmarks quote.
#pragma once
#include <cstddef>

namespace vr {

// Peak resident set size in bytes (VmHWM of /proc/self/status); 0 where /proc does not say.
std::size_t peakResidentBytes();
// Resets the peak to the current resident size (Linux 4.0 and later), so that a part of a run can be measured.
void resetPeakResident();

}  // namespace vr

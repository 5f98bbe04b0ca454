#include "tools/peak_resident.h"

#include <fstream>
#include <string>

namespace vr {

std::size_t peakResidentBytes() {
    std::ifstream status("/proc/self/status");
    std::string key;
    std::size_t kB = 0;
    while (status >> key)
        if (key == "VmHWM:" && status >> kB) return kB * 1024;
    return 0;
}

void resetPeakResident() { std::ofstream("/proc/self/clear_refs") << "5"; }

}  // namespace vr

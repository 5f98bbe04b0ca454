#include "volrender/cmd/process_timeline.h"

#include <chrono>
#include <map>
#include <mutex>

namespace vr {
namespace {

const std::chrono::steady_clock::time_point processStart = std::chrono::steady_clock::now();
std::mutex milestonesMutex;
std::map<std::string, double> milestones;

}  // namespace

void markMilestone(const std::string& milestone) {
    const std::chrono::duration<double, std::milli> since = std::chrono::steady_clock::now() - processStart;
    const std::lock_guard lock(milestonesMutex);
    milestones.try_emplace(milestone, since.count());
}

nlohmann::json processTimeline() {
    const std::lock_guard lock(milestonesMutex);
    return milestones;
}

}  // namespace vr

#include "preprocess/pipeline/stage_time.h"

#include <sys/resource.h>

namespace vr {
namespace {

double processCpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(u.ru_utime) + seconds(u.ru_stime);
}

}  // namespace

StageClock::StageClock() : wall_(std::chrono::steady_clock::now()), cpu_(processCpuSeconds()) {}

StageTime StageClock::stop(std::string stage) const {
    return {std::move(stage), std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_).count(),
            processCpuSeconds() - cpu_};
}

}  // namespace vr

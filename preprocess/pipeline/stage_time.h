// What each stage of the pipeline costs, and the progress bar volprep shows while it runs.
#pragma once
#include <chrono>
#include <string>
#include <type_traits>
#include <vector>

#include "tools/progress.h"

namespace vr {

struct StageTime {
    std::string stage;   // load, classify, segment, acd, pc, eacd, write
    double seconds;      // wall time
    double cpuSeconds;   // CPU time of the whole process (all threads) meanwhile: steadier on a shared machine
};

// Measures a stage from construction to stop(): wall time and this process's CPU time.
class StageClock {
public:
    StageClock();
    StageTime stop(std::string stage) const;

private:
    std::chrono::steady_clock::time_point wall_;
    double cpu_;
};

// Runs `work` as the stage `name` with a progress bar (shown on a terminal only), appends its time to `times` and
// returns what `work` returns. A stage that throws appends nothing. `work` takes no argument, or the bar's Progress
// (core/progress.h) to report how far it has come.
template <typename Work>
auto runStage(const std::string& name, std::vector<StageTime>& times, Work&& work) {
    ProgressBar bar(name, 1);
    const StageClock clock;
    auto done = [&] {
        times.push_back(clock.stop(name));
        bar.finish();
    };
    auto run = [&] {
        if constexpr (std::is_invocable_v<Work, const Progress&>)
            return work(bar.report());
        else
            return work();
    };
    if constexpr (std::is_void_v<decltype(run())>) {
        run();
        done();
    } else {
        auto result = run();
        done();
        return result;
    }
}

}  // namespace vr

// A progress bar on stderr for long stages; silent when stderr is not a terminal (CI logs, tests), or everywhere in
// the process once silenced (the tools' --quiet).
#pragma once
#include <atomic>
#include <cstddef>
#include <string>

#include "core/progress.h"

namespace vr {

class ProgressBar {
public:
    ProgressBar(std::string label, std::size_t total);
    ~ProgressBar();
    void advance(std::size_t n = 1);  // thread-safe
    void show(double fraction);       // thread-safe: the bar at that fraction of its total
    Progress report() { return [this](double fraction) { show(fraction); }; }  // valid while the bar lives
    void finish();
    // From now on no bar of this process draws.
    static void silenceAll();

private:
    void draw(std::size_t done);
    void drawPercent(int percent);
    std::string label_;
    std::size_t total_;
    std::atomic<std::size_t> done_{0};
    std::atomic<int> lastPercent_{-1};
    bool enabled_;
    bool finished_ = false;
};

}  // namespace vr

#include "tools/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace vr {
namespace {

std::atomic<bool> silenced{false};

}  // namespace

void ProgressBar::silenceAll() { silenced = true; }

ProgressBar::ProgressBar(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total ? total : 1), enabled_(!silenced && ::isatty(STDERR_FILENO)) {
    draw(0);
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::advance(std::size_t n) { draw(done_.fetch_add(n) + n); }

void ProgressBar::show(double fraction) { drawPercent(int(100.0 * (fraction > 0 ? std::min(fraction, 1.0) : 0.0))); }

void ProgressBar::finish() {
    if (finished_) return;
    finished_ = true;
    draw(total_);
    if (enabled_) std::fputc('\n', stderr);
}

void ProgressBar::draw(std::size_t done) { drawPercent(int(100.0 * double(std::min(done, total_)) / double(total_))); }

void ProgressBar::drawPercent(int percent) {
    if (!enabled_) return;
    // Redraw only when the percentage changes, and let one thread win the race to do it.
    int last = lastPercent_.load();
    if (percent <= last || !lastPercent_.compare_exchange_strong(last, percent)) return;
    constexpr int width = 40;
    int filled = percent * width / 100;
    std::fprintf(stderr, "\r%-12s [%.*s%*s] %3d%%", label_.c_str(), filled,
                 "========================================", width - filled, "", percent);
    std::fflush(stderr);
}

}  // namespace vr

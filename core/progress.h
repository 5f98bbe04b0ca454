// How far a long algorithm has come, for whoever shows it (tools/progress.h's bar): called with the fraction of the
// work done, 0 to 1, from any thread. An empty one means nobody listens.
#pragma once
#include <functional>

namespace vr {

using Progress = std::function<void(double fraction)>;

// The stretch [from, to] of `whole` that one step of the work covers: the step's fraction f is reported as
// from + (to - from) f.
inline Progress progressPart(const Progress& whole, double from, double to) {
    if (!whole) return {};
    return [whole, from, to](double f) { whole(from + (to - from) * f); };
}

inline void reportProgress(const Progress& progress, double fraction) {
    if (progress) progress(fraction);
}

}  // namespace vr

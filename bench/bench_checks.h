// What a benchmark's printed figures promise (equal images, positive counts and times, bytes that follow from the
// layout...), checked as they are printed. A broken promise is reported on stderr as "BENCH: check failed: WHAT",
// and the benchmark, once it has printed everything, exits with kChecksFailed: CTest's --short runs then fail on
// wrong figures, not only on a crash.
#pragma once
#include <cstdarg>
#include <cstdio>

namespace vr::bench {

constexpr int kChecksFailed = 3;

class Checks {
public:
    explicit Checks(const char* bench) : bench_(bench) {}

    // Counts the check; when `ok` is false, prints the printf-style description of what should have held.
    __attribute__((format(printf, 3, 4))) bool expect(bool ok, const char* format, ...) {
        ++checked_;
        if (ok) return true;
        ++failed_;
        std::fprintf(stderr, "%s: check failed: ", bench_);
        va_list args;
        va_start(args, format);
        std::vfprintf(stderr, format, args);
        va_end(args);
        std::fprintf(stderr, "\n");
        return false;
    }

    // 0 when every check held (and there was at least one), else kChecksFailed, with a line on stderr either way.
    int exitStatus() const {
        if (checked_ == 0) {
            std::fprintf(stderr, "%s: check failed: nothing was checked\n", bench_);
            return kChecksFailed;
        }
        std::fprintf(stderr, "%s: %d of %d checks failed\n", bench_, failed_, checked_);
        return failed_ == 0 ? 0 : kChecksFailed;
    }

private:
    const char* bench_;
    int checked_ = 0, failed_ = 0;
};

}  // namespace vr::bench

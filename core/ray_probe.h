// What the ray probe measured on a prepared volume (render/caster_choice.h: probeRays), kept in the prepared file
// for --caster auto: per caster and class of ray directions, the mean loop iterations per pixel of the CPU
// reference renderer.
#pragma once
#include <array>
#include <optional>

namespace vr {

// The classes of ray directions by the signs of their components (render/direction_class.h): class
// (sx + 1) + 3 (sy + 1) + 9 (sz + 1), class 13 (all signs 0) being no direction.
constexpr int kProbeDirectionClasses = 27;
using PerDirectionClass = std::array<double, kProbeDirectionClasses>;

// One caster's mean iterations per pixel in each direction class (0 in class 13), split into iterations that
// leapt several samples (independent of the step) and single samples (which grow as the step shrinks).
struct ProbeCounts {
    PerDirectionClass leaps{};
    PerDirectionClass singleSamples{};
    bool operator==(const ProbeCounts&) const = default;
};

struct RayProbe {
    double stepVoxels = 0;  // the renderer's default step and early ray termination, at which the probe ran
    double ert = 0;
    int octantViews = 0, quadrantViews = 0, axisViews = 0;  // views per direction class of each kind
    // The primitive caster's counts are the lattice samples a leaping caster's iterations stood for (all single
    // samples); a leaping caster has counts where the volume has its field.
    ProbeCounts primitive;
    std::optional<ProbeCounts> pc, acd, eacd;
    bool operator==(const RayProbe&) const = default;
};

}  // namespace vr

// Factorized span integration and shading (docs/ALGORITHMS.md sections 5 and 6), shared by every caster: the
// math is shaders/ray_math.h's, here in double with the CPU reference's types.
#pragma once
#include <cmath>

#include "core/vec3.h"
#include "shaders/ray_math.h"

namespace vr {

// Opacity of a homogeneous span of extinction sigma and world length L (device::spanOpacity of sigma L).
inline double spanOpacity(double sigma, double length) { return device::spanOpacity(sigma * length); }

// Front-to-back accumulation of premultiplied colour C and opacity A, and of the optical depth behind A.
struct Accumulator {
    Vec3d colour{0, 0, 0};
    double alpha = 0;
    double depth = 0;  // sum of sigma L over the spans: -ln(1 - A) up to rounding

    // spanDepth: sigma L of the span; spanAlpha = spanOpacity(sigma, L).
    void composite(const Vec3d& shaded, double spanAlpha, double spanDepth) {
        const double w = (1 - alpha) * spanAlpha;
        colour += shaded * w;
        alpha += w;
        depth += spanDepth;
    }
};

// The optical depth at which the opacity reaches ert, -ln(1 - ert): +inf for ert = 1 (no early termination).
inline double terminationDepth(double ert) { return -std::log1p(-ert); }

// The samples of a span of extinction sigma, from a ray of optical depth `depth`, until primitive stepping would
// stop (device::samplesToTermination). From the depth, not from A: a division where a log was, which was most of a
// leaping caster's iteration on lavapipe. The slack covers the depth's rounding, which differs with the grouping of
// samples into spans.
inline double samplesToTermination(double depth, double sigma, double dt, double ertDepth) {
    constexpr double kTerminationSlack = 1e-9;
    return device::samplesToTermination(ertDepth - depth, sigma * dt, kTerminationSlack);
}

// Phong with one directional light; material constants shared with the GPU.
struct ShadingModel {
    double ambient = 0.25, diffuse = 0.65, specular = 0.25, shininess = 24;
};

// Shaded emission of a sample (device::shade): two-sided, a flat voxel's normal (0,0,0) lit as facing the viewer.
inline Vec3d shade(const Vec3d& colour, const Vec3d& normal, const Vec3d& toEye, const Vec3d& toLight,
                   const ShadingModel& m = {}) {
    return device::shade(colour, normal, toEye, toLight, m.ambient, m.diffuse, m.specular, m.shininess);
}

}  // namespace vr

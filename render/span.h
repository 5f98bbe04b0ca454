// Factorized span integration and shading (docs/ALGORITHMS.md sections 5 and 6), shared by every caster.
// GLSL counterpart: shaders/span.glsl, the same functions (with its own expm1, which GLSL lacks).
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/vec3.h"

namespace vr {

// Opacity of a homogeneous span of world length L: 1 - exp(-sigma L) without cancellation for tiny sigma L
// (in float, 1 - (1 - 1e-8)^n loses everything). sigma is finite (alpha = 1 is clamped), so an opaque span
// gives exactly 1.
inline double spanOpacity(double sigma, double length) { return -std::expm1(-sigma * length); }

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

// Early ray termination belongs to the samples, not to the spans: a span of n samples stops at the sample after
// which primitive stepping would have stopped, the first m with depth + sigma dt m >= terminationDepth(ert), so
// every caster terminates where the primitive one does (A < ert decides, in every caster's loop). From the depth,
// not from A: a division where a log was, which was most of a leaping caster's iteration on lavapipe. Rounding
// may leave the count a hair above an integer; it is rounded down: a span one sample short costs one more
// iteration, one sample too long would composite a sample that primitive stepping never takes. Returns +inf when
// the span never reaches ert.
inline double samplesToTermination(double depth, double sigma, double dt, double ertDepth) {
    constexpr double kTerminationSlack = 1 - 1e-9;  // relative: a count this close above an integer is that integer
    if (sigma <= 0) return std::numeric_limits<double>::infinity();
    return std::max(1.0, std::ceil((ertDepth - depth) / (sigma * dt) * kTerminationSlack));
}

// Phong with one directional light; material constants shared with the GPU.
struct ShadingModel {
    double ambient = 0.25, diffuse = 0.65, specular = 0.25, shininess = 24;
};

// Shaded emission of a sample. toEye: unit vector toward the viewer (minus the ray direction); toLight: unit
// vector toward the light (a headlight uses toEye). normal: unit, or (0,0,0) for a flat voxel. Two-sided: the
// normal is turned to face the viewer. A flat voxel gets ambient + diffuse with the view vector as normal and
// no highlight (never normalize(0)).
inline Vec3d shade(const Vec3d& colour, const Vec3d& normal, const Vec3d& toEye, const Vec3d& toLight,
                   const ShadingModel& m = {}) {
    const bool flat = dot(normal, normal) == 0;
    Vec3d n = flat ? toEye : normal;
    if (dot(n, toEye) < 0) n = -n;
    const double nl = dot(n, toLight);
    const double diffuse = std::abs(nl);
    double highlight = 0;
    if (!flat && nl > 0) {
        const Vec3d reflected = n * (2 * nl) - toLight;  // unit since n and toLight are
        highlight = std::pow(std::max(0.0, dot(reflected, toEye)), m.shininess);
    }
    return colour * (m.ambient + m.diffuse * diffuse) + Vec3d{1, 1, 1} * (m.specular * highlight);
}

}  // namespace vr

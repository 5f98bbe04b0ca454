// A list's composite rays cast in pieces (shaders/caster.comp PIECES): each piece of a ray is a stretch of its
// samples cast by an invocation of its own, which gathers from a transparent start; the pieces, composited front to
// back, give what the whole ray would (to float rounding: a leap stops at its piece's end, and the piece after it
// starts a span of its own, which at thresholds 0 holds the same samples).
#pragma once
#include <cstddef>
#include <cstdint>

#include "core/vec3.h"
#include "shaders/device_contract.h"

namespace vr {

// How many pieces each ray of a composite list of `listPixels` takes on a device, where `framePixels` fill it as a
// whole frame does: a discrete GPU gets about as many invocations as a whole frame's, at most kMostPieces a ray;
// other devices keep whole rays (a CPU device's cores, and a small GPU's, are busy with a list's rays already, and a
// piece behind an opaque one is work the whole ray would have ended before).
constexpr int kMostPieces = 8;
int raysPieces(bool discreteGpu, std::size_t listPixels, std::size_t framePixels);

// The pixel of a ray cast in `pieces` pieces: piece j's colour (premultiplied rgb, a: its optical depth) and counts
// (samples, iterations with the failure flags) at first + j stride. The colour is the whole ray's (rgb over the
// background, alpha), with the failure flags of any piece in its alpha (device::failureAlphaBits); the counts
// are the pieces' summed.
struct RayFromPieces {
    device::uvec4 colour;
    uint32_t samples = 0, iterations = 0;  // iterations with the failure flags
};
RayFromPieces compositePieces(const device::uvec4* colours, const device::uvec4* counts, std::size_t first,
                              std::size_t stride, int pieces, const Vec3d& background);

}  // namespace vr

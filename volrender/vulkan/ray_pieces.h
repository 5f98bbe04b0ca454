// Composite rays cast in pieces (shaders/caster.comp PIECES): each piece of a ray is a stretch of its samples cast by
// an invocation of its own, which gathers from a transparent start; the ray's first invocation composites its pieces
// front to back, which gives what the whole ray would (to float rounding: a leap stops at its piece's end, and the
// piece after it starts a span of its own, which at thresholds 0 holds the same samples; and each piece ends at early
// termination alone, which adds at most 1 - ert of the colour that the whole ray leaves out).
#pragma once
#include <cstddef>

namespace vr {

// How many pieces each ray of a composite list of `listPixels` takes on a device, where `framePixels` fill it as a
// whole frame does: a discrete GPU gets about as many invocations as a whole frame's, at most device::kMostPieces a
// ray; other devices keep whole rays (a CPU device's cores, and a small GPU's, are busy with a list's rays already,
// and a piece behind an opaque one is work the whole ray would have ended before).
int raysPieces(bool discreteGpu, std::size_t listPixels, std::size_t framePixels);

}  // namespace vr

// Clipping a ray's volume interval by a plane, stated once: the CPU reference clips in double, the casters in float
// (shared_language.h), before their loops, so that no sample lies outside the kept side and no leap crosses the
// plane (a leap never passes the interval's exit).
#ifndef VR_CLIP_PLANES_H
#define VR_CLIP_PLANES_H

#include "shared_language.h"

#ifdef __cplusplus
namespace vr::device {
#endif

// Along the grid ray p(t) = o + t d, the half-space dot(n, p) >= c keeps the t with t r >= s, where s = c - dot(n, o)
// and r = dot(n, d): t >= s / r where r > 0 (the plane is an entry), t <= s / r where r < 0 (an exit), every t
// where r == 0 and s <= 0 (the ray runs inside), none where r == 0 and s > 0 (it runs outside: the exit becomes 0,
// at or before any entry, which is >= 0).
VR_FUNCTION VR_REAL clipEntry(VR_REAL tEntry, VR_REAL s, VR_REAL r) {
    return r > VR_REAL(0) && s / r > tEntry ? s / r : tEntry;
}
VR_FUNCTION VR_REAL clipExit(VR_REAL tExit, VR_REAL s, VR_REAL r) {
    if (r < VR_REAL(0)) return s / r < tExit ? s / r : tExit;
    return r == VR_REAL(0) && s > VR_REAL(0) ? VR_REAL(0) : tExit;
}

#ifdef __cplusplus
}  // namespace vr::device
#endif

#endif

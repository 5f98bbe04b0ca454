// Which ray octants a view can produce: ACD and EACD upload the distance fields of those octants only.
#pragma once
#include "render/camera.h"

namespace vr {

// Bit oct set when some pixel's ray may lie in octant oct (device::octantOf of its direction). Orthographic: exactly
// the octant of the view direction. Perspective: the direction components are linear over the image plane, so
// every octant some pixel reaches has a vertex of its part of the image rectangle at a corner, where a
// component's zero line crosses an edge, or where two zero lines cross; those points are tested, with a zero
// counting for both signs (a conservative superset).
unsigned viewOctants(const Camera& camera);

}  // namespace vr

// A view timed as users render it, without ray counts (the colours alone come back: on a discrete GPU that copy is a
// fixed cost of every frame), then rendered again with its rays counted for the iteration figures, so that the
// counts' copy is not charged to the frame.
#ifndef VR_BENCH_COUNTED_RENDER_H
#define VR_BENCH_COUNTED_RENDER_H

#include <utility>

#include "volrender/vulkan/vulkan_renderer.h"

namespace vr::bench {

struct CountedRender {
    RenderResult counted;   // the image, with each ray's iterations and samples
    double deviceMs = 0;    // of the render without counts
};

inline CountedRender timedThenCounted(VulkanRenderer& renderer, const GpuVolume& volume, const Camera& camera,
                                      RenderSettings s) {
    s.rayCounts = false;
    const double ms = renderer.render(volume, camera, s).deviceMilliseconds;
    s.rayCounts = true;
    return {renderer.render(volume, camera, s), ms};
}

}  // namespace vr::bench

#endif

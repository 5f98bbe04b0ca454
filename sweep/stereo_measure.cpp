#include "sweep/stereo_measure.h"

#include <algorithm>
#include <utility>

#include "sweep/order_statistics.h"

namespace vr {

StereoMeasurement measureStereo(VulkanRenderer& renderer, const GpuVolume& volume, const std::vector<Camera>& cameras,
                                const RenderSettings& settings, int rounds) {
    auto pairAbout = [&](const Camera& camera) {
        const double focus = dot(volume.grid().centre() - camera.eye, camera.forward);
        return stereoPair(camera, volume.grid(), kSeparationPerFocus * focus, focus);
    };
    // Pairs timed as users render them, without ray counts; counted again, untimed, for the re-cast work.
    RenderSettings timed = settings, counted = settings;
    timed.rayCounts = false;
    counted.rayCounts = true;
    renderer.renderStereo(volume, pairAbout(cameras.front()), timed, true);  // warm-up: pipelines compiled
    renderer.renderStereo(volume, pairAbout(cameras.front()), timed, false);
    StereoMeasurement m;
    m.separation = pairAbout(cameras.front()).separation;
    std::vector<double> pair, oneEye, leftEye, fullPair, reproject;
    std::vector<ImageError> errors;
    double recastIterations = 0, fullIterations = 0;
    auto timePairs = [&](const StereoPair& eyes) {
        StereoRender reused = renderer.renderStereo(volume, eyes, timed, true);
        StereoRender full = renderer.renderStereo(volume, eyes, timed, false);
        pair.push_back(reused.left.deviceMilliseconds + reused.right.deviceMilliseconds);
        oneEye.push_back(full.left.deviceMilliseconds);
        leftEye.push_back(reused.left.deviceMilliseconds);
        fullPair.push_back(full.left.deviceMilliseconds + full.right.deviceMilliseconds);
        reproject.push_back(reused.reprojectMilliseconds);
        return std::pair{std::move(reused), std::move(full)};
    };
    for (const Camera& camera : cameras) {
        const StereoPair eyes = pairAbout(camera);
        const auto [reused, full] = timePairs(eyes);
        m.recastFraction += reused.recastFraction / double(cameras.size());
        m.recastInPart += reused.recastInPartFraction / double(cameras.size());
        m.recastPieces = std::max(m.recastPieces, reused.recastPieces);
        errors.push_back(imageError(full.right.image, reused.right.image));
        const StereoRender reusedCounted = renderer.renderStereo(volume, eyes, counted, true);
        const StereoRender fullCounted = renderer.renderStereo(volume, eyes, counted, false);
        for (std::size_t i = 0; i < fullCounted.right.iterations.size(); ++i) {
            recastIterations += reusedCounted.right.iterations[i];
            fullIterations += fullCounted.right.iterations[i];
        }
        m.leftEyesEqual = m.leftEyesEqual && reused.left.image.rgba == full.left.image.rgba;
        if (m.reusedRight.empty()) {
            m.reusedRight.push_back(reused.right.image);
            m.fullRight.push_back(full.right.image);
        }
    }
    for (int round = 1; round < rounds; ++round)
        for (const Camera& camera : cameras) timePairs(pairAbout(camera));
    m.pairMs = median(pair);
    m.oneEyeMs = median(oneEye);
    m.leftEyeMs = median(leftEye);
    m.fullPairMs = median(fullPair);
    m.reprojectMs = median(reproject);
    m.error = summarize(errors);
    m.recastWork = fullIterations > 0 ? recastIterations / fullIterations : 0;
    return m;
}

}  // namespace vr

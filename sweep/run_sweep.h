// The sweep itself: load and classify once, then per (T_o, T_a) segment, build the fields and render every
// caster at every view on the Vulkan device, comparing each image with the reference.
#pragma once
#include <filesystem>
#include <string>

#include "sweep/sweep_options.h"

namespace vr {

// Where a sweep keeps its images: OUTDIR/images/DATASET/.
std::filesystem::path imagesDir(const std::filesystem::path& outDir, const std::string& dataset);
// View 0's image (or its error map, |diff| x10) of a caster at a setting, inside imagesDir.
std::string imageName(const std::string& caster, double opacityThreshold, double angleThreshold, bool errorMap);

// Appends one row per setting and caster to OUTDIR/sweep.csv (after each setting, so an interrupted run keeps
// what it finished; with options.resume, settings whose rows are all there are skipped), writes view 0's images
// and error maps, and with options.peersDir compares the peers' images with the reference into
// OUTDIR/peers_DATASET.json. Returns the number of settings run. Throws InputError for bad input,
// std::runtime_error for device failures.
int runSweep(const SweepOptions& options);

}  // namespace vr

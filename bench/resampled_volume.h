// Volumes the benchmarks make from a shared one: resampled to another size, and with CT-like noise added, so that
// a clinical-size CT (e.g. 512x512x1024 int16) can be measured without shipping one.
#pragma once
#include "core/volume.h"

namespace vr::bench {

// Trilinear resampling to `dims` over the same physical extent (voxel centres aligned); integer volumes stay
// integer (rounded).
Volume resample(const Volume& v, Vec3i dims);

// `v` with zero-mean Gaussian noise of standard deviation `sigma` added to every voxel, rounded and clamped to the
// range of v's type (integer types). Deterministic for a seed, whatever the number of threads: each slice draws from
// its own generator.
Volume withNoise(Volume v, double sigma, unsigned seed);

}  // namespace vr::bench

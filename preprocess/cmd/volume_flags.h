// The flags that say how to read and prepare a volume, shared by volprep and by volrender's one-command path:
// the transfer function, the thresholds and the raw-file description.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "preprocess/pipeline/staged_prepare.h"

namespace vr {

struct VolumeFlags {
    std::string tf;
    double to = 0.01, ta = 3;
    std::vector<int> dims;
    std::string type;
    std::vector<double> spacing;
    bool bigEndian = false;
};

// Adds --tf, --to, --ta and the raw group (--dims, --type, --spacing, --big-endian); returns the --tf option.
CLI::Option* addVolumeFlags(CLI::App& app, VolumeFlags& flags);

// Throws InputError naming --to or --ta when a threshold is negative or not finite.
void checkThresholds(const VolumeFlags& flags);

RawOptions rawOptionsFrom(const VolumeFlags& flags);

// The transfer function (loaded: a bad one fails here, before any volume is read) and the thresholds; regions for
// trilinear sampling unless `nearest`, with normals unless `noNormals`. Fields and EACD code as PrepareOptions'.
PrepareOptions prepareOptionsFrom(const VolumeFlags& flags, bool nearest, bool noNormals);

}  // namespace vr

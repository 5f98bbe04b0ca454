// The pipeline on a shared dataset, for the tests that link it (volpipeline): loaded as MANIFEST.tsv says.
#pragma once
#include <stdexcept>
#include <string>

#include "preprocess/pipeline/staged_prepare.h"
#include "support/datasets.h"

namespace vr::test {

// How a shared dataset loads: with the spacing the manifest gives (dims and type come from its name).
inline RawOptions manifestRawOptions(const std::string& file) {
    for (const DatasetEntry& e : manifest()) {
        if (e.file != file) continue;
        RawOptions raw;
        raw.spacing = e.spacing;
        return raw;
    }
    throw std::invalid_argument(file + ": not in MANIFEST.tsv");
}

// A shared dataset loaded and prepared at once, as volprep prepares it.
inline PreparedVolume prepareDataset(const std::string& file, const PrepareOptions& options) {
    return prepare(loadVolume(datasetsDir() / file, manifestRawOptions(file)), options);
}

}  // namespace vr::test

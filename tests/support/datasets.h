// Where the tests find the shared real datasets, and their manifest rows.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "core/volume.h"

namespace vr::test {

std::filesystem::path datasetsDir();

struct DatasetEntry {
    std::string file;       // e.g. cranium_ct_256x256x108_int16.raw.gz
    Vec3i dims;
    ScalarType type;
    Vec3d spacing;          // 1,1,1 where the manifest says unknown
    std::string tf;         // transfer function file name beside it
    bool isRaw() const;     // a headerless .raw.gz (the ones named NAME_DxDxD_TYPE.raw.gz)
};

// Rows of MANIFEST.tsv; each throws when it finds none, so that a test looping over them cannot pass having
// looped over nothing.
std::vector<DatasetEntry> manifest();
std::vector<DatasetEntry> rawManifest();  // only the .raw.gz rows

// The row of the raw dataset whose file name starts with `prefix` (the first such); throws naming the prefix when
// there is none.
DatasetEntry rawDataset(const std::string& prefix);

// The row of the dataset named `file` exactly; throws naming the file when there is none.
DatasetEntry dataset(const std::string& file);

// A fresh empty folder under the build tree for one test's outputs (unique to this process).
std::filesystem::path scratchDir(const std::string& name);

}  // namespace vr::test

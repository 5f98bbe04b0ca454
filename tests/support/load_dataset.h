// The shared datasets loaded as MANIFEST.tsv describes them, and their transfer functions (library vrloaddataset:
// the load and classify stages).
#pragma once
#include <string>

#include "core/volume.h"
#include "preprocess/classify/transfer_function.h"
#include "preprocess/load/load_volume.h"
#include "support/datasets.h"

namespace vr::test {

// How a shared dataset loads: with the spacing the manifest gives (a raw file's dims and type come from its name).
RawOptions manifestRawOptions(const std::string& file);

// A shared dataset loaded with the manifest's spacing.
Volume loadDataset(const DatasetEntry& entry);
// The raw dataset whose file name starts with `prefix` (rawDataset), loaded.
Volume loadDataset(const std::string& prefix);

// A transfer function shipped beside the datasets (e.g. "cranium_ct.tf.json").
TransferFunction datasetTransferFunction(const std::string& name);

// Opacity rising linearly from 0 at x0 to 1 at x1, colour from red to blue: a function every value maps apart.
TransferFunction linearTransferFunction(double x0, double x1);

}  // namespace vr::test

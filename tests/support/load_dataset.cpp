#include "support/load_dataset.h"

namespace vr::test {

static RawOptions rawOptionsOf(const DatasetEntry& entry) {
    RawOptions raw;
    raw.spacing = entry.spacing;
    return raw;
}

RawOptions manifestRawOptions(const std::string& file) { return rawOptionsOf(dataset(file)); }

Volume loadDataset(const DatasetEntry& entry) { return loadVolume(datasetsDir() / entry.file, rawOptionsOf(entry)); }

Volume loadDataset(const std::string& prefix) { return loadDataset(rawDataset(prefix)); }

TransferFunction datasetTransferFunction(const std::string& name) { return loadTransferFunction(datasetsDir() / name); }

TransferFunction linearTransferFunction(double x0, double x1) {
    TransferFunction tf;
    tf.opacity = {{x0, 0.0}, {x1, 1.0}};
    tf.colour = {{x0, 1, 0, 0}, {x1, 0, 0, 1}};
    return tf;
}

}  // namespace vr::test

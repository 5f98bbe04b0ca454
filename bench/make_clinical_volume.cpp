// A CT of clinical size made from a shared one, for the whole-process benchmark (scripts/whole_process.sh with
// CLINICAL=DIMS): the source resampled trilinearly to DIMS over the same physical extent, with Gaussian noise of a
// CT's order added (20 HU by default), written as a headerless raw file whose name carries its dims and type
// (NAME_DxDxD_TYPE.raw, as the raw loader reads). Prints the file's path and its spacing (x,y,z) on one line.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "preprocess/load/load_volume.h"
#include "resampled_volume.h"
#include "support/datasets.h"
#include "support/load_dataset.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    CLI::App app{"Write a CT of clinical size: a shared CT resampled to --dims with CT-like noise"};
    std::string from = "cranium_ct_256x256x108_int16.raw.gz", dimsText = "512x512x1024", name = "clinical_ct";
    fs::path outDir = ".";
    double noise = 20;
    unsigned seed = 1;
    app.add_option("--from", from, "raw dataset of MANIFEST.tsv to resample (its file name or the start of it)")
        ->capture_default_str();
    app.add_option("--dims", dimsText, "size of the volume written, XxYxZ")->capture_default_str();
    app.add_option("--noise", noise, "standard deviation of the Gaussian noise, in the volume's units")
        ->capture_default_str();
    app.add_option("--seed", seed, "seed of the noise")->capture_default_str();
    app.add_option("--name", name, "file name before _DIMS_TYPE.raw")->capture_default_str();
    app.add_option("-o,--output-dir", outDir, "folder to write into")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    try {
        vr::Vec3i dims;
        char tail = 0;
        if (std::sscanf(dimsText.c_str(), "%dx%dx%d%c", &dims.x, &dims.y, &dims.z, &tail) != 3 || dims.x < 1 ||
            dims.y < 1 || dims.z < 1 || dims.x > 4096 || dims.y > 4096 || dims.z > 4096)
            throw vr::InputError("--dims: expected XxYxZ with each edge in 1..4096, got " + dimsText);
        if (!std::isfinite(noise) || noise < 0)
            throw vr::InputError("--noise: the noise's standard deviation must be a finite number >= 0");
        const vr::test::DatasetEntry entry = vr::test::rawDataset(from);
        const vr::Volume v =
            vr::bench::withNoise(vr::bench::resample(vr::test::loadDataset(entry), dims), noise, seed);
        const fs::path path =
            outDir / (name + "_" + dimsText + "_" + std::string(vr::scalarTypeName(v.sourceType)) + ".raw");
        std::vector<unsigned char> bytes(v.values.size() * vr::scalarBytes(v.sourceType));
        vr::narrowScalars(v.values.data(), v.values.size(), v.sourceType, bytes.data());
        vr::writeFileAtomically(path, [&](std::ostream& out) {
            out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        });
        std::printf("%s %g,%g,%g\n", path.c_str(), v.grid.spacing.x, v.grid.spacing.y, v.grid.spacing.z);
    } catch (const std::exception& e) {  // bad input, or no such dataset in the manifest
        std::fprintf(stderr, "make_clinical_volume: %s\n", e.what());
        return 1;
    }
    return 0;
}

// Preprocessing benchmark: per dataset, the median over several runs of each stage's wall and CPU time (load,
// classify, segment, each distance field, write, and reading the prepared file back), the bytes of every chunk in
// memory and in the file (compressed), and what the segmentation produced. Prints Markdown tables.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <map>

#include "core/errors.h"
#include "io/prepared_file.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "support/datasets.h"
#include "support/load_dataset.h"
#include "sweep/order_statistics.h"

namespace {
namespace fs = std::filesystem;
using vr::median;

const std::vector<std::string> kStages = {"load", "classify", "segment", "pc", "acd", "eacd", "write", "read"};
const std::vector<std::string> kChunks = {"scalars", "table", "labels", "pc", "acd", "eacd"};


double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

struct DatasetResult {
    std::string name;
    // Per stage, one entry per run. Besides the pipeline's stages: "read" (readPrepared of every chunk), and the
    // comparison with OpenVDB: "core read" (readPrepared of the scalars, the table and the labels only), "vdb
    // write" and "vdb read" (the scalars as an OpenVDB FloatGrid, read back and densified).
    std::map<std::string, std::vector<double>> wall, cpu;
    nlohmann::json statistics;  // from the last run (the same every run)
    std::uintmax_t fileBytes = 0, vdbBytes = 0;
    std::map<std::string, std::uint64_t> storedBytes;  // per entry of kChunks: its chunks' blocks in the file
};

// The chunk group of kChunks a chunk belongs to (acd0 .. acd7: acd).
std::string chunkGroup(const std::string& name) {
    for (const char* octants : {"eacd", "acd"})
        if (name.rfind(octants, 0) == 0) return octants;
    return name;
}

void record(DatasetResult& result, const vr::StageTime& t) {
    result.wall[t.stage].push_back(t.seconds);
    result.cpu[t.stage].push_back(t.cpuSeconds);
}

// The dense scalars (as float) through OpenVDB with its default file compression: the format the prepared file is
// meant to beat on dense grids. Zero voxels stay inactive background, which favours OpenVDB.
std::uintmax_t vdbRoundTrip(const std::vector<float>& scalars, vr::Vec3i dims, const fs::path& path,
                            DatasetResult& result) {
    using namespace openvdb;
    const CoordBBox box(Coord(0), Coord(dims.x - 1, dims.y - 1, dims.z - 1));
    vr::StageClock write;
    {
        tools::Dense<const float, tools::LayoutXYZ> dense(box, scalars.data());
        FloatGrid::Ptr grid = FloatGrid::create(0.0f);
        tools::copyFromDense(dense, *grid, 0.0f);
        grid->setName("scalars");
        io::File(path.string()).write({grid});
    }
    record(result, write.stop("vdb write"));

    vr::StageClock read;
    io::File file(path.string());
    file.open();
    FloatGrid::Ptr grid = gridPtrCast<FloatGrid>(file.readGrid("scalars"));
    file.close();
    std::vector<float> back(scalars.size());
    tools::Dense<float, tools::LayoutXYZ> dense(box, back.data());
    tools::copyToDense(*grid, dense);
    record(result, read.stop("vdb read"));
    if (back != scalars) throw std::runtime_error("OpenVDB changed the scalars on the round trip");
    std::uintmax_t bytes = fs::file_size(path);
    fs::remove(path);
    return bytes;
}

// Every stage as volprep runs them, the write included.
void prepareFile(const fs::path& input, const vr::RawOptions& raw, const vr::PrepareOptions& options,
                 const fs::path& out, DatasetResult& result) {
    vr::StagedPreparation staged = vr::StagedPreparation::load(input, raw);
    staged.prepare(options);
    staged.write(out);
    for (const vr::StageTime& t : staged.stageTimes()) record(result, t);
    result.statistics = staged.withStatistics().meta.statistics;
    result.fileBytes = fs::file_size(out);
    result.storedBytes.clear();
    for (const vr::PreparedChunkBytes& c : vr::readPreparedHeader(out).chunks)
        result.storedBytes[chunkGroup(c.name)] += c.storedBytes;
}

DatasetResult benchDataset(const std::string& file, const vr::PrepareOptions& base, int runs, const fs::path& scratch) {
    vr::test::DatasetEntry e = vr::test::dataset(file);
    vr::RawOptions raw;
    raw.spacing = e.spacing;
    vr::PrepareOptions options = base;
    options.classify.transferFunction = vr::test::datasetTransferFunction(e.tf);
    fs::path out = scratch / (file + ".vprep");
    DatasetResult result{file, {}, {}, {}, 0, 0, {}};
    for (int run = 0; run < runs; ++run) {
        prepareFile(vr::test::datasetsDir() / file, raw, options, out, result);  // freed before reading it back

        vr::StageClock all;
        vr::PreparedVolume back = vr::readPrepared(out, options.fields);
        record(result, all.stop("read"));
        back = {};
        vr::StageClock core;
        back = vr::readPrepared(out, 0);
        record(result, core.stop("core read"));
        result.vdbBytes = vdbRoundTrip(back.scalars.values, back.grid().dims, scratch / (file + ".vdb"), result);
        std::fprintf(stderr, "%s: run %d of %d done\n", file.c_str(), run + 1, runs);
    }
    fs::remove(out);
    return result;
}

void printTimes(const char* title, const std::vector<DatasetResult>& results,
                std::map<std::string, std::vector<double>> DatasetResult::*times) {
    std::printf("%s\n\n| dataset | voxels |", title);
    for (const auto& s : kStages) std::printf(" %s |", s.c_str());
    std::printf(" total (no read) |\n|---|---:|");
    for (std::size_t i = 0; i <= kStages.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (const auto& r : results) {
        std::printf("| %s | %zu |", r.name.c_str(), r.statistics["voxels"].get<std::size_t>());
        double total = 0;
        for (const auto& s : kStages) {
            if (!(r.*times).count(s)) {
                std::printf(" - |");
                continue;
            }
            double m = median((r.*times).at(s));
            if (s != "read") total += m;
            std::printf(" %.3f |", m);
        }
        std::printf(" %.3f |\n", total);
    }
    std::printf("\n");
}

void printTables(const std::vector<DatasetResult>& results, const vr::PrepareOptions& o, int runs) {
    std::printf("Preprocessing, T_o = %g, T_a = %g deg, normals %s, %s sampling, %d threads; median of %d runs.\n"
                "pc is timed on its own (with its own 8 ACD passes); eacd on top of acd; read is readPrepared of every "
                "chunk written.\n\n",
                o.segmentation.opacityThreshold, o.segmentation.angleThresholdDeg, o.classify.normals ? "on" : "off",
                o.segmentation.trilinear ? "trilinear" : "nearest", tbb::info::default_concurrency(), runs);
    printTimes("Wall seconds per stage:", results, &DatasetResult::wall);
    printTimes("CPU seconds per stage (all threads; steadier than wall time on a shared machine):", results,
               &DatasetResult::cpu);

    std::printf("Dense float data through this format and through OpenVDB %s (file compression flags %u), "
                "median wall (CPU) seconds. Prepared: readPrepared of the scalars, the table and the labels only. "
                "OpenVDB: the scalars as a FloatGrid (zero voxels inactive), read and densified.\n\n"
                "| dataset | prepared MiB | read s | MiB/s | OpenVDB scalars MiB (file) | write s | read s | MiB/s |\n"
                "|---|---:|---:|---:|---:|---:|---:|---:|\n",
                openvdb::getLibraryVersionString(), openvdb::io::Archive::DEFAULT_COMPRESSION_FLAGS);
    for (const auto& r : results) {
        const nlohmann::json& b = r.statistics["bytes"];
        double ours = mib(b["scalars"].get<double>() + b["table"].get<double>() + b["labels"].get<double>());
        double dense = mib(r.statistics["voxels"].get<double>() * sizeof(float));
        double read = median(r.wall.at("core read")), vdbRead = median(r.wall.at("vdb read"));
        std::printf("| %s | %.1f | %.3f (%.3f) | %.0f | %.1f (%.1f) | %.3f (%.3f) | %.3f (%.3f) | %.0f |\n",
                    r.name.c_str(), ours, read, median(r.cpu.at("core read")), ours / read, dense,
                    mib(double(r.vdbBytes)), median(r.wall.at("vdb write")), median(r.cpu.at("vdb write")), vdbRead,
                    median(r.cpu.at("vdb read")), dense / vdbRead);
    }

    std::printf("\nMiB per chunk, in memory (uncompressed) / in the file (zstd level %d, blocks of %zu MiB):\n\n"
                "| dataset |", vr::kPreparedZstdLevel, vr::kPreparedBlockBytes >> 20);
    for (const auto& c : kChunks) std::printf(" %s |", c.c_str());
    std::printf(" all | file | file bytes per voxel | write: MB/s of arrays, of file |\n|---|");
    for (std::size_t i = 0; i <= kChunks.size() + 3; ++i) std::printf("---:|");
    std::printf("\n");
    for (const auto& r : results) {
        std::printf("| %s |", r.name.c_str());
        double all = 0, stored = 0;
        for (const auto& c : kChunks) {
            const double bytes = r.statistics["bytes"][c].get<double>();
            const double inFile = r.storedBytes.count(c) ? double(r.storedBytes.at(c)) : 0.0;
            all += bytes;
            stored += inFile;
            std::printf(" %.1f / %.2f |", mib(bytes), mib(inFile));
        }
        // The write stage's rate: encoding, compressing, checksumming, writing and fsyncing, per second.
        const double write = median(r.wall.at("write"));
        std::printf(" %.1f / %.2f (%.1fx) | %.2f | %.2f | %.0f, %.0f |\n", mib(all), mib(stored), all / stored,
                    mib(double(r.fileBytes)), double(r.fileBytes) / r.statistics["voxels"].get<double>(),
                    all / write / 1e6, double(r.fileBytes) / write / 1e6);
    }

    std::printf("\nRegions and mean leaps in voxels (ACD edge: the same in every octant; EACD extents x,y,z of "
                "octant 0):\n\n"
                "| dataset | regions | mean region size | PC radius | ACD edge | EACD extents |\n"
                "|---|---:|---:|---:|---:|---|\n");
    for (const auto& r : results) {
        const nlohmann::json& s = r.statistics;
        const nlohmann::json& l = s["leaps"];
        auto number = [&](const char* key, auto get) {
            if (!l.contains(key)) return std::string("-");
            char text[32];
            std::snprintf(text, sizeof(text), "%.2f", get(l[key]));
            return std::string(text);
        };
        std::string extents = "-";
        if (l.contains("eacdMeanExtent")) {
            const nlohmann::json& e = l["eacdMeanExtent"][0];
            char text[64];
            std::snprintf(text, sizeof(text), "%.2f, %.2f, %.2f", e[0].get<double>(), e[1].get<double>(),
                          e[2].get<double>());
            extents = text;
        }
        std::printf("| %s | %u | %.1f | %s | %s | %s |\n", r.name.c_str(), s["regions"].get<uint32_t>(),
                    s["meanRegionSize"].get<double>(),
                    number("pcMeanRadius", [](const nlohmann::json& j) { return j.get<double>(); }).c_str(),
                    number("acdMeanEdge", [](const nlohmann::json& j) { return j[0].get<double>(); }).c_str(),
                    extents.c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Times every preprocessing stage on real datasets (spacing and transfer function from MANIFEST.tsv)."};
    std::vector<std::string> datasets{"boston_teapot_256x256x178_uint8.raw.gz", "cranium_ct_256x256x108_int16.raw.gz"};
    vr::PrepareOptions options;
    options.segmentation.opacityThreshold = 0.01;
    options.segmentation.angleThresholdDeg = 3;
    bool noNormals = false;
    int runs = 3;
    std::string scratch = (fs::temp_directory_path() / "prep_bench").string();
    app.add_option("datasets", datasets, "file names in MANIFEST.tsv")->capture_default_str();
    app.add_option("--to", options.segmentation.opacityThreshold, "T_o")->capture_default_str();
    app.add_option("--ta", options.segmentation.angleThresholdDeg, "T_a, degrees")->capture_default_str();
    bool nearest = false;
    app.add_flag("--nearest", nearest, "regions for nearest sampling only (default: trilinear, as volprep makes)");
    app.add_flag("--no-normals", noNormals, "no gradients (T_a ignored)");
    app.add_option("--runs", runs, "runs per dataset (the median is printed)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--scratch", scratch, "folder for the prepared files")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    options.segmentation.trilinear = !nearest;
    openvdb::initialize();
    options.classify.normals = options.segmentation.useNormals = !noNormals;

    try {
        fs::create_directories(scratch);
        std::vector<DatasetResult> results;
        for (const std::string& d : datasets) results.push_back(benchDataset(d, options, runs, scratch));
        printTables(results, options, runs);
    } catch (const std::exception& e) {  // bad input, or no such dataset in the manifest
        std::fprintf(stderr, "prep_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}

// Preprocessing benchmark: per dataset, the median over several runs of each stage's time (load, classify,
// segment, each distance field, write, and reading the prepared file back), the bytes of every field, and
// what the segmentation produced. Prints Markdown tables.
#include <sys/resource.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "core/errors.h"
#include "core/prepared_file.h"
#include "preprocess/pipeline/prepare.h"
#include "support/datasets.h"

namespace {
namespace fs = std::filesystem;

const std::vector<std::string> kStages = {"load",  "classify", "segment", "pc",      "acd",
                                          "eacd",  "write",    "read",    "read cpu"};
const std::vector<std::string> kChunks = {"sigma", "colour", "normal", "labels", "pc", "acd", "eacd"};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

// CPU seconds of this process, all threads: on a shared machine it says what a read costs when wall time cannot.
double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(u.ru_utime) + seconds(u.ru_stime);
}

struct DatasetResult {
    std::string name;
    std::map<std::string, std::vector<double>> seconds;  // per stage, one entry per run
    nlohmann::json statistics;                          // from the last run (identical every run)
    std::uintmax_t fileBytes = 0;
};

vr::test::DatasetEntry findDataset(const std::string& file) {
    for (const auto& e : vr::test::manifest())
        if (e.file == file) return e;
    throw vr::InputError(file + ": not in " + (vr::test::datasetsDir() / "MANIFEST.tsv").string());
}

DatasetResult benchDataset(const std::string& file, const vr::PrepareOptions& base, int runs, const fs::path& scratch) {
    vr::test::DatasetEntry e = findDataset(file);
    vr::PrepareOptions options = base;
    options.raw.spacing = e.spacing;
    options.classify.transferFunction = vr::loadTransferFunction(vr::test::datasetsDir() / e.tf);
    fs::path out = scratch / (file + ".vprep");
    DatasetResult result{file, {}, {}, 0};
    for (int run = 0; run < runs; ++run) {
        vr::PrepareResult r = vr::prepareFile(vr::test::datasetsDir() / file, out, options);
        for (const vr::StageTime& t : r.stages) result.seconds[t.stage].push_back(t.seconds);
        double cpu = cpuSeconds();
        auto start = std::chrono::steady_clock::now();
        vr::PreparedVolume back = vr::readPrepared(out, options.fields, options.classify.normals);
        result.seconds["read"].push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        result.seconds["read cpu"].push_back(cpuSeconds() - cpu);
        result.statistics = r.prepared.meta.statistics;
        result.fileBytes = r.fileBytes;
        std::fprintf(stderr, "%s: run %d of %d done\n", file.c_str(), run + 1, runs);
    }
    fs::remove(out);
    return result;
}

void printTables(const std::vector<DatasetResult>& results, const vr::PrepareOptions& o, int runs) {
    std::printf("Preprocessing, T_o = %g, T_a = %g deg, normals %s, %s sampling, %zu threads; median of %d runs.\n\n",
                o.segmentation.opacityThreshold, o.segmentation.angleThresholdDeg, o.classify.normals ? "on" : "off",
                o.segmentation.trilinear ? "trilinear" : "nearest", std::size_t(tbb::info::default_concurrency()), runs);
    std::printf("Seconds per stage (pc: on its own, with its own ACD passes; eacd: on top of acd; read: readPrepared "
                "of every field written, wall and CPU time of all threads):\n\n| dataset | voxels |");
    for (const auto& s : kStages) std::printf(" %s |", s.c_str());
    std::printf(" total (no read) |\n|---|---:|");
    for (std::size_t i = 0; i <= kStages.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (const auto& r : results) {
        std::printf("| %s | %zu |", r.name.c_str(), r.statistics["voxels"].get<std::size_t>());
        double total = 0;
        for (const auto& s : kStages) {
            if (!r.seconds.count(s)) {
                std::printf(" - |");
                continue;
            }
            double m = median(r.seconds.at(s));
            if (!s.starts_with("read")) total += m;
            std::printf(" %.3f |", m);
        }
        std::printf(" %.3f |\n", total);
    }

    std::printf("\nMiB per chunk:\n\n| dataset |");
    for (const auto& c : kChunks) std::printf(" %s |", c.c_str());
    std::printf(" file |\n|---|");
    for (std::size_t i = 0; i <= kChunks.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (const auto& r : results) {
        std::printf("| %s |", r.name.c_str());
        for (const auto& c : kChunks) std::printf(" %.1f |", mib(r.statistics["bytes"][c].get<double>()));
        std::printf(" %.1f |\n", mib(double(r.fileBytes)));
    }

    std::printf("\nRegions and mean leaps (voxels; ACD edge and EACD extents of octant 0):\n\n"
                "| dataset | regions | mean region size | PC radius | ACD edge | EACD extents |\n|---|---:|---:|---:|---:|---|\n");
    for (const auto& r : results) {
        const nlohmann::json& s = r.statistics;
        const nlohmann::json& l = s["leaps"];
        std::printf("| %s | %u | %.1f | %s | %s | %s |\n", r.name.c_str(), s["regions"].get<uint32_t>(),
                    s["meanRegionSize"].get<double>(),
                    l.contains("pcMeanRadius") ? std::to_string(l["pcMeanRadius"].get<double>()).c_str() : "-",
                    l.contains("acdMeanEdge") ? std::to_string(l["acdMeanEdge"][0].get<double>()).c_str() : "-",
                    l.contains("eacdMeanExtent") ? l["eacdMeanExtent"][0].dump().c_str() : "-");
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
    app.add_flag("--trilinear", options.segmentation.trilinear, "regions for trilinear sampling");
    app.add_flag("--no-normals", noNormals, "no gradients (T_a ignored)");
    app.add_option("--runs", runs, "runs per dataset (the median is printed)")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--scratch", scratch, "folder for the prepared files")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    options.classify.normals = options.segmentation.useNormals = !noNormals;

    try {
        fs::create_directories(scratch);
        std::vector<DatasetResult> results;
        for (const std::string& d : datasets) results.push_back(benchDataset(d, options, runs, scratch));
        printTables(results, options, runs);
    } catch (const vr::InputError& e) {
        std::fprintf(stderr, "prep_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}

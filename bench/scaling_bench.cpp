// Preprocessing cost against volume size: per edge N (64 .. 512, N^3 voxels), the wall and CPU seconds of every
// stage (classify, segment, pc, acd, eacd) of a full staged preparation, and of the two incremental ones: a
// threshold change (segmentation and fields) and a transfer-function change (classification too). For a
// synthetic phantom made at each size and a real volume resampled (trilinear) to each size. Prints Markdown
// tables with nanoseconds per voxel, so that linear growth reads as a flat column. One size is alive at a time.
// --checksums prints CRC-32 checksums of every array the scenarios make (classification, labels, fields), so that
// a faster stage can be checked bit for bit. Each size's peak resident memory is printed too (docs/BENCH.md: memory).
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <utility>

#include "bench_checks.h"
#include "resampled_volume.h"
#include "io/crc32.h"
#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "support/datasets.h"
#include "sweep/order_statistics.h"
#include "tools/peak_resident.h"

namespace {
namespace fs = std::filesystem;
using vr::median;
using vr::Vec3i;

const std::vector<std::string> kStages = {"classify", "segment", "pc", "acd", "eacd"};
const std::vector<std::string> kScenarios = {"full", "threshold change", "TF change"};


// Per scenario and stage (and "total" for the whole prepare call), one wall and one CPU time per run.
struct SizeResult {
    std::string volume;
    int edge = 0;
    std::map<std::string, std::map<std::string, std::vector<double>>> wall, cpu;
    uint32_t regions = 0;
    double peakBytes = 0;  // the process's peak resident memory while this size ran
    std::map<std::string, std::string> checksums;  // per scenario, of its first run (--checksums)
};

// Checksums of every array of a preparation, so that a faster stage can be checked bit for bit.
std::string checksums(const vr::PreparedVolume& p) {
    using vr::crc32Of;
    uint32_t acd = 0, eacd = 0;
    for (int o = 0; o < vr::kOctants; ++o) {
        acd = crc32Of(p.fields.acd[o], acd);
        eacd = crc32Of(p.fields.eacd[o].data(), p.fields.eacd[o].bytes(), eacd);
    }
    char text[160];
    std::snprintf(text, sizeof text, "table %08x %08x labels %08x PC %08x ACD %08x EACD %08x",
                  crc32Of(p.classification.table.sigma), crc32Of(p.classification.table.colour),
                  crc32Of(p.regions.label), crc32Of(p.fields.pc), acd, eacd);
    return text;
}

void record(SizeResult& r, const std::string& scenario, const vr::StagedPreparation& staged,
            const vr::StageTime& total) {
    for (const vr::StageTime& t : staged.lastStages()) {
        r.wall[scenario][t.stage].push_back(t.seconds);
        r.cpu[scenario][t.stage].push_back(t.cpuSeconds);
    }
    r.wall[scenario]["total"].push_back(total.seconds);
    r.cpu[scenario]["total"].push_back(total.cpuSeconds);
}

// The three scenarios on one volume, `runs` times: a fresh preparation, then a new T_o, then a new TF (every
// opacity scaled by 0.8). While a run is timed, its preparation holds the only copy of the volume, as volprep's
// does (a second one took 0.5 GB more at 512^3, where fresh pages cost more as the footprint grows).
SizeResult benchSize(const std::string& name, vr::Volume volume, const vr::PrepareOptions& base, int runs,
                     bool withChecksums, vr::bench::Checks& checks) {
    SizeResult r{name, volume.grid.dims.x, {}, {}, 0, 0, {}};
    vr::resetPeakResident();
    vr::PrepareOptions thresholdChanged = base;
    thresholdChanged.segmentation.opacityThreshold *= 2;
    vr::PrepareOptions tfChanged = thresholdChanged;
    for (auto& p : tfChanged.classify.transferFunction->opacity) p.opacity *= 0.8;
    for (int run = 0; run < runs; ++run) {
        vr::StagedPreparation staged(std::move(volume));
        const std::pair<std::string, const vr::PrepareOptions*> steps[] = {
            {"full", &base}, {"threshold change", &thresholdChanged}, {"TF change", &tfChanged}};
        for (const auto& [scenario, options] : steps) {
            vr::StageClock clock;
            const vr::PreparedVolume& p = staged.prepare(*options);
            record(r, scenario, staged, clock.stop("total"));
            if (scenario == "full") r.regions = p.regions.count;
            if (!withChecksums) continue;
            // Printed for the first run; every later run must make the same arrays, bit for bit.
            const std::string sums = checksums(p);
            if (run == 0) {
                r.checksums[scenario] = sums;
                std::fprintf(stderr, "%s %s %d^3 CRC-32: %s\n", name.c_str(), scenario.c_str(), r.edge, sums.c_str());
            } else {
                checks.expect(sums == r.checksums[scenario], "%s %s %d^3: run %d made other arrays (%s) than the first",
                              name.c_str(), scenario.c_str(), r.edge, run + 1, sums.c_str());
            }
        }
        volume = staged.volume();  // for the next run
    }
    r.peakBytes = double(vr::peakResidentBytes());
    std::fprintf(stderr, "%s %d^3:", name.c_str(), r.edge);  // the figures so far, should a long run be cut short
    for (const auto& s : kScenarios)
        std::fprintf(stderr, " %s %.3f s (%.3f CPU s)", s.c_str(), median(r.wall[s]["total"]),
                     median(r.cpu[s]["total"]));
    std::fprintf(stderr, "\n");
    return r;
}

// What the tables say of one size: regions partition the voxels; the full preparation ran every stage, the
// threshold change segmentation and the fields only, the TF change classification too; every prepare() call took
// time, and at least as long as its stages together; the process's peak memory was measured.
void checkSize(vr::bench::Checks& checks, const SizeResult& r, int runs) {
    const std::string size = r.volume + " " + std::to_string(r.edge) + "^3";
    const double voxels = std::pow(double(r.edge), 3);
    checks.expect(r.regions >= 1 && r.regions <= voxels, "%s: %u regions, not within 1..%.0f voxels", size.c_str(),
                  r.regions, voxels);
    const std::map<std::string, std::vector<std::string>> ran{
        {"full", kStages}, {"threshold change", {"segment", "pc", "acd", "eacd"}}, {"TF change", kStages}};
    for (const auto& scenario : kScenarios) {
        const auto& wall = r.wall.at(scenario);
        for (const auto& stage : kStages) {
            const bool expected = std::find(ran.at(scenario).begin(), ran.at(scenario).end(), stage) !=
                                  ran.at(scenario).end();
            checks.expect(wall.count(stage) == expected, "%s: %s %s the stage %s", size.c_str(), scenario.c_str(),
                          expected ? "did not run" : "ran", stage.c_str());
        }
        checks.expect(wall.count("total") && int(wall.at("total").size()) == runs, "%s: %s timed %zu of %d runs",
                      size.c_str(), scenario.c_str(), wall.count("total") ? wall.at("total").size() : 0, runs);
        for (std::size_t run = 0; wall.count("total") && run < wall.at("total").size(); ++run) {
            double stages = 0;
            for (const auto& [stage, times] : wall)
                if (stage != "total" && run < times.size()) stages += times[run];
            const double total = wall.at("total")[run];
            checks.expect(total > 0 && stages > 0 && stages <= total * (1 + 1e-9) + 1e-6,
                          "%s: %s run %zu took %g s in all but %g s in its stages", size.c_str(), scenario.c_str(),
                          run + 1, total, stages);
        }
        for (const auto& [stage, times] : r.cpu.at(scenario))
            for (double t : times)
                checks.expect(t >= 0, "%s: %s %s took %g CPU s", size.c_str(), scenario.c_str(), stage.c_str(), t);
    }
    if (std::ifstream("/proc/self/status")) {
        checks.expect(r.peakBytes > 0, "%s: peak resident memory %g bytes", size.c_str(), r.peakBytes);
    }
}

void printTable(const char* title, const std::vector<SizeResult>& results,
                std::map<std::string, std::map<std::string, std::vector<double>>> SizeResult::*times) {
    std::printf("%s\n\n| volume | N | voxels | regions |", title);
    for (const auto& s : kStages) std::printf(" %s |", s.c_str());
    for (const auto& s : kScenarios) std::printf(" %s | ns/voxel |", s.c_str());
    std::printf("\n|---|---:|---:|---:|");
    for (std::size_t i = 0; i < kStages.size() + 2 * kScenarios.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (const SizeResult& r : results) {
        const double voxels = std::pow(double(r.edge), 3);
        const auto& full = (r.*times).at("full");
        std::printf("| %s | %d | %.0f | %u |", r.volume.c_str(), r.edge, voxels, r.regions);
        for (const auto& s : kStages)
            std::printf(full.count(s) ? " %.3f |" : " - |", full.count(s) ? median(full.at(s)) : 0);
        for (const auto& s : kScenarios) {
            const double t = median((r.*times).at(s).at("total"));
            std::printf(" %.3f | %.1f |", t, 1e9 * t / voxels);
        }
        std::printf("\n");
    }
    std::printf("\n");
}

// Peak memory per size. It includes the process's baseline, about 0.15 GB here (libraries, and the real volume's
// source kept for resampling), which dominates the small sizes.
void printPeakMemory(const std::vector<SizeResult>& results) {
    std::printf("Peak resident memory (whole process, all scenarios and runs of a size):\n\n"
                "| volume | N | GB | B/voxel |\n|---|---:|---:|---:|\n");
    for (const SizeResult& r : results)
        std::printf("| %s | %d | %.2f | %.1f |\n", r.volume.c_str(), r.edge, r.peakBytes * 1e-9,
                    r.peakBytes / std::pow(double(r.edge), 3));
    std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Preprocessing time per stage against volume size (64^3 .. 512^3): full, threshold change, TF change"};
    bool shortMode = false, checksums = false;
    std::vector<int> edges{64, 128, 256, 512};
    int runs = 3;
    std::string real = "vispy_mri_head_256x256x256_uint8.raw.gz";
    std::string phantom = "engine", volumes = "both";
    vr::PrepareOptions options;
    options.segmentation = {0.05, 10, true, false};
    app.add_flag("--short", shortMode, "64^3 and 128^3 only, one run: a few seconds (CTest)");
    app.add_option("--sizes", edges, "edges N of the N^3 volumes")->delimiter(',')->check(CLI::Range(2, 1600))
        ->capture_default_str();
    app.add_option("--runs", runs, "runs per size (medians are printed)")->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--real", real, "raw dataset of MANIFEST.tsv resampled to each size")->capture_default_str();
    app.add_option("--phantom", phantom, "engine or shells")->check(CLI::IsMember({"engine", "shells"}))
        ->capture_default_str();
    app.add_option("--volumes", volumes, "which to time: the phantom, the real volume or both")
        ->check(CLI::IsMember({"both", "phantom", "real"}))->capture_default_str();
    app.add_option("--to", options.segmentation.opacityThreshold, "T_o (a threshold change doubles it)")
        ->capture_default_str();
    app.add_option("--ta", options.segmentation.angleThresholdDeg, "T_a, degrees")->capture_default_str();
    app.add_flag("--checksums", checksums, "print checksums of every array each scenario's first run makes");
    CLI11_PARSE(app, argc, argv);
    if (shortMode) edges = {64, 128}, runs = 1;

    vr::bench::Checks checks("scaling_bench");
    try {
        const fs::path dir = vr::test::datasetsDir();
        const vr::test::DatasetEntry entry = vr::test::dataset(real);
        vr::RawOptions raw;
        raw.dims = entry.dims;
        raw.type = entry.type;
        raw.spacing = entry.spacing;
        const vr::Volume source = vr::loadVolume(dir / entry.file, raw);
        std::string realName = entry.file.substr(0, entry.file.find(".raw"));  // NAME_DxDxD_TYPE -> NAME
        for (int cut = 0; cut < 2; ++cut) realName.resize(std::min(realName.size(), realName.rfind('_')));

        vr::PrepareOptions phantomOptions = options, realOptions = options;
        phantomOptions.classify.transferFunction =
            vr::loadTransferFunction(dir / (phantom == "shells" ? "cranium_ct.tf.json" : "sim.tf.json"));
        realOptions.classify.transferFunction = vr::loadTransferFunction(dir / entry.tf);

        std::vector<SizeResult> results;
        for (int n : edges) {
            const Vec3i dims{n, n, n};
            if (volumes != "real") {
                results.push_back(benchSize("phantom " + phantom,
                                            phantom == "shells" ? vr::shellsPhantom(dims) : vr::enginePhantom(dims),
                                            phantomOptions, runs, checksums, checks));
            }
            if (volumes != "phantom") {
                results.push_back(
                    benchSize(realName, vr::bench::resample(source, dims), realOptions, runs, checksums, checks));
            }
        }
        std::stable_sort(results.begin(), results.end(),
                         [](const SizeResult& a, const SizeResult& b) { return a.volume < b.volume; });

        std::printf("Staged preparation against size: T_o = %g (a threshold change doubles it), T_a = %g deg, "
                    "normals on, nearest sampling, EACD code %s, %d threads; median of %d runs. Stages of the full "
                    "preparation; full, threshold change and TF change are whole prepare() calls (%s resampled "
                    "trilinearly to N^3; the phantom made at N^3).\n\n",
                    options.segmentation.opacityThreshold, options.segmentation.angleThresholdDeg,
                    std::string(vr::extentCodeName(options.eacdCode)).c_str(), tbb::info::default_concurrency(),
                    runs, entry.file.c_str());
        printTable("Wall seconds:", results, &SizeResult::wall);
        printTable("CPU seconds (all threads; steadier than wall time on a shared machine):", results,
                   &SizeResult::cpu);
        printPeakMemory(results);
        checks.expect(!results.empty(), "no size was timed");
        for (const SizeResult& r : results) checkSize(checks, r, runs);
    } catch (const vr::InputError& e) {
        std::fprintf(stderr, "scaling_bench: %s\n", e.what());
        return 1;
    }
    return checks.exitStatus();
}

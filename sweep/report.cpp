#include "sweep/report.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/atomic_file.h"
#include "core/errors.h"
#include "sweep/error_plot.h"
#include "sweep/image_strip.h"
#include "sweep/metrics/pixel_fractions.h"
#include "sweep/metrics/ssim.h"
#include "sweep/run_sweep.h"
#include "sweep/selection.h"
#include "sweep/stereo_row.h"

namespace vr {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string fmt(const char* format, double v) {
    char s[64];
    std::snprintf(s, sizeof s, format, v);
    return s;
}
std::string db(double psnr) { return std::isinf(psnr) ? "inf" : fmt("%.1f", psnr); }
std::string setting(const SweepRow& r) {
    return r.caster + " T_o=" + thresholdText(r.opacityThreshold) + " T_a=" + thresholdText(r.angleThreshold);
}

const SweepRow* find(const std::vector<SweepRow>& rows, const std::string& caster, double to, double ta) {
    for (const SweepRow& r : rows)
        if (r.caster == caster && r.opacityThreshold == to && r.angleThreshold == ta) return &r;
    return nullptr;
}

void settingsTable(std::ostream& md, const std::vector<SweepRow>& rows) {
    md << "| T_o | T_a | caster | regions | segment+fields s | device ms median | p95 | speed-up | iter/ray mean "
          "| p95 | max | field MB | PSNR mean | PSNR worst | SSIM worst | RMSE mean | max abs worst "
          "| % off>1/255 worst | % dE00>2.3 worst |\n"
       << "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const SweepRow& r : rows) {
        const double prep = r.segmentSeconds + r.pcSeconds + r.acdSeconds + r.eacdSeconds;
        md << "| " << thresholdText(r.opacityThreshold) << " | " << thresholdText(r.angleThreshold) << " | "
           << r.caster << " | " << r.regions << " | " << fmt("%.2f", prep) << " | " << fmt("%.2f", r.deviceMsMedian)
           << " | " << fmt("%.2f", r.deviceMsP95) << " | " << fmt("%.2fx", speedUp(r)) << " | "
           << fmt("%.1f", r.iterationsMean) << " | " << fmt("%.0f", r.iterationsP95) << " | "
           << fmt("%.0f", r.iterationsMax) << " | " << fmt("%.1f", double(r.fieldBytes) / 1e6) << " | "
           << db(r.error.mean.psnr) << " | " << db(r.error.worst.psnr) << " | " << fmt("%.4f", r.error.worst.ssim)
           << " | " << fmt("%.2e", std::sqrt(r.error.mean.mse)) << " | " << fmt("%.3f", r.error.worst.maxAbs)
           << " | " << fmt("%.2f", r.error.worst.percentOff8Bit) << " | "
           << fmt("%.2f", r.error.worst.percentPerceptual) << " |\n";
    }
}

void bestSettings(std::ostream& md, const std::vector<SweepRow>& rows) {
    md << "\nBest setting per caster meeting the target (worst view: PSNR >= " << kTargetPsnr << " dB and < "
       << kTargetPercentOff << " % of pixels off by more than 1/255), by speed-up over the primitive caster:\n\n"
       << "| caster | T_o | T_a | speed-up | PSNR worst | % off>1/255 worst | % dE00>2.3 worst |\n"
       << "|---|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string& caster : castersOf(rows)) {
        if (caster == "primitive") continue;
        if (const SweepRow* b = bestMeetingTarget(rows, caster))
            md << "| " << caster << " | " << thresholdText(b->opacityThreshold) << " | "
               << thresholdText(b->angleThreshold) << " | " << fmt("%.2fx", speedUp(*b)) << " | "
               << db(b->error.worst.psnr) << " | " << fmt("%.2f", b->error.worst.percentOff8Bit) << " | "
               << fmt("%.2f", b->error.worst.percentPerceptual) << " |\n";
        else
            md << "| " << caster << " | - | - | - | none meets the target | | |\n";
    }
    if (const SweepRow* best = bestMeetingTarget(rows)) {
        md << "\n**Best overall:** " << setting(*best) << ", " << fmt("%.2fx", speedUp(*best))
           << " faster than the primitive caster, PSNR worst view " << db(best->error.worst.psnr) << " dB.\n";
    }
    // How much the thresholds change the work: when the iterations per ray hardly move, so do the render times,
    // and the differences in speed-up between settings are timing noise.
    md << "\nIterations per ray (mean) over the grid:";
    const char* separator = " ";
    for (const std::string& caster : castersOf(rows)) {
        double lo = INFINITY, hi = 0;
        for (const SweepRow& r : rows)
            if (r.caster == caster) {
                lo = std::min(lo, r.iterationsMean);
                hi = std::max(hi, r.iterationsMean);
            }
        md << separator << caster << " " << fmt("%.2f", lo) << " .. " << fmt("%.2f", hi);
        separator = "; ";
    }
    md << ".\n";
    if (const SweepRow* eacd = bestMeetingTarget(rows, "eacd")) {
        md << "\n**Speed-up target (EACD >= " << kTargetSpeedUp << "x faster with the quality target):** "
           << (speedUp(*eacd) >= kTargetSpeedUp ? "met" : "not met") << " here; best EACD setting T_o="
           << thresholdText(eacd->opacityThreshold) << " T_a=" << thresholdText(eacd->angleThreshold) << " at "
           << fmt("%.2fx", speedUp(*eacd)) << ".";
        // The speed-up is the iteration ratio divided by what one leaping iteration costs in primitive samples:
        // the two figures say whether leaping finds too few long spans or each leap costs too much.
        const SweepRow* primitive = find(rows, "primitive", eacd->opacityThreshold, eacd->angleThreshold);
        if (primitive && eacd->iterationsMean > 0 && speedUp(*eacd) > 0) {
            const double fewer = primitive->iterationsMean / eacd->iterationsMean;
            md << " It runs " << fmt("%.1fx", fewer) << " fewer iterations per ray than the primitive caster ("
               << fmt("%.1f", primitive->iterationsMean) << " -> " << fmt("%.1f", eacd->iterationsMean)
               << "), and each costs the device time of " << fmt("%.2f", fewer / speedUp(*eacd))
               << " primitive samples; " << kTargetSpeedUp << "x would need at most "
               << fmt("%.2f", fewer / kTargetSpeedUp) << ".";
        }
        md << "\n";
    }
}

void paretoList(std::ostream& md, const std::vector<SweepRow>& rows) {
    md << "\nPareto front (render time relative to primitive vs mean PSNR; exact = inf):\n\n";
    const std::vector<bool> front = psnrFront(rows);
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (front[i])
            md << "- " << setting(rows[i]) << ": " << fmt("%.3f", rows[i].ratioToPrimitive) << " of primitive's time, "
               << "PSNR " << db(rows[i].error.mean.psnr) << " dB, " << fmt("%.2f", rows[i].error.mean.percentPerceptual)
               << " % dE00 > 2.3\n";
}

// One dataset's peers against our casters, for the table at the end of the report.
struct PeerSummary {
    std::string dataset;
    int width = 0, height = 0, views = 0;
    double primitiveMs = 0, eacdMs = 0;
    std::string vtk;  // the fastest VTK renderer; empty when none rendered
    double vtkMs = 0;
};

std::string peerPsnr(const json& p) {
    if (!p.contains("psnr")) return "-";
    return p["psnr"].is_string() ? p["psnr"].get<std::string>() : fmt("%.1f", p["psnr"].get<double>());
}

// Our reference and EACD image beside each peer's, error maps below: the strip strips/DATASET_peers.png.
void peersStrip(std::ostream& md, const json& peers, const fs::path& outDir, const std::string& dataset,
                const SweepRow* eacd) {
    const fs::path images = imagesDir(outDir, dataset);
    std::vector<StripColumn> cols{{"ours: reference", "primitive T=0", images / "reference.png", {}}};
    if (eacd)
        cols.push_back({"ours: eacd T=0", fmt("%.1f ms", eacd->deviceMsMedian), images / imageName("eacd", 0, 0, false),
                        images / imageName("eacd", 0, 0, true)});
    for (const json& p : peers)
        if (p.contains("image") && p.contains("error_map"))
            cols.push_back({p.value("peer", "?"), fmt("%.1f ms", p.value("median_ms", 0.0)) + ", PSNR " + peerPsnr(p),
                            p["image"].get<std::string>(), p["error_map"].get<std::string>()});
    for (const StripColumn& c : cols)
        if (!fs::exists(c.image) || (!c.errorMap.empty() && !fs::exists(c.errorMap))) return;
    if (cols.size() < 3) return;
    writeImageStrip(cols, outDir / "strips" / (dataset + "_peers.png"));
    md << "\nSide by side, view 0 (top: image; bottom: |difference to our reference| x10), columns:";
    for (const StripColumn& c : cols) md << " " << c.label << " (" << c.subLabel << ");";
    md << "\n\n![peers side by side](strips/" << dataset << "_peers.png)\n";
}

PeerSummary peersTable(std::ostream& md, const fs::path& file, const std::vector<SweepRow>& rows,
                       const fs::path& outDir) {
    std::ifstream in(file);
    const json peers = json::parse(in);
    const SweepRow* primitive = find(rows, "primitive", 0, 0);
    const SweepRow* eacd = find(rows, "eacd", 0, 0);
    PeerSummary summary{rows.front().dataset, rows.front().width, rows.front().height, rows.front().views,
                        primitive ? primitive->deviceMsMedian : 0, eacd ? eacd->deviceMsMedian : 0, "", 0};
    md << "\nPeers (scripts/peers.sh, same views, size and sample distance; their render ms per view as each "
          "measures it, against our device ms median at T_o = T_a = 0 (dispatches only; like the peers' times, "
          "without the upload); ratio > 1: the peer is slower; error against this section's reference):\n\n"
       << "| peer | median ms | / our primitive | / our EACD | PSNR | SSIM | notes |\n"
       << "|---|---:|---:|---:|---:|---:|---|\n";
    for (const json& p : peers) {
        md << "| " << p.value("peer", "?") << " | ";
        if (!p.contains("median_ms")) {
            md << "- | - | - | - | - | " << p.value("error", "") << " |\n";
            continue;
        }
        const double ms = p["median_ms"].get<double>();
        const std::string name = p.value("peer", "?");
        if (name.rfind("vtk", 0) == 0 && ms > 0 && (summary.vtk.empty() || ms < summary.vtkMs)) {
            summary.vtk = name;
            summary.vtkMs = ms;
        }
        md << fmt("%.1f", ms) << " | "
           << (primitive && primitive->deviceMsMedian > 0 ? fmt("%.2f", ms / primitive->deviceMsMedian) : "-")
           << " | " << (eacd && eacd->deviceMsMedian > 0 ? fmt("%.2f", ms / eacd->deviceMsMedian) : "-") << " | ";
        if (p.contains("psnr"))
            md << peerPsnr(p) << " | " << fmt("%.4f", p.value("ssim", 0.0)) << " | ";
        else
            md << "- | - | ";
        md << p.value("notes", "") << (p.contains("error") ? " " + p["error"].get<std::string>() : "") << " |\n";
    }
    if (!summary.vtk.empty() && summary.eacdMs > 0)
        md << "\n**EACD against the fastest VTK renderer (" << summary.vtk << "):** " << fmt("%.1f", summary.vtkMs)
           << " ms against " << fmt("%.1f", summary.eacdMs) << " ms: EACD is "
           << (summary.vtkMs >= summary.eacdMs ? fmt("%.2fx faster", summary.vtkMs / summary.eacdMs)
                                                : fmt("%.2fx slower", summary.eacdMs / summary.vtkMs))
           << ".\n";
    peersStrip(md, peers, outDir, rows.front().dataset, eacd);
    return summary;
}

// Per dataset, the time its sweep spent preprocessing and rendering, from the CSV (render seconds estimated as
// the median wall ms x views; the primitive caster's renders are the reference's, counted once).
void timeTable(std::ostream& md, const std::vector<SweepRow>& all) {
    md << "## Where the time went (from sweep.csv)\n\n"
       << "| dataset | settings | segment s | PC s | ACD s | EACD s | render s: primitive | PC | ACD | EACD |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string& dataset : datasetsOf(all)) {
        const std::vector<SweepRow> rows = rowsOf(all, dataset);
        std::map<std::string, double> render;
        double segment = 0, pc = 0, acd = 0, eacd = 0;
        int settings = 0;
        for (const SweepRow& r : rows) {
            const double seconds = r.wallMsMedian * r.views / 1000;
            if (r.caster != "primitive") {
                render[r.caster] += seconds;
                continue;
            }
            if (settings++ == 0) render["primitive"] = seconds;
            segment += r.segmentSeconds, pc += r.pcSeconds, acd += r.acdSeconds, eacd += r.eacdSeconds;
        }
        md << "| " << dataset << " | " << settings << " | " << fmt("%.1f", segment) << " | " << fmt("%.1f", pc)
           << " | " << fmt("%.1f", acd) << " | " << fmt("%.1f", eacd);
        for (const char* c : {"primitive", "pc", "acd", "eacd"}) md << " | " << fmt("%.1f", render[c]);
        md << " |\n";
    }
    md << "\n";
}

// The targets of a stereo pair (docs/BENCH.md "Stereo pairs"): the pair within 1.4 x one eye's time (on the CTs),
// and the reused right eye at PSNR >= 40 dB with < 3 % of pixels at CIEDE2000 > 2.3 against its full render.
constexpr double kStereoPairTarget = 1.4, kStereoPsnrTarget = 40, kStereoPerceptualTarget = 3;

void stereoTableHead(std::ostream& md, bool withDataset) {
    md << "| " << (withDataset ? "dataset | " : "") << "caster | one eye ms | pair ms | pair / one eye | both eyes "
          "in full ms | reprojection ms | right eye re-cast | PSNR mean (worst) | SSIM worst | % off>1/255 mean | "
          "% dE00>2.3 mean (worst) | time target | quality target |\n|"
       << (withDataset ? "---|" : "") << "---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n";
}

void stereoTableRow(std::ostream& md, const StereoRow& r, bool withDataset) {
    const double ratio = r.oneEyeMs > 0 ? r.pairMs / r.oneEyeMs : 0;
    const bool quality = r.error.mean.psnr >= kStereoPsnrTarget &&
                         r.error.mean.percentPerceptual < kStereoPerceptualTarget;
    md << "| " << (withDataset ? r.dataset + " | " : "") << r.caster << " | " << fmt("%.1f", r.oneEyeMs) << " | "
       << fmt("%.1f", r.pairMs) << " | " << fmt("%.2fx", ratio) << " | " << fmt("%.1f", r.fullPairMs) << " | "
       << fmt("%.1f", r.reprojectMs) << " | " << fmt("%.1f %%", r.recastPercent) << " | " << db(r.error.mean.psnr)
       << " (" << db(r.error.worst.psnr) << ") | " << fmt("%.4f", r.error.worst.ssim) << " | "
       << fmt("%.2f", r.error.mean.percentOff8Bit) << " | " << fmt("%.2f", r.error.mean.percentPerceptual) << " ("
       << fmt("%.2f", r.error.worst.percentPerceptual) << ") | " << (ratio <= kStereoPairTarget ? "met" : "missed")
       << " | " << (quality ? "met" : "missed") << " |\n";
}

// The dataset's stereo row: the pair against one eye, the reused right eye against its full render.
void stereoSection(std::ostream& md, const StereoRow& r) {
    md << "\nStereo pairs (perspective views of the same orbit, the eyes 1/" << fmt("%.0f", 1 / r.separationPerFocus)
       << " of the focus distance apart; the right eye reprojected from the left and cast again where the "
          "reprojection cannot vouch for a pixel, against both eyes cast in full; medians over the views; the "
          "plot's stereo point is the pair's time over one eye's):\n\n";
    stereoTableHead(md, false);
    stereoTableRow(md, r, false);
}

// Every dataset's stereo row in one table.
void stereoSummary(std::ostream& md, const std::vector<StereoRow>& rows) {
    if (rows.empty()) return;
    md << "## Stereo pairs at a glance\n\nPer dataset, an orbit of pairs whose right eye is the left's reprojection "
          "(docs/ALGORITHMS.md section 12). Targets: the pair within "
       << kStereoPairTarget << "x one eye's device time (on the CTs); PSNR >= " << kStereoPsnrTarget << " dB and < "
       << kStereoPerceptualTarget << " % of pixels with CIEDE2000 > 2.3 (means over the views).\n\n";
    stereoTableHead(md, true);
    for (const StereoRow& r : rows) stereoTableRow(md, r, true);
    md << "\n";
}

// Every dataset with peers in one table: our EACD against the fastest VTK renderer.
void peersSummary(std::ostream& md, const std::vector<PeerSummary>& all) {
    if (all.empty()) return;
    md << "## Peers at a glance: EACD against the fastest VTK renderer\n\n"
       << "Same image size, views and sample distance in one run; our device ms median at T_o = T_a = 0, the "
          "peers' render ms as each measures it (details and images in each dataset's section).\n\n"
       << "| dataset | image | views | our primitive ms | our EACD ms | fastest VTK | VTK ms | VTK ms / EACD ms "
          "(> 1: EACD faster) |\n"
       << "|---|---|---:|---:|---:|---|---:|---:|\n";
    for (const PeerSummary& s : all)
        md << "| " << s.dataset << " | " << s.width << "x" << s.height << " | " << s.views << " | "
           << fmt("%.1f", s.primitiveMs) << " | " << fmt("%.1f", s.eacdMs) << " | " << (s.vtk.empty() ? "-" : s.vtk)
           << " | " << (s.vtk.empty() ? "-" : fmt("%.1f", s.vtkMs)) << " | "
           << (s.vtk.empty() || s.eacdMs <= 0 ? "-" : fmt("%.1fx", s.vtkMs / s.eacdMs)) << " |\n";
    md << "\n";
}

// Reference, EACD (or the last caster) at the smallest thresholds, the best setting meeting the target, and the
// largest thresholds: the columns of the strip whose images exist.
std::vector<StripColumn> stripColumns(const fs::path& images, const std::vector<SweepRow>& rows) {
    std::vector<StripColumn> cols{{"reference", "primitive T=0", images / "reference.png", {}}};
    const std::vector<std::string> casters = castersOf(rows);
    const std::string caster = std::find(casters.begin(), casters.end(), "eacd") != casters.end() ? "eacd"
                                                                                                   : casters.back();
    std::vector<const SweepRow*> chosen;
    const SweepRow* smallest = nullptr;
    const SweepRow* largest = nullptr;
    for (const SweepRow& r : rows) {
        if (r.caster != caster) continue;
        const double size = r.opacityThreshold * 1000 + r.angleThreshold;  // order: T_o first, then T_a
        if (!smallest || size < smallest->opacityThreshold * 1000 + smallest->angleThreshold) smallest = &r;
        if (!largest || size > largest->opacityThreshold * 1000 + largest->angleThreshold) largest = &r;
    }
    for (const SweepRow* r : {smallest, bestMeetingTarget(rows, caster), largest})
        if (r && std::find(chosen.begin(), chosen.end(), r) == chosen.end()) chosen.push_back(r);
    for (const SweepRow* r : chosen) {
        const fs::path image = images / imageName(r->caster, r->opacityThreshold, r->angleThreshold, false);
        const fs::path error = images / imageName(r->caster, r->opacityThreshold, r->angleThreshold, true);
        if (fs::exists(image) && fs::exists(error))
            cols.push_back({r->caster + " " + thresholdText(r->opacityThreshold) + "/" +
                                thresholdText(r->angleThreshold),
                            "PSNR " + db(r->error.worst.psnr) + " dB", image, error});
    }
    return cols;
}

}  // namespace

fs::path writeReport(const fs::path& outDir) {
    const std::vector<SweepRow> all = readSweepCsv(outDir / "sweep.csv");
    const std::vector<StereoRow> stereo = readStereoCsv(outDir / "stereo.csv");
    if (all.empty()) throw fileError((outDir / "sweep.csv").string(), "no sweep results to report");
    const bool gnuplot = gnuplotAvailable();
    if (!gnuplot) std::fprintf(stderr, "volsweep: gnuplot not found (install gnuplot-nox): the plots are skipped\n");
    fs::create_directories(outDir / "plots");
    fs::create_directories(outDir / "strips");

    std::ostringstream md;
    md << "# Error against render time: the (T_o, T_a) sweep\n\n"
       << "Made by volsweep from `sweep.csv` (one row per dataset, setting and caster). Reference: the primitive "
          "caster at T_o = T_a = 0 on the same lattice, float RGB (premultiplied over black). Render times: Vulkan "
          "timestamp queries around the dispatches (device time; wall time where the queue has none), median and "
          "p95 over the views after one warm-up frame per caster; **speed-up** = the primitive caster's device "
          "median / the caster's, in the same run (the primitive caster reads no regions or fields, so its work and "
          "image do not depend on the thresholds: its row at every setting is the reference's renders, after one "
          "warm-up frame; on lavapipe only ratios hold, not ms). "
          "Preprocessing: wall seconds of segmentation and of each distance field (PC, the 8 ACD octants, EACD on "
          "top of ACD) at the setting; load and classification run once per dataset.\n\n"
          "Error figures per image over linear RGB, then over the views (mean; worst = the worst view): RMSE; PSNR "
          "in dB with peak 1 (of the mean MSE over the views, so one exact view does not make it infinite; inf = "
          "exact); max abs error; SSIM on linear luminance (Rec. 709 weights) with the **Gaussian 11x11 window, "
          "sigma 1.5** (K1 0.01, K2 0.03, valid positions only); % of pixels whose 8-bit sRGB value differs by "
          "more than 1 in some channel; % of pixels with **CIEDE2000 > "
       << kPerceptualDeltaE
       << "** (linear RGB with sRGB primaries -> XYZ -> CIELAB, D65 white; Sharma et al. 2005).\n\n";

    std::vector<PeerSummary> peerSummaries;
    for (const std::string& dataset : datasetsOf(all)) {
        const std::vector<SweepRow> rows = rowsOf(all, dataset);
        const SweepRow& first = rows.front();
        md << "## " << dataset << "\n\n"
           << first.width << "x" << first.height << " pixels, " << first.views << " views; " << first.render
           << ".\n\n";
        settingsTable(md, rows);
        bestSettings(md, rows);
        paretoList(md, rows);
        std::vector<SweepRow> stereoPoints;
        for (const StereoRow& r : stereo)
            if (r.dataset == dataset) {
                stereoSection(md, r);
                stereoPoints.push_back(r.plotted());
            }
        const fs::path plot = outDir / "plots" / (dataset + ".png");
        if (gnuplot) {
            plotErrorAgainstTime(rows, dataset + ": error against render time (labels T_o/T_a)", plot, stereoPoints);
            md << "\n![error against render time](plots/" << dataset << ".png)\n";
        } else {
            md << "\n(Plot skipped: gnuplot is not installed; `bash scripts/install-deps.sh gnuplot-nox`.)\n";
        }
        const std::vector<StripColumn> columns = stripColumns(imagesDir(outDir, dataset), rows);
        if (columns.size() > 1 && fs::exists(columns.front().image)) {
            writeImageStrip(columns, outDir / "strips" / (dataset + ".png"));
            md << "\nImage strip, view 0 (top: image; bottom: |difference to the reference| x10; labels: caster "
                  "T_o/T_a and the worst view's PSNR), columns:";
            for (const StripColumn& c : columns) md << " " << c.label << " (" << c.subLabel << ");";
            md << "\n\n![image strip](strips/" << dataset << ".png)\n";
        }
        const fs::path peers = outDir / ("peers_" + dataset + ".json");
        if (fs::exists(peers)) peerSummaries.push_back(peersTable(md, peers, rows, outDir));
        md << "\n";
    }
    peersSummary(md, peerSummaries);
    stereoSummary(md, stereo);
    timeTable(md, all);
    const fs::path report = outDir / "report.md";
    writeFileAtomically(report, [&](std::ostream& out) { out << md.str(); });
    return report;
}

}  // namespace vr

// OUTDIR/report.md from OUTDIR/sweep.csv (every dataset in it), with per dataset the plot of error against
// render time (plots/DATASET.png, when gnuplot is installed) and the image strip (strips/DATASET.png).
#pragma once
#include <filesystem>

namespace vr {

// Returns the report's path. A missing gnuplot is said in the report and on stderr; only the plots are skipped.
std::filesystem::path writeReport(const std::filesystem::path& outDir);

}  // namespace vr

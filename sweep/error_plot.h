// The plot of error against render time for one dataset, drawn by gnuplot (Debian package gnuplot-nox).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "sweep/sweep_row.h"

namespace vr {

// Whether a gnuplot executable is on the PATH.
bool gnuplotAvailable();

// Two panels: mean PSNR and the mean percentage of pixels with CIEDE2000 > 2.3 against the render time relative
// to the primitive caster (log scale), one point style per caster, each labelled "T_o/T_a", the Pareto front
// joined. `beside`: more points in styles of their own (a stereo pair: its time relative to one eye's), outside the
// front. Writes `png` and beside it the gnuplot script and data (NAME.gp, NAME.dat). Throws std::runtime_error
// when gnuplot fails.
void plotErrorAgainstTime(const std::vector<SweepRow>& rows, const std::string& title,
                          const std::filesystem::path& png, const std::vector<SweepRow>& beside = {});

}  // namespace vr

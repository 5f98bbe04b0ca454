#include "sweep/error_plot.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "sweep/selection.h"

namespace vr {
namespace fs = std::filesystem;

bool gnuplotAvailable() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

namespace {

// Gnuplot's single-quoted strings: a quote is doubled.
std::string quoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
    return out + "'";
}

// The front's points sorted by time, as a data block.
void writeFront(std::ofstream& out, const std::vector<SweepRow>& rows, const std::vector<bool>& front, bool psnr) {
    std::vector<std::pair<double, double>> points;
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (front[i]) points.emplace_back(rows[i].ratioToPrimitive,
                                          psnr ? plottedPsnr(rows[i]) : rows[i].error.mean.percentPerceptual);
    std::sort(points.begin(), points.end());
    for (const auto& [x, y] : points) out << x << ' ' << y << '\n';
    out << "\n\n";
}

}  // namespace

void plotErrorAgainstTime(const std::vector<SweepRow>& rows, const std::string& title, const fs::path& png,
                          const std::vector<SweepRow>& beside) {
    const fs::path data = fs::path(png).replace_extension(".dat");
    const fs::path script = fs::path(png).replace_extension(".gp");
    std::vector<SweepRow> points = rows;
    points.insert(points.end(), beside.begin(), beside.end());
    const std::vector<std::string> casters = castersOf(points);
    {
        // Blocks: one per caster (ratio, PSNR, perceptual %, label), then the two fronts.
        std::ofstream out(data);
        for (const std::string& c : casters) {
            out << "# " << c << '\n';
            for (const SweepRow& r : points)
                if (r.caster == c)
                    out << r.ratioToPrimitive << ' ' << plottedPsnr(r) << ' ' << r.error.mean.percentPerceptual
                        << ' ' << thresholdText(r.opacityThreshold) << '/' << thresholdText(r.angleThreshold)
                        << '\n';
            out << "\n\n";
        }
        writeFront(out, rows, psnrFront(rows), true);
        writeFront(out, rows, perceptualFront(rows), false);
        if (!out) throw std::runtime_error("cannot write " + data.string());
    }
    const std::size_t n = casters.size();
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 1600,700 font ',10' noenhanced\n"
       << "set output " << quoted(png.string()) << "\n"
       << "set datafile commentschars '#'\n"
       << "set multiplot layout 1,2 title " << quoted(title) << "\n"
       << "set logscale x\nset grid\n"
       << "set xlabel 'render time / primitive caster (device time, median over views; log)'\n";
    // Keys away from where the good points gather: top for PSNR, bottom for the perceptual percentage.
    auto panel = [&](const std::string& ylabel, int column, std::size_t frontBlock, const char* key) {
        gp << "set key " << key << " right box opaque\nset ylabel " << quoted(ylabel) << "\nplot ";
        for (std::size_t i = 0; i < n; ++i)
            gp << quoted(data.string()) << " index " << i << " using 1:" << column << " with points pt " << (i + 4)
               << " ps 1.5 title " << quoted(casters[i]) << ", ";
        gp << quoted(data.string()) << " index " << frontBlock
           << " using 1:2 with linespoints lw 2 pt 6 ps 2.5 lc rgb 'black' title 'Pareto front', ";
        for (std::size_t i = 0; i < n; ++i)
            gp << quoted(data.string()) << " index " << i << " using 1:" << column
               << ":4 with labels offset 0.6,0.6 left font ',7' notitle" << (i + 1 < n ? ", " : "\n");
    };
    panel("PSNR, dB (mean MSE over views; exact = " + std::to_string(int(kPlotPsnrCap)) + ")", 2, n, "bottom");
    gp << "set yrange [0:*]\n";
    panel("% pixels with CIEDE2000 > 2.3 (mean over views)", 3, n + 1, "top");
    gp << "unset multiplot\n";
    gp.close();
    const std::string command = "gnuplot " + quoted(script.string()) + " 2>&1";
    if (std::system(command.c_str()) != 0 || !fs::exists(png))
        throw std::runtime_error("gnuplot failed on " + script.string());
}

}  // namespace vr

#include "sweep/selection.h"

#include <algorithm>

namespace vr {

bool meetsQualityTarget(const SweepRow& r) {
    return r.error.worst.psnr >= kTargetPsnr && r.error.worst.percentOff8Bit < kTargetPercentOff;
}

double speedUp(const SweepRow& r) { return r.ratioToPrimitive > 0 ? 1 / r.ratioToPrimitive : 0; }

const SweepRow* bestMeetingTarget(const std::vector<SweepRow>& rows, const std::string& caster) {
    const SweepRow* best = nullptr;
    for (const SweepRow& r : rows) {
        const bool wanted = caster.empty() ? r.caster != "primitive" : r.caster == caster;
        if (wanted && meetsQualityTarget(r) && (!best || speedUp(r) > speedUp(*best))) best = &r;
    }
    return best;
}

namespace {
template <typename Get>
std::vector<std::string> distinct(const std::vector<SweepRow>& rows, Get get) {
    std::vector<std::string> out;
    for (const SweepRow& r : rows)
        if (std::find(out.begin(), out.end(), get(r)) == out.end()) out.push_back(get(r));
    return out;
}
}  // namespace

std::vector<std::string> datasetsOf(const std::vector<SweepRow>& rows) {
    return distinct(rows, [](const SweepRow& r) { return r.dataset; });
}

std::vector<std::string> castersOf(const std::vector<SweepRow>& rows) {
    return distinct(rows, [](const SweepRow& r) { return r.caster; });
}

std::vector<SweepRow> rowsOf(const std::vector<SweepRow>& rows, const std::string& dataset) {
    std::vector<SweepRow> out;
    std::copy_if(rows.begin(), rows.end(), std::back_inserter(out),
                 [&](const SweepRow& r) { return r.dataset == dataset; });
    return out;
}

}  // namespace vr

#include "sweep/pareto.h"

namespace vr {

double plottedPsnr(const SweepRow& r) { return std::min(r.error.mean.psnr, kPlotPsnrCap); }

std::vector<bool> psnrFront(const std::vector<SweepRow>& rows) {
    std::vector<std::pair<double, double>> points;
    for (const SweepRow& r : rows) points.emplace_back(r.ratioToPrimitive, -plottedPsnr(r));
    return paretoFront(points);
}

std::vector<bool> perceptualFront(const std::vector<SweepRow>& rows) {
    std::vector<std::pair<double, double>> points;
    for (const SweepRow& r : rows) points.emplace_back(r.ratioToPrimitive, r.error.mean.percentPerceptual);
    return paretoFront(points);
}

}  // namespace vr

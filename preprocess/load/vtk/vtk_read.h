// Running a VTK reader so that its failures become InputError instead of text on the terminal.
#pragma once
#include <filesystem>
#include <sstream>
#include <streambuf>
#include <string>

#include <vtkSmartPointer.h>

class vtkAlgorithm;
class vtkCommand;
class vtkImageData;
class vtkObject;
class vtkOutputWindow;

namespace vr {

// VTK readers report problems with vtkErrorMacro, which logs to stderr and the output window and throws nothing;
// MetaIO (behind vtkMetaImageReader) writes straight to std::cerr. While one of these lives, the objects it
// watches send their errors and warnings to it (an observer keeps them off stderr), the output window and
// std::cerr are captured for the rest, VTK's logger is kept off stderr, and read() names the first error in an
// InputError. All three are process-wide, so loads must not run concurrently on several threads.
class VtkReadErrors {
public:
    VtkReadErrors();
    ~VtkReadErrors();
    VtkReadErrors(const VtkReadErrors&) = delete;
    VtkReadErrors& operator=(const VtkReadErrors&) = delete;

    // Sends `object`'s ErrorEvent and WarningEvent here; read() watches the reader and its executive itself.
    void watch(vtkObject* object);
    vtkCommand* observer() const;

    // Updates `reader` and returns its image output. Throws InputError "PATH: cannot read FORMAT: PROBLEM" when
    // the reader reported an error, printed to std::cerr, set an error code, or produced no image with voxels.
    vtkImageData* read(vtkAlgorithm* reader, const std::filesystem::path& path, const std::string& format);

private:
    class Observer;
    class CapturingWindow;
    void noteError(const char* text);
    void noteWarning(const char* text);
    std::string complaint() const;

    // Messages without VTK's "ERROR: In FILE, line N / CLASS (ADDRESS):" prefix.
    std::string firstError_, firstWarning_;
    bool pipelineFailed_ = false;  // the executive's "returned failure", which says nothing of the cause
    vtkSmartPointer<Observer> observer_;
    vtkSmartPointer<CapturingWindow> window_;
    vtkSmartPointer<vtkOutputWindow> previousWindow_;
    std::ostringstream cerrText_;
    std::streambuf* previousCerr_;
    int previousLogVerbosity_;
};

}  // namespace vr

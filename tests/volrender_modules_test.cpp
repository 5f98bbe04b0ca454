// The tools' modules (tools/runtime_module.h): the heavy libraries (FFmpeg, VTK's readers, OpenVDB) are the
// modules', loaded by a run that needs them, not the tools', loaded at every start; a tool without its modules still
// does what needs none, and refuses the rest naming the module's file, writing nothing.
#include <gtest/gtest.h>

#include <fstream>

#include "support/cli.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;
using test::shellQuote;

TEST(VolrenderModules, TheToolsLoadNoneOfTheModulesLibrariesAtStart) {
    for (const fs::path& tool : {test::volprepExecutable(), test::volrenderExecutable(),
                                 fs::path(VR_BINARY_DIR) / "sweep" / "volsweep"}) {
        ASSERT_TRUE(fs::exists(tool)) << tool;
        const test::CliOutcome libraries = test::runCli("/usr/bin/ldd", shellQuote(tool));
        ASSERT_EQ(libraries.status, 0) << libraries.err;
        EXPECT_NE(libraries.out.find("libc.so"), std::string::npos) << libraries.out;  // ldd listed them
        for (const char* heavy : {"libavcodec", "libavformat", "libswscale", "libopenvdb", "libvtkIO"})
            EXPECT_EQ(libraries.out.find(heavy), std::string::npos) << tool << " loads " << heavy << ":\n"
                                                                    << libraries.out;
    }
}

// A copy of volprep in a folder without lib/volrender/: raw files need no module; every other format's loader is
// a module's, refused before the file is read.
TEST(VolrenderModules, WithoutTheFormatModulesRawFilesAreReadAndOtherFormatsRefused) {
    const fs::path copy = test::copiedWithoutModules(test::volprepExecutable(), "volrender_modules_formats");
    const fs::path dir = copy.parent_path().parent_path(), in = dir / "in", out = dir / "out";
    fs::create_directories(in / "dicom");
    fs::create_directories(out);
    const std::string transfer = " --window 255 --level 128 -o ";

    std::ofstream(in / "cube_8x8x8_uint8.raw", std::ios::binary) << std::string(512, '\x40');
    const test::CliOutcome raw = test::runCli(copy, shellQuote(in / "cube_8x8x8_uint8.raw") + transfer +
                                                        shellQuote(out / "cube.vprep"));
    EXPECT_EQ(raw.status, 0) << raw.err;
    EXPECT_TRUE(fs::exists(out / "cube.vprep"));

    const fs::path vtk = dir / "lib/volrender/volload_vtk.so", vdb = dir / "lib/volrender/volload_vdb.so";
    const std::pair<const char*, fs::path> formats[] = {
        {"head.nrrd", vtk}, {"head.mha", vtk}, {"head.nii.gz", vtk}, {"head.vti", vtk},
        {"head.vtk", vtk},  {"dicom", vtk},    {"head.vdb", vdb}};
    for (const auto& [name, module] : formats) {
        if (name != std::string("dicom")) std::ofstream(in / name) << "not read";
        const std::string args = shellQuote(in / name) + transfer + shellQuote(out / "refused.vprep");
        test::expectRefusal(test::runCli(copy, args), "volprep", args,
                            {(in / name).string(), module.string(), "cannot load the module that reads",
                             "No such file"});
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1);  // cube.vprep only
}

}  // namespace
}  // namespace vr

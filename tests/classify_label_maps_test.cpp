// Label maps as users bring them (docs/ALGORITHMS.md section 2, label maps): written by VTK's NIfTI writer on the
// volume's grid, with 3D Slicer colour tables or the default palette; and each bad input refused with a message
// that names the flag, the file and the problem.
#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.h"
#include "preprocess/classify/label_colours.h"
#include "preprocess/load/load_labels.h"
#include "support/datasets.h"
#include "support/label_maps.h"
#include "support/load_dataset.h"

namespace vr {
namespace {

namespace fs = std::filesystem;

class ClassifyLabelMaps : public ::testing::Test {
protected:
    void SetUp() override {
        dir = test::scratchDir("classify_label_maps");
        volume = test::loadDataset("vtk_headsq_ct");
        labels = test::thresholdLabels(volume, {1000, 2200});
        values.assign(labels.label.begin(), labels.label.end());
    }
    // The message of the InputError that `load` throws; a failure where it throws none.
    template <typename Load>
    std::string errorOf(Load load) {
        try {
            load();
        } catch (const InputError& e) {
            return e.what();
        }
        ADD_FAILURE() << "no InputError";
        return "";
    }
    fs::path writeTable(const std::string& text) {
        const fs::path path = dir / "colours.txt";
        std::ofstream(path) << text;
        return path;
    }
    fs::path dir;
    Volume volume;
    LabelMap labels;
    std::vector<float> values;
};

TEST_F(ClassifyLabelMaps, ReadsAMapWrittenByVtk) {
    const fs::path path = dir / "labels.nii.gz";
    test::writeNiftiWithVtk(path, values, volume.grid, ScalarType::UInt8);
    const LabelMap read = loadLabelMap(path, volume.grid, "--labels");
    EXPECT_EQ(read.label, labels.label);
    EXPECT_EQ(read.type, ScalarType::UInt8);
    // Labels past 255 are held in 16 bits; integral floats are labels too.
    for (float& v : values) v = v == 2 ? 1000 : v;
    test::writeNiftiWithVtk(path, values, volume.grid, ScalarType::Float32);
    const LabelMap wide = loadLabelMap(path, volume.grid, "--labels");
    EXPECT_EQ(wide.type, ScalarType::UInt16);
    EXPECT_EQ(*std::max_element(wide.label.begin(), wide.label.end()), 1000);
}

TEST_F(ClassifyLabelMaps, RefusesAnotherGrid) {
    const fs::path path = dir / "labels.nii";
    GridGeometry shifted = volume.grid;
    shifted.spacing.z *= 2;
    test::writeNiftiWithVtk(path, values, shifted, ScalarType::UInt8);
    const std::string message = errorOf([&] { loadLabelMap(path, volume.grid, "--labels"); });
    EXPECT_NE(message.find("--labels " + path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("is not the volume's"), std::string::npos) << message;
    GridGeometry smaller = volume.grid;
    smaller.dims.z -= 1;
    test::writeNiftiWithVtk(path, std::vector<float>(smaller.voxels(), 1), smaller, ScalarType::UInt8);
    EXPECT_NE(errorOf([&] { loadLabelMap(path, volume.grid, "--labels"); }).find("64x64x92 voxels"), std::string::npos);
}

TEST_F(ClassifyLabelMaps, RefusesValuesThatAreNoLabels) {
    const fs::path path = dir / "labels.nii";
    for (float bad : {1.5f, -1.0f, 70000.0f}) {
        values[1234] = bad;
        test::writeNiftiWithVtk(path, values, volume.grid, ScalarType::Float32);
        const std::string message = errorOf([&] { loadLabelMap(path, volume.grid, "--labels"); });
        EXPECT_NE(message.find("voxel 1234 holds"), std::string::npos) << message;
        EXPECT_NE(message.find("not a label"), std::string::npos) << message;
    }
}

TEST_F(ClassifyLabelMaps, TakesSlicerColourTables) {
    const fs::path path = writeTable("# Slicer colour table\n0 background 0 0 0 0\n1 skin 230 180 150 60\n\n"
                                     "2 bone 255 250 240 255\n7 unused 1 2 3 4\n");
    const LabelColourTable table = readLabelColourTable(path, "--label-colors");
    const auto rgba = labelColours(labels, &table, "--label-colors");
    ASSERT_EQ(rgba.size(), 3u);  // labels 0 .. the map's largest
    EXPECT_EQ(rgba[1], (std::array<uint8_t, 4>{230, 180, 150, 60}));
    const LabelClasses classes = classifyLabels(rgba, 2.0);
    EXPECT_EQ(classes.sigma[0], 0);
    EXPECT_NEAR(classes.sigma[1], -std::log(1 - 60 / 255.0) / 2, 1e-6);
    EXPECT_FLOAT_EQ(classes.colour[2][1], 250 / 255.0f);
    // The default palette: background clear, the labels apart.
    const auto palette = labelColours(labels, nullptr, "--label-colors");
    EXPECT_EQ(palette[0][3], 0);
    EXPECT_GT(palette[1][3], 0);
    EXPECT_NE(palette[1], palette[2]);
}

TEST_F(ClassifyLabelMaps, RefusesBadTablesAndMissingLabels) {
    const auto messageOf = [&](const std::string& text) {
        const fs::path path = writeTable(text);
        return errorOf([&] { readLabelColourTable(path, "--label-colors"); });
    };
    EXPECT_NE(messageOf("0 background 0 0 0\n").find("line 1: expected 'index name r g b a'"), std::string::npos);
    EXPECT_NE(messageOf("# x\n1 a 0 0 300 10\n").find("line 2: colour and opacity must be 0..255, got 300"),
              std::string::npos);
    EXPECT_NE(messageOf("1 a 0 0 0 10\n1 b 0 0 0 10\n").find("label 1 is given twice"), std::string::npos);
    EXPECT_NE(messageOf("70000 a 0 0 0 10\n").find("outside 0..65535"), std::string::npos);
    EXPECT_NE(messageOf("# nothing\n").find("holds no label"), std::string::npos);
    // A binary table (MRIcron's .lut) is quoted escaped, not printed to the terminal byte for byte.
    const std::string binary = messageOf(std::string("\xFF\xCC\x00\x1B[2J\n", 7));
    EXPECT_NE(binary.find("got '\\xFF\\xCC\\x00\\x1B[2J'"), std::string::npos) << binary;
    const fs::path path = writeTable("0 background 0 0 0 0\n1 skin 230 180 150 60\n");
    const LabelColourTable table = readLabelColourTable(path, "--label-colors");
    const std::string missing = errorOf([&] { labelColours(labels, &table, "--label-colors"); });
    EXPECT_NE(missing.find("--label-colors " + path.string()), std::string::npos) << missing;
    EXPECT_NE(missing.find("holds labels the colour table lacks: 2"), std::string::npos) << missing;
}

}  // namespace
}  // namespace vr

// The built-in presets and the transfer-function flags' choice: the presets embedded in the library, read by name;
// the window/level ramp; every bad choice named by its flag; CT-Bone on the shared head CT in Hounsfield units.
#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.h"
#include "preprocess/classify/classify.h"
#include "preprocess/classify/embedded_presets.h"
#include "preprocess/classify/transfer_choice.h"
#include "preprocess/classify/transfer_presets.h"
#include "support/load_dataset.h"

namespace vr {
namespace {

const TransferFunction& preset(const std::string& name) {
    const TransferFunction* p = findTransferPreset(name);
    if (!p) throw std::runtime_error("no preset " + name);
    return *p;
}

std::string errorOf(const TransferChoice& choice) {
    try {
        chooseTransferFunction(choice);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ClassifyTransferPresets, TheCtAndMrPresetsAreBuiltInWithTheirUnits) {
    for (const char* name : {"CT-Bone", "CT-Soft-Tissue", "CT-Muscle", "CT-Lung", "CT-AAA", "CT-Cardiac"})
        EXPECT_EQ(preset(name).units, "HU") << name;
    for (const char* name : {"MR-Default", "MR-Angio", "MR-T2-Brain"})
        EXPECT_NE(preset(name).units.find("MR intensity"), std::string::npos) << name;
    for (const TransferFunction& p : transferPresets()) {
        SCOPED_TRACE(p.name);
        EXPECT_FALSE(p.description.empty());
        EXPECT_EQ(p.colourSpace, "RGB");
        EXPECT_GE(p.opacity.size(), 2u);
        EXPECT_GE(p.colour.size(), 2u);
        EXPECT_NE(p.json.find("\"Units\": \"" + p.units + "\""), std::string::npos);  // stated in the file
        int sameName = 0;
        for (const TransferFunction& q : transferPresets()) sameName += findTransferPreset(q.name) == &p;
        EXPECT_EQ(sameName, 1);  // no two names alike, even ignoring case
    }
    // Each preset file is named for its preset, and they come in name order.
    const std::vector<EmbeddedFile> files = embeddedPresetFiles();
    ASSERT_EQ(files.size(), transferPresets().size());
    for (std::size_t i = 0; i < files.size(); ++i) EXPECT_EQ(files[i].name, transferPresets()[i].name + ".json");
}

TEST(ClassifyTransferPresets, NamesIgnoreCaseAndUnknownNamesFindNothing) {
    EXPECT_EQ(findTransferPreset("ct-bone"), &preset("CT-Bone"));
    EXPECT_EQ(findTransferPreset("MR-DEFAULT"), &preset("MR-Default"));
    EXPECT_EQ(findTransferPreset("CT-Bon"), nullptr);
    EXPECT_EQ(findTransferPreset(""), nullptr);
    EXPECT_EQ(findTransferPreset("CT-Bone.json"), nullptr);
}

TEST(ClassifyTransferPresets, ListingGivesEachPresetsValuesUnitsAndWhatIsVisible) {
    const std::string listing = transferPresetListing();
    for (const TransferFunction& p : transferPresets()) EXPECT_NE(listing.find(p.name), std::string::npos) << p.name;
    EXPECT_NE(listing.find("CT-Bone         -3024 .. 3071 HU, visible above 150: "), std::string::npos) << listing;
    EXPECT_NE(listing.find("CT-Lung         -1000 .. 2952 HU, visible between -600 and -399: "), std::string::npos);
    EXPECT_NE(listing.find("MR-T2-Brain     0 .. 641 MR intensity"), std::string::npos) << listing;
    EXPECT_EQ(std::count(listing.begin(), listing.end(), '\n'), std::ptrdiff_t(transferPresets().size()));
}

TEST(ClassifyTransferPresets, ParaViewJsonReadsBackToTheSameFunction) {
    for (const TransferFunction& p : transferPresets()) {
        TransferFunction back = parseTransferFunction(paraViewJson(p), "written " + p.name);
        EXPECT_EQ(back.json, paraViewJson(p));
        back.json = p.json;
        EXPECT_EQ(back, p) << p.name;
    }
}

TEST(ClassifyTransferPresets, WindowLevelIsALinearRampGreyOrInTheColoursOfTf) {
    const TransferFunction grey = chooseTransferFunction({"", 400.0, 40.0});
    EXPECT_EQ(grey.name, "window 400 level 40");
    for (auto [f, alpha] : {std::pair{-1024.0, 0.0}, {-160.0, 0.0}, {-60.0, 0.25}, {40.0, 0.5}, {240.0, 1.0},
                            {2000.0, 1.0}}) {
        EXPECT_NEAR(grey.opacityAt(f), alpha, 1e-12) << f;
        for (double c : grey.colourAt(f)) EXPECT_NEAR(c, alpha, 1e-12) << f;  // black to white over the window
    }
    // The file the prepared volume keeps reads back to the same ramp.
    TransferFunction kept = parseTransferFunction(grey.json, "kept");
    kept.json = grey.json;
    EXPECT_EQ(kept, grey);

    // With a preset: the ramp's opacity, the preset's colours at the preset's values, and its units.
    const TransferFunction& bone = preset("CT-Bone");
    const TransferFunction ramp = chooseTransferFunction({"ct-bone", 1000.0, 500.0});
    EXPECT_EQ(ramp.name, "CT-Bone, window 1000 level 500");
    EXPECT_EQ(ramp.units, "HU");
    EXPECT_EQ(ramp.colour, bone.colour);
    EXPECT_NEAR(ramp.opacityAt(0), 0.0, 1e-12);
    EXPECT_NEAR(ramp.opacityAt(750), 0.75, 1e-12);
    EXPECT_EQ(ramp.colourAt(641.385), bone.colourAt(641.385));

    // With a file: the same, the file's colours.
    const std::string file = (test::datasetsDir() / "cranium_ct.tf.json").string();
    const TransferFunction fromFile = chooseTransferFunction({file, 100.0, 0.0});
    EXPECT_EQ(fromFile.colour, loadTransferFunction(file).colour);
    EXPECT_EQ(fromFile.opacity.size(), 2u);
    EXPECT_NEAR(fromFile.opacityAt(25), 0.75, 1e-12);
}

TEST(ClassifyTransferPresets, TfIsAPresetBeforeAFileAndAFileBesideIt) {
    EXPECT_EQ(chooseTransferFunction({"CT-Lung", {}, {}}), preset("CT-Lung"));
    const std::filesystem::path dir = test::scratchDir("classify_transfer_presets_files");
    std::ofstream(dir / "CT-Lung") << R"({"Name": "mine", "Points": [0, 0, 0.5, 0, 1, 1, 0.5, 0]})";
    EXPECT_EQ(chooseTransferFunction({(dir / "CT-Lung").string(), {}, {}}).name, "mine");
    EXPECT_EQ(chooseTransferFunction({"CT-Lung", {}, {}}).name, "CT-Lung");
}

TEST(ClassifyTransferPresets, EveryBadChoiceNamesItsFlag) {
    struct Case {
        TransferChoice choice;
        std::vector<std::string> mentions;
    };
    const double nan = std::nan(""), inf = INFINITY;
    for (const Case& c : std::vector<Case>{
             {{"", {}, {}}, {"no transfer function", "--tf", "--window", "--level"}},
             {{"CT-Bon", {}, {}}, {"--tf CT-Bon", "no such file, nor a built-in preset", "CT-AAA", "CT-Bone",
                                   "CT-Cardiac", "CT-Lung", "CT-Muscle", "CT-Soft-Tissue", "MR-Angio", "MR-Default",
                                   "MR-T2-Brain"}},
             {{"CT-Bon", 400.0, 40.0}, {"--tf CT-Bon", "MR-T2-Brain"}},
             {{"", 400.0, {}}, {"--window needs --level"}},
             {{"CT-Bone", {}, 40.0}, {"--level needs --window"}},
             {{"", 0.0, 40.0}, {"--window 0", "above 0"}},
             {{"", -10.0, 40.0}, {"--window -10", "above 0"}},
             {{"", nan, 40.0}, {"--window nan", "above 0"}},
             {{"", inf, 40.0}, {"--window inf", "finite"}},
             {{"CT-Bone", 400.0, nan}, {"--level nan", "finite"}},
             {{"", 400.0, -inf}, {"--level -inf", "finite"}},
             {{"", 1.0, 1e20}, {"--window 1 --level 1e+20", "not two distinct finite numbers"}},
             {{"", 1e308, 1.5e308}, {"--window 1e+308 --level 1.5e+308", "not two distinct finite numbers"}},
         }) {
        const std::string message = errorOf(c.choice);
        ASSERT_FALSE(message.empty()) << c.mentions[0];
        for (const std::string& m : c.mentions) EXPECT_NE(message.find(m), std::string::npos) << message;
    }
    // A bad file keeps the loader's message, naming the file.
    const std::filesystem::path bad = test::scratchDir("classify_transfer_presets_bad") / "bad.json";
    std::ofstream(bad) << "{\"Points\": [0, 0, 0.5]}";
    for (const TransferChoice& choice : {TransferChoice{bad.string(), {}, {}}, TransferChoice{bad.string(), 1.0, 0.0}})
        EXPECT_NE(errorOf(choice).find(bad.string() + ": \"Points\" has 3 numbers"), std::string::npos)
            << errorOf(choice);
}

// The shared head CT is in Hounsfield units (-1024 air .. 2986): CT-Bone leaves air, fat, water and soft tissue
// transparent and makes cortical bone opaque.
TEST(ClassifyTransferPresets, CtBoneMakesTheCraniumsBoneOpaqueAndItsSoftTissueClear) {
    const Volume ct = test::loadDataset("cranium_ct");
    ClassifyParams params;
    params.transferFunction = preset("CT-Bone");
    params.normals = false;
    const ClassifiedVolume classified = classify(ct, params);
    std::size_t clear = 0, soft = 0, bone = 0;
    for (std::size_t i = 0; i < ct.values.size(); ++i) {
        const float hu = ct.values[i];
        if (hu <= 150) {
            ASSERT_EQ(classified.sigma[i], 0.f) << hu;
            ++clear;
            soft += hu >= -100 && hu <= 100;
        } else if (hu >= 700) {
            ASSERT_GE(classified.opacity(i), 0.7) << hu;
            ++bone;
        }
    }
    // Each class is a large part of the head: air over 4 million voxels, soft tissue over a million, bone 250 000.
    EXPECT_GT(clear - soft, 4'000'000u);
    EXPECT_GT(soft, 1'000'000u);
    EXPECT_GT(bone, 250'000u);
}

}  // namespace
}  // namespace vr

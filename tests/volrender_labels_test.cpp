// Label maps and jitter end to end: a label map written by VTK's NIfTI writer rendered with the one-command path and
// through volprep's prepared file (the same image), on the CPU reference and the Vulkan device; every bad label
// input refused with a message naming its flags and nothing written.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "io/prepared_file.h"
#include "render/image.h"
#include "support/cli.h"
#include "support/label_maps.h"
#include "support/load_dataset.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

constexpr auto q = test::shellQuote;

// The head CT with its manifest spacing, labelled soft tissue (1) and bone (2) into a NIfTI file by VTK, a 3D Slicer
// colour table for them, and the flags that render it small.
struct Head {
    fs::path dir, volume, labels, colours;
    std::string flags;
};

const Head& head() {
    static const Head h = [] {
        Head h;
        h.dir = test::scratchDir("volrender_labels");
        const test::DatasetEntry e = test::rawDataset("vtk_headsq_ct_64x64x93_uint16");
        const Volume v = test::loadDataset(e);
        const LabelMap labels = test::thresholdLabels(v, {1000, 2200});
        h.volume = test::datasetsDir() / e.file;
        h.labels = h.dir / "head_labels.nii.gz";
        test::writeNiftiWithVtk(h.labels, std::vector<float>(labels.label.begin(), labels.label.end()), v.grid,
                                ScalarType::UInt8);
        h.colours = h.dir / "head_colours.txt";
        std::ofstream(h.colours) << "# index name r g b a\n0 background 0 0 0 0\n1 skin 230 160 140 40\n"
                                    "2 bone 250 245 230 255\n";
        h.flags = " --tf " + q(test::datasetsDir() / e.tf) +
                  " --spacing 3.2,3.2,1.5 --to 0 --ta 0 --size 40x40 --elevation 20";
        return h;
    }();
    return h;
}

TEST(VolrenderLabels, RendersAVtkLabelMapHereAndThroughVolprep) {
    const Head& h = head();
    const std::string labelled = " --labels " + q(h.labels) + " --label-colors " + q(h.colours);
    const fs::path here = h.dir / "here.png", plain = h.dir / "plain.png", device = h.dir / "device.png";
    test::CliOutcome r = test::runVolrender(q(h.volume) + h.flags + labelled + " --cpu -o " + q(here));
    ASSERT_EQ(r.status, 0) << r.err;
    r = test::runVolrender(q(h.volume) + h.flags + " --cpu -o " + q(plain));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(maxAbsDifference(readImage(here), readImage(plain)), 0.1) << "the labels changed nothing";

    const fs::path prepared = h.dir / "head.vrp";
    r = test::runVolprep(q(h.volume) + " --tf " + q(test::datasetsDir() / "vtk_headsq_ct.tf.json") +
                         " --spacing 3.2,3.2,1.5 --to 0 --ta 0 -q" + labelled + " -o " + q(prepared));
    ASSERT_EQ(r.status, 0) << r.err;
    const PreparedVolume p = readPrepared(prepared);
    ASSERT_TRUE(p.labels);
    EXPECT_EQ(p.labels->classes.size(), 3u);
    EXPECT_EQ(p.labels->source, h.labels.string());
    const fs::path fromFile = h.dir / "from_file.png";
    r = test::runVolrender(q(prepared) + " --size 40x40 --elevation 20 --cpu --caster eacd -o " + q(fromFile));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_LT(maxAbsDifference(readImage(fromFile), readImage(here)), 2.0 / 255);

    const std::string again = q(prepared) + " --labels " + q(h.labels) + " -o " + q(h.dir / "again.png");
    test::expectRefusal(test::runVolrender(again), "volrender", again,
                        {"prepared file holds its label map", "--labels"});
    // The hier caster's blocks are classified by the scalars alone: a label map is refused, here and from a file.
    for (const std::string& hier : {q(h.volume) + h.flags + labelled + " --caster hier -o " + q(h.dir / "hier.png"),
                                    q(prepared) + " --size 40x40 --caster hier -o " + q(h.dir / "hier.png")})
        test::expectRefusal(test::runVolrender(hier), "volrender", hier, {"hier caster does not take a label map"});

    r = test::runVolrender(q(h.volume) + h.flags + labelled + " -o " + q(device));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_LT(maxAbsDifference(readImage(device), readImage(here)), 3.0 / 255);
}

TEST(VolrenderLabels, JitterIsAFlag) {
    const Head& h = head();
    const fs::path jittered = h.dir / "jittered.png", stats = h.dir / "jittered.json";
    const test::CliOutcome r =
        test::runVolrender(q(h.volume) + h.flags + " --cpu --jitter -o " + q(jittered) + " --stats " + q(stats));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(nlohmann::json::parse(test::slurp(stats))["settings"]["jitter"].get<bool>());
    EXPECT_NE(test::runVolrender("--help").out.find("--jitter"), std::string::npos);
}

TEST(VolrenderLabels, BadLabelInputIsRefusedWithNothingWritten) {
    const Head& h = head();
    const fs::path out = h.dir / "refused.png";
    const auto refused = [&](const std::string& args, const std::vector<std::string>& mentions) {
        const std::string all = args + " -o " + q(out);
        test::expectRefusal(test::runVolrender(all), "volrender", all, mentions);
        EXPECT_FALSE(fs::exists(out)) << args;
    };
    // Another grid: the label map read without the volume's spacing.
    const fs::path unspaced = h.dir / "unspaced.nii";
    GridGeometry grid;
    grid.dims = {64, 64, 93};
    test::writeNiftiWithVtk(unspaced, std::vector<float>(grid.voxels(), 1), grid, ScalarType::UInt8);
    refused(q(h.volume) + h.flags + " --cpu --labels " + q(unspaced), {"--labels", "is not the volume's"});
    // Values that are no labels.
    const fs::path fractional = h.dir / "fractional.nii";
    grid.spacing = {3.2, 3.2, 1.5};
    test::writeNiftiWithVtk(fractional, std::vector<float>(grid.voxels(), 0.5f), grid, ScalarType::Float32);
    refused(q(h.volume) + h.flags + " --cpu --labels " + q(fractional), {"--labels", "voxel 0 holds 0.5"});
    // Labels the table lacks.
    const fs::path partial = h.dir / "partial.txt";
    std::ofstream(partial) << "0 background 0 0 0 0\n1 skin 230 160 140 40\n";
    refused(q(h.volume) + h.flags + " --cpu --labels " + q(h.labels) + " --label-colors " + q(partial),
            {"--label-colors", "lacks: 2"});
    // Conflicting flags name both.
    refused(q(h.volume) + h.flags + " --cpu --label-colors " + q(h.colours), {"--label-colors", "--labels"});
    refused(q(h.volume) + h.flags + " --cpu --labels " + q(h.labels) + " --blend mip", {"--labels", "--blend mip"});
    EXPECT_NE(test::runVolrender("--help").out.find("--label-colors"), std::string::npos);
    // volprep refuses them alike, before it writes anything.
    const fs::path prepared = h.dir / "refused.vrp";
    const std::string prep = q(h.volume) + " --tf " + q(test::datasetsDir() / "vtk_headsq_ct.tf.json") +
                             " --spacing 3.2,3.2,1.5 --labels " + q(unspaced) + " -o " + q(prepared);
    test::expectRefusal(test::runVolprep(prep), "volprep", prep, {"--labels", "is not the volume's"});
    EXPECT_FALSE(fs::exists(prepared));
}

}  // namespace
}  // namespace vr

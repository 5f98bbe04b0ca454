#include "volrender/cmd/stereo_flags.h"

#include "core/errors.h"
#include "render/stereo_camera.h"

namespace vr {

void addStereoFlags(CLI::App& app, StereoFlags& f) {
    app.add_option("--stereo", f.separation, "render a stereo pair: two parallel perspective eyes SEPARATION world "
                                             "units apart, with off-axis frusta (needs --projection persp)");
    app.add_option("--focus", f.focus, "the pair's zero-parallax distance from the eyes, world units (default: the "
                                       "volume centre's depth)");
    app.add_option("--stereo-layout", f.layout, "how the pair is written: separate (-o pair.png writes pair_left.png "
                                                "and pair_right.png), side-by-side, top-bottom or anaglyph (red-cyan)")
        ->capture_default_str();
    app.add_option("--stereo-reuse", f.reuse, "on: the right eye is the left's reprojection, cast again only where "
                                              "it cannot vouch for a pixel; off: both eyes cast in full (default: "
                                              "on, off with --cpu)");
}

StereoLayout stereoLayout(const StereoFlags& f) { return parseStereoLayout(f.layout); }

bool stereoReuse(const StereoFlags& f, bool cpu) { return f.reuse ? *f.reuse == "on" : !cpu; }

bool checkStereoFlags(const StereoFlags& f, Projection projection, bool cpu) {
    if (!f.separation) {
        if (f.focus) throw InputError("--focus is the stereo pair's zero-parallax distance: it needs --stereo");
        if (f.layout != "separate") throw InputError("--stereo-layout " + f.layout + " lays out a stereo pair: it "
                                                     "needs --stereo SEPARATION");
        if (f.reuse) throw InputError("--stereo-reuse is for a stereo pair: it needs --stereo SEPARATION");
        return false;
    }
    stereoLayout(f);
    if (f.reuse && *f.reuse != "on" && *f.reuse != "off")
        throw InputError("--stereo-reuse '" + *f.reuse + "': expected on or off");
    if (cpu && f.reuse && *f.reuse == "on")
        throw InputError("--stereo-reuse on reprojects on the Vulkan device: --cpu casts both eyes in full "
                         "(--stereo-reuse off)");
    checkStereo(*f.separation, f.focus, projection);
    return true;
}

nlohmann::json stereoStatistics(const StereoFlags& f, bool cpu) {
    if (!f.separation) return {{"stereo", nullptr}};
    return {{"stereo",
             {{"separation", *f.separation},
              {"focus", f.focus ? nlohmann::json(*f.focus) : nlohmann::json()},
              {"layout", f.layout},
              {"reuse", stereoReuse(f, cpu)}}}};
}

}  // namespace vr

#include "render/render_settings.h"

#include "core/enum_names.h"

namespace vr {
namespace {

constexpr EnumName<Caster> kCasterNames[] = {
    {Caster::Primitive, "primitive"}, {Caster::PC, "pc"}, {Caster::ACD, "acd"}, {Caster::EACD, "eacd"},
    {Caster::Blocks, "blocks"}, {Caster::Hier, "hier"}};
constexpr EnumName<Blend> kBlendNames[] = {{Blend::Composite, "composite"}, {Blend::MIP, "mip"},
                                           {Blend::MinIP, "minip"},         {Blend::Average, "average"},
                                           {Blend::Iso, "iso"}};
constexpr EnumName<Gradients> kGradientNames[] = {{Gradients::OnTheFly, "on-the-fly"}, {Gradients::Stored, "stored"}};

}  // namespace

std::string_view casterName(Caster c) { return nameOf(kCasterNames, c); }

Caster parseCaster(std::string_view name) { return valueNamed(kCasterNames, name, "caster"); }

std::string_view blendName(Blend b) { return nameOf(kBlendNames, b); }

Blend parseBlend(std::string_view name) { return valueNamed(kBlendNames, name, "--blend mode"); }

std::string_view gradientsName(Gradients g) { return nameOf(kGradientNames, g); }

Gradients parseGradients(std::string_view name) { return valueNamed(kGradientNames, name, "--gradients source"); }

}  // namespace vr

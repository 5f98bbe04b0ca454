#include "render/render_settings.h"

#include "core/enum_names.h"

namespace vr {
namespace {

constexpr EnumName<Caster> kCasterNames[] = {
    {Caster::Primitive, "primitive"}, {Caster::PC, "pc"}, {Caster::ACD, "acd"}, {Caster::EACD, "eacd"},
    {Caster::Blocks, "blocks"}};
constexpr EnumName<Blend> kBlendNames[] = {{Blend::Composite, "composite"}, {Blend::MIP, "mip"},
                                           {Blend::MinIP, "minip"},         {Blend::Average, "average"},
                                           {Blend::Iso, "iso"}};

}  // namespace

std::string_view casterName(Caster c) { return nameOf(kCasterNames, c); }

Caster parseCaster(std::string_view name) { return valueNamed(kCasterNames, name, "caster"); }

std::string_view blendName(Blend b) { return nameOf(kBlendNames, b); }

Blend parseBlend(std::string_view name) { return valueNamed(kBlendNames, name, "--blend mode"); }

}  // namespace vr

#include "render/render_settings.h"

#include "core/enum_names.h"

namespace vr {
namespace {

constexpr EnumName<Caster> kCasterNames[] = {
    {Caster::Primitive, "primitive"}, {Caster::PC, "pc"}, {Caster::ACD, "acd"}, {Caster::EACD, "eacd"}};

}  // namespace

std::string_view casterName(Caster c) { return nameOf(kCasterNames, c); }

Caster parseCaster(std::string_view name) { return valueNamed(kCasterNames, name, "caster"); }

}  // namespace vr

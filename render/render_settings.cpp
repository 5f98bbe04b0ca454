#include "render/render_settings.h"

#include <string>

#include "core/errors.h"

namespace vr {

std::string_view casterName(Caster c) {
    switch (c) {
        case Caster::Primitive: return "primitive";
        case Caster::PC: return "pc";
        case Caster::ACD: return "acd";
        case Caster::EACD: return "eacd";
    }
    return "unknown";
}

Caster parseCaster(std::string_view name) {
    for (Caster c : {Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD})
        if (name == casterName(c)) return c;
    throw InputError("unknown caster '" + std::string(name) + "' (expected primitive, pc, acd or eacd)");
}

}  // namespace vr

// What a render is asked to do: caster, view, step, shading. Shared by the CPU reference and Vulkan.
#pragma once
#include <optional>
#include <string_view>

#include "core/vec3.h"

namespace vr {

enum class Caster { Primitive, PC, ACD, EACD };
enum class Projection { Orthographic, Perspective };

std::string_view casterName(Caster c);    // "primitive", "pc", "acd", "eacd"
Caster parseCaster(std::string_view name); // throws InputError

struct ViewParams {
    Projection projection = Projection::Orthographic;
    double fovDeg = 30;       // vertical field of view (perspective)
    double azimuthDeg = 0;    // about the up axis
    double elevationDeg = 0;  // about the right axis
    int width = 512, height = 512;
};

struct RenderSettings {
    Caster caster = Caster::Primitive;
    double stepVoxels = 0.5;   // dt in voxels of the smallest spacing
    double ert = 0.99;         // early ray termination: stop when alpha >= ert
    bool shading = true;       // Phong with one directional light; false: emission-absorption only
    bool trilinear = false;    // trilinear sampling (needs a volume prepared with --trilinear for leaping casters)
    std::optional<Vec3d> lightDirection;  // world direction towards the light; empty: headlight
    Vec3d background{0, 0, 0};
    long long maxIterationsPerRay = 1 << 24;  // a bug must not hang a render
};

}  // namespace vr

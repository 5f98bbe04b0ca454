// Small 3-vector value type shared by every stage (grid indices, spacing, world positions).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace vr {

template <typename T>
struct Vec3 {
    T x{}, y{}, z{};

    constexpr Vec3() = default;
    constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    template <typename U>
    constexpr explicit Vec3(const Vec3<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}

    constexpr T& operator[](int a) { return a == 0 ? x : (a == 1 ? y : z); }
    constexpr const T& operator[](int a) const { return a == 0 ? x : (a == 1 ? y : z); }

    constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator*(const Vec3& o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3 operator/(const Vec3& o) const { return {x / o.x, y / o.y, z / o.z}; }
    constexpr Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(T s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
    constexpr bool operator==(const Vec3& o) const = default;
};

using Vec3d = Vec3<double>;
using Vec3f = Vec3<float>;
using Vec3i = Vec3<int>;

template <typename T> constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <typename T> constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T> T length(const Vec3<T>& a) { return std::sqrt(dot(a, a)); }
template <typename T> Vec3<T> normalize(const Vec3<T>& a) { return a / length(a); }
template <typename T> constexpr T maxComponent(const Vec3<T>& a) { return std::max({a.x, a.y, a.z}); }
template <typename T> constexpr T minComponent(const Vec3<T>& a) { return std::min({a.x, a.y, a.z}); }
template <typename T> Vec3<T> abs(const Vec3<T>& a) { return {std::abs(a.x), std::abs(a.y), std::abs(a.z)}; }

// Number of voxels of a grid, in 64 bits so that products of large dims cannot overflow int.
constexpr std::size_t voxelCount(const Vec3i& dims) {
    return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
}

// Linear index of voxel (x, y, z): x fastest, then y, then z (the layout of every grid here).
constexpr std::size_t linearIndex(const Vec3i& dims, int x, int y, int z) {
    return (std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) + std::size_t(x);
}

constexpr bool inside(const Vec3i& dims, int x, int y, int z) {
    return x >= 0 && y >= 0 && z >= 0 && x < dims.x && y < dims.y && z < dims.z;
}

}  // namespace vr

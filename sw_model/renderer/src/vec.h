// Small 3-vector and hash helpers of the renderer. Plain float arithmetic only (the library is
// built with -ffp-contract=off), so results do not depend on compiler contraction choices.
#pragma once

#include <cmath>
#include <cstdint>

namespace msr {

struct Vec3 {
    float x = 0.f, y = 0.f, z = 0.f;
    Vec3() = default;
    constexpr Vec3(float a, float b, float c) : x(a), y(b), z(c) {}
    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    float &operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(float s, Vec3 a) { return a * s; }
inline Vec3 operator/(Vec3 a, float s) { return a * (1.f / s); }
inline Vec3 &operator+=(Vec3 &a, Vec3 b) { a = a + b; return a; }
inline Vec3 &operator*=(Vec3 &a, float s) { a = a * s; return a; }
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) {
    float l = length(a);
    return l > 0.f ? a / l : Vec3{0.f, 0.f, 0.f};
}
// min/max that compile to one instruction (std::fmin is a libm call without -ffast-math);
// NaN handling does not matter where they are used.
inline float minf(float a, float b) { return b < a ? b : a; }
inline float maxf(float a, float b) { return b > a ? b : a; }
inline Vec3 vmin(Vec3 a, Vec3 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
inline Vec3 vmax(Vec3 a, Vec3 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }
inline float max_component(Vec3 a) { return maxf(a.x, maxf(a.y, a.z)); }

// Orthonormal basis around a unit normal (Duff et al. 2017, branchless up to the sign).
inline void onb(Vec3 n, Vec3 &t, Vec3 &b) {
    float s = std::copysign(1.f, n.z);
    float a = -1.f / (s + n.z);
    float c = n.x * n.y * a;
    t = {1.f + s * n.x * n.x * a, s * c, -s * n.x};
    b = {c, s + n.y * n.y * a, -n.y};
}

// Integer hash (lowbias32, Chris Wellons): the only source of "random" numbers, so a sample
// depends on nothing but (x, y, sample index, purpose, seed).
inline uint32_t hash32(uint32_t v) {
    v ^= v >> 16; v *= 0x7feb352dU;
    v ^= v >> 15; v *= 0x846ca68bU;
    v ^= v >> 16;
    return v;
}
inline uint32_t hash_combine(uint32_t h, uint32_t v) { return hash32(h ^ (v + 0x9e3779b9U + (h << 6) + (h >> 2))); }
// Uniform float in [0, 1) from the top 24 bits (exact in float).
inline float u01(uint32_t h) { return float(h >> 8) * (1.f / 16777216.f); }

}  // namespace msr

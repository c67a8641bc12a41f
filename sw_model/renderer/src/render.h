// The per-pixel render function: Whitted ray tracing (direct light with shadow rays, mirror
// reflection, glass refraction, recursion limit, sky), then tone mapping and sRGB to 8 bits.
#pragma once

#include <cstdint>
#include <memory>

#include "scene.h"

namespace msr {

// 8-bit sRGB code of a linear value in [0, 1] (round half up), by exact thresholds.
uint8_t srgb8(float linear);

// Unoccluded irradiance at p (normal n) from a parallelogram emitter of unit radiance:
// Lambert's polygon formula, the polygon clipped to the hemisphere above p.
float polygon_irradiance(Vec3 p, Vec3 n, const AreaLight &l);

enum class Quality { Fast = 0, Heavy = 1 };

class Renderer {
public:
    // Takes a committed scene. width, height >= 1. grid: the antialiasing grid, grid x grid
    // stratified jittered samples per pixel (0 = the quality's own: 1 fast, kHeavyGrid heavy;
    // fast with grid 1 samples the pixel centre); seed: the seed of every pixel hash. The
    // defaults give the pixels of the two quality modes, bit for bit.
    Renderer(std::unique_ptr<Scene> scene, int width, int height, Quality q, int grid = 0,
             uint32_t seed = kDefaultSeed);

    // Linear radiance of pixel (x, y) (averaged over its samples), before exposure; adds the
    // number of rays cast to *rays when given.
    Vec3 radiance(int x, int y, uint64_t *rays = nullptr) const;
    // Final 8-bit sRGB colour; outside the frame: (0, 0, 0).
    void pixel(int x, int y, uint8_t rgb[3], uint64_t *rays = nullptr) const;

    // What the primary ray through the pixel centre hits: triangle index + 1 over the whole
    // scene, material index + 1 (both 0 for the sky), and its depth along the camera's
    // viewing axis (+inf for the sky). Outside the frame: 0, 0, +inf.
    void gbuffer(int x, int y, uint32_t &prim, uint32_t &material, float &depth) const;

    // Tone mapping (exposure, ACES fit) and sRGB encoding, rounded to 8 bits.
    static void encode(Vec3 linear, float exposure, uint8_t rgb[3]);

    // Primary ray through image position (fx, fy) in pixels (pixel centre = x + 0.5).
    void primary_ray(float fx, float fy, Vec3 &org, Vec3 &dir) const;

    const Scene &scene() const { return *scene_; }
    int width() const { return width_; }
    int height() const { return height_; }
    Quality quality() const { return quality_; }
    int samples_per_pixel() const { return spp_; }
    int grid() const { return grid_; }
    uint32_t seed() const { return seed_; }

    static constexpr int kMaxDepth = 6;        // Whitted recursion limit (reflection/refraction)
    static constexpr int kHeavyGrid = 4;       // heavy mode: kHeavyGrid^2 samples per pixel
    static constexpr int kMaxGrid = 64;        // largest antialiasing grid (4096 samples per pixel)
    static constexpr uint32_t kDefaultSeed = 0x4d5352u;  // "MSR": the fixed seed of every pixel hash

private:
    struct Sample;
    // path: distance from the eye to org along the ray path (texture footprint).
    Vec3 trace(Vec3 org, Vec3 dir, int depth, float weight, float path, const Sample &s) const;
    Vec3 shade_diffuse(const Hit &h, Vec3 dir, Vec3 nf, Vec3 ngf, Vec3 albedo, const Material &m,
                       const Sample &s) const;
    float shadow(Vec3 org, Vec3 dir, float dist, Vec3 &tint, const Sample &s) const;
    Vec3 sky(Vec3 dir) const;

    std::unique_ptr<Scene> scene_;
    int width_, height_;
    Quality quality_;
    int grid_;
    int spp_;
    uint32_t seed_;
    Vec3 eye_, fwd_, right_, up_;
    float scale_;  // tan(fov/2) / (shorter side / 2): a pixel's width at unit distance
};

// x^n for an integer n >= 0 by repeated squaring (no libm pow).
float ipow(float x, int n);

// Smoothstep falloff of a spot light for the cosine c of the angle to its axis.
float spot_falloff(const PointLight &l, float c);

}  // namespace msr

// Unit tests of the rendering unit: ray casts on analytic geometry, the shading terms against
// closed-form or numerically integrated values, the elementary functions, and the C API
// (errors, determinism across call order and threads).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "detmath.h"
#include "msr_render.h"
#include "render.h"
#include "scene.h"
#include "scenes.h"

using namespace msr;

namespace {

constexpr double kPi = 3.14159265358979323846;

// One Embree device for the whole test program, pinned like the library's.
RTCDevice device() {
    static RTCDevice d = rtcNewDevice("isa=avx2");
    return d;
}

std::unique_ptr<Scene> committed(std::unique_ptr<Scene> s) {
    std::string err;
    EXPECT_TRUE(s->commit(device(), err)) << err;
    return s;
}

// Oracle of the output transform, written independently of the library: ACES fit, then the
// sRGB curve with std::pow, rounded half up.
int expected_code(double linear) {
    double x = std::max(0.0, linear);
    double y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    y = std::min(1.0, std::max(0.0, y));
    double c = y <= 0.0031308 ? 12.92 * y : 1.055 * std::pow(y, 1.0 / 2.4) - 0.055;
    return int(std::floor(c * 255.0 + 0.5));
}

// Camera at eye looking at target; a 1x1 frame shoots exactly one ray, eye -> target.
void aim(Scene &s, Vec3 eye, Vec3 target, Vec3 up = {0.f, 1.f, 0.f}) {
    s.camera.eye = eye;
    s.camera.target = target;
    s.camera.up = up;
}

Vec3 radiance_1x1(std::unique_ptr<Scene> s) {
    Renderer r(committed(std::move(s)), 1, 1, Quality::Fast);
    return r.radiance(0, 0);
}

}  // namespace

// ---- ray casts --------------------------------------------------------------------------------

TEST(RayCast, QuadHitAndMiss) {
    auto s = std::make_unique<Scene>();
    int m = s->add_material(Material::diffuse({0.5f, 0.5f, 0.5f}));
    s->add_quad({-1, -1, 0}, {-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, m);  // faces -z
    s = committed(std::move(s));

    Hit h = s->intersect({0.3f, -0.2f, -5.f}, {0, 0, 1}, 0.f, 100.f);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.t, 5.f, 1e-5f);
    EXPECT_NEAR(h.p.x, 0.3f, 1e-6f);
    EXPECT_NEAR(h.p.y, -0.2f, 1e-6f);
    EXPECT_NEAR(h.ng.z, -1.f, 1e-6f);
    EXPECT_EQ(h.material, m);

    // Oblique hit: from (0,0,-4) towards (0.5, 0.5, 0), distance sqrt(16.5).
    Vec3 d = normalize(Vec3{0.5f, 0.5f, 4.f});
    h = s->intersect({0, 0, -4.f}, d, 0.f, 100.f);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.t, std::sqrt(16.5f), 1e-4f);

    EXPECT_FALSE(s->intersect({1.5f, 0.f, -5.f}, {0, 0, 1}, 0.f, 100.f).hit);   // beside the quad
    EXPECT_FALSE(s->intersect({0.f, 0.f, -5.f}, {0, 0, -1}, 0.f, 100.f).hit);   // pointing away
    EXPECT_FALSE(s->intersect({0.f, 0.f, -5.f}, {0, 0, 1}, 0.f, 4.9f).hit);     // too short
    EXPECT_TRUE(s->intersect({0.f, 0.f, 5.f}, {0, 0, -1}, 0.f, 100.f).hit);     // back side hits too
    EXPECT_TRUE(s->occluded({0.f, 0.f, -5.f}, {0, 0, 1}, 0.f, 5.1f, MASK_ALL));
    EXPECT_FALSE(s->occluded({0.f, 0.f, -5.f}, {0, 0, 1}, 0.f, 4.9f, MASK_ALL));
}

TEST(RayCast, BoxFacesAndOutwardNormals) {
    auto s = std::make_unique<Scene>();
    s->add_box({0, 0, 0}, {1, 2, 3}, s->add_material(Material::diffuse({0.5f, 0.5f, 0.5f})));
    s = committed(std::move(s));
    struct Case { Vec3 org, dir; float t; Vec3 n; };
    const Case cases[] = {
        {{-1.f, 0.7f, 1.3f}, {1, 0, 0}, 1.f, {-1, 0, 0}},
        {{3.f, 0.7f, 1.3f}, {-1, 0, 0}, 2.f, {1, 0, 0}},
        {{0.3f, -2.f, 1.3f}, {0, 1, 0}, 2.f, {0, -1, 0}},
        {{0.3f, 5.f, 1.3f}, {0, -1, 0}, 3.f, {0, 1, 0}},
        {{0.3f, 0.7f, -0.5f}, {0, 0, 1}, 0.5f, {0, 0, -1}},
        {{0.3f, 0.7f, 4.f}, {0, 0, -1}, 1.f, {0, 0, 1}},
        {{0.5f, 1.1f, 1.3f}, {0, 1, 0}, 0.9f, {0, 1, 0}},  // from inside: the far face
    };
    for (const Case &c : cases) {
        Hit h = s->intersect(c.org, c.dir, 0.f, 100.f);
        ASSERT_TRUE(h.hit);
        EXPECT_NEAR(h.t, c.t, 1e-5f);
        EXPECT_NEAR(dot(h.ng, c.n), 1.f, 1e-6f);
    }
    // Misses: passing beside, above and diagonally past a corner.
    EXPECT_FALSE(s->intersect({-1.f, 2.5f, 1.f}, {1, 0, 0}, 0.f, 100.f).hit);
    EXPECT_FALSE(s->intersect({-1.f, 1.f, 3.2f}, {1, 0, 0}, 0.f, 100.f).hit);
    EXPECT_FALSE(s->intersect({-1.f, -1.f, -1.f}, normalize(Vec3{1.f, 1.f, -0.1f}), 0.f, 100.f).hit);
}

TEST(RayCast, SphereHitsNearTheTrueSurface) {
    auto s = std::make_unique<Scene>();
    s->add_sphere({1.f, 2.f, 3.f}, 2.f, s->add_material(Material::diffuse({0.5f, 0.5f, 0.5f})));
    s = committed(std::move(s));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < 200; ++i) {
        Vec3 d = normalize(Vec3{u(rng), u(rng), u(rng)});
        Vec3 org = Vec3{1.f, 2.f, 3.f} + d * 10.f;
        Hit h = s->intersect(org, -d, 0.f, 100.f);
        ASSERT_TRUE(h.hit);
        EXPECT_NEAR(h.t, 8.f, 2.f * 0.005f);  // 5120 faces: the chords sag < 0.5 % of r
        EXPECT_GT(dot(h.ng, d), 0.95f);         // outward winding
        EXPECT_NEAR(dot(h.ns, d), 1.f, 1e-3f);  // smooth normal is the radial direction
    }
    EXPECT_FALSE(s->intersect({1.f, 2.f + 2.1f, -10.f}, {0, 0, 1}, 0.f, 100.f).hit);
}

TEST(RayCast, GlassIsMaskedOutOfShadowRays) {
    auto s = std::make_unique<Scene>();
    s->add_quad({-1, -1, 0}, {-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, s->add_material(Material::glass({1, 1, 1}, 1.5f)));
    s = committed(std::move(s));
    EXPECT_TRUE(s->has_glass());
    EXPECT_TRUE(s->occluded({0, 0, -1}, {0, 0, 1}, 0.f, 2.f, MASK_ALL));
    EXPECT_TRUE(s->occluded({0, 0, -1}, {0, 0, 1}, 0.f, 2.f, MASK_GLASS));
    EXPECT_FALSE(s->occluded({0, 0, -1}, {0, 0, 1}, 0.f, 2.f, MASK_OPAQUE));
}

TEST(RayCast, EmptySceneIsAnError) {
    Scene s;
    std::string err;
    EXPECT_FALSE(s.commit(device(), err));
    EXPECT_NE(err.find("no triangles"), std::string::npos);
}

// ---- shading ------------------------------------------------------------------------------------

// Floor y = 0 seen straight down; point light above; optionally a small quad near, but off,
// both the camera ray and the shadow ray.
std::unique_ptr<Scene> floor_scene(bool blocked) {
    auto s = std::make_unique<Scene>();
    int m = s->add_material(Material::diffuse({0.5f, 0.4f, 0.3f}));
    s->add_quad({-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, m);
    if (blocked) s->add_quad({0.5f, 2, -0.1f}, {0.5f, 2, 0.1f}, {0.7f, 2, 0.1f}, {0.7f, 2, -0.1f}, m);
    s->add_point_light({{0.f, 4.f, 3.f}, {2.f, 2.f, 2.f}});
    s->ambient = {0.1f, 0.1f, 0.1f};
    aim(*s, {0.f, 5.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f});
    return s;
}

TEST(Shading, PointLightAndShadowRay) {
    // Lit: albedo / pi * I * cos / d^2 + albedo * ambient, with d^2 = 25, cos = 4/5.
    Vec3 lit = radiance_1x1(floor_scene(false));
    const double e = 2.0 * 0.8 / 25.0;
    const double alb[3] = {0.5, 0.4, 0.3};
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(lit[i], alb[i] / kPi * e + alb[i] * 0.1, 1e-6);
    // The quad off the light path casts no shadow on the origin.
    Vec3 side = radiance_1x1(floor_scene(true));
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(side[i], lit[i], 1e-6);
}

TEST(Shading, ShadowedPointGetsAmbientOnly) {
    auto s = floor_scene(false);
    int m = s->add_material(Material::diffuse({0.9f, 0.9f, 0.9f}));
    s->add_quad({-0.2f, 2, 1.3f}, {-0.2f, 2, 1.7f}, {0.2f, 2, 1.7f}, {0.2f, 2, 1.3f}, m);  // on the light path
    Vec3 c = radiance_1x1(std::move(s));
    EXPECT_NEAR(c.x, 0.5f * 0.1f, 1e-6f);
    EXPECT_NEAR(c.y, 0.4f * 0.1f, 1e-6f);
    EXPECT_NEAR(c.z, 0.3f * 0.1f, 1e-6f);
}

// Numerical oracle: E = integral over the emitter of cos_p * cos_l / d^2 (midpoint rule).
double irradiance_numeric(Vec3 p, Vec3 n, const AreaLight &l, int steps = 600) {
    Vec3 ln = normalize(cross(l.e1, l.e2));
    double area = length(cross(l.e1, l.e2)), sum = 0.0;
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
            Vec3 q = l.corner + l.e1 * ((i + 0.5f) / steps) + l.e2 * ((j + 0.5f) / steps);
            Vec3 d = q - p;
            double d2 = dot(d, d), dist = std::sqrt(d2);
            double cp = dot(n, d) / dist, cl = -dot(ln, d) / dist;
            if (cp > 0 && cl > 0) sum += cp * cl / d2;
        }
    return sum * area / (double(steps) * steps);
}

// The light of the shading tests: a 2 x 2 square centred above the origin at height 3,
// emitting down.
AreaLight square_light(Vec3 radiance = {1.f, 1.f, 1.f}) {
    AreaLight l;
    l.corner = {-1.f, 3.f, -1.f};
    l.e1 = {2.f, 0.f, 0.f};
    l.e2 = {0.f, 0.f, 2.f};
    l.radiance = radiance;
    return l;
}

TEST(Shading, PolygonIrradianceMatchesClosedFormAndIntegration) {
    AreaLight l = square_light();
    // Point under the centre: 4 x the corner form factor of a 1 x 1 rectangle at height 3
    // (F = (1/2pi)[X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))]);
    // E = pi * F for unit radiance.
    double X = 1.0 / 3.0, Y = 1.0 / 3.0;
    double F = (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
                Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) / (2 * kPi);
    EXPECT_NEAR(polygon_irradiance({0, 0, 0}, {0, 1, 0}, l), kPi * 4 * F, 1e-6);
    // Tilted receivers, including ones whose horizon cuts the light (clipping).
    struct Case { Vec3 p, n; };
    const Case cases[] = {{{0.5f, 0.f, 0.2f}, normalize(Vec3{0.3f, 1.f, 0.1f})},
                          {{0.f, 1.f, 0.f}, {1.f, 0.f, 0.f}},                     // half the light above the horizon
                          {{0.3f, 2.f, -2.f}, normalize(Vec3{0.2f, 0.4f, 1.f})},
                          {{2.f, 2.5f, 0.f}, normalize(Vec3{-1.f, 0.2f, 0.f})}};
    for (const Case &c : cases) {
        double ref = irradiance_numeric(c.p, c.n, l);
        EXPECT_NEAR(polygon_irradiance(c.p, c.n, l), ref, 2e-3 * std::max(ref, 0.05)) << c.p.x << "," << c.p.y;
    }
    EXPECT_EQ(polygon_irradiance({0, 4, 0}, {0, -1, 0}, l), 0.f);  // behind the emitter
    EXPECT_EQ(polygon_irradiance({0, 0, 0}, {0, -1, 0}, l), 0.f);  // facing away
}

TEST(Shading, AreaLightFloorPixel) {
    auto s = std::make_unique<Scene>();
    int m = s->add_material(Material::diffuse({0.6f, 0.6f, 0.6f}));
    s->add_quad({-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, m);
    AreaLight l = square_light({2.f, 1.f, 0.5f});
    s->add_area_light(l);
    aim(*s, {0.f, 2.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f});
    double e = irradiance_numeric({0, 0, 0}, {0, 1, 0}, l, 800);
    Vec3 c = radiance_1x1(std::move(s));
    EXPECT_NEAR(c.x, 0.6 / kPi * 2.0 * e, 1e-4);
    EXPECT_NEAR(c.y, 0.6 / kPi * 1.0 * e, 1e-4);
    EXPECT_NEAR(c.z, 0.6 / kPi * 0.5 * e, 1e-4);
}

TEST(Shading, AreaLightCutByTheHorizonIsNotShadowedTwice) {
    // A wall x = 0 facing +x; the light straddles its plane, so half of it is below the
    // horizon of the wall points. Nothing occludes: the pixel must equal albedo / pi * L * E
    // with E the irradiance of the visible half (numerical integration), in both modes.
    for (Quality q : {Quality::Fast, Quality::Heavy}) {
        auto s = std::make_unique<Scene>();
        int m = s->add_material(Material::diffuse({0.6f, 0.6f, 0.6f}));
        s->add_quad({0, -5, -5}, {0, -5, 5}, {0, 2, 5}, {0, 2, -5}, m);
        AreaLight l = square_light();
        s->add_area_light(l);
        aim(*s, {2.f, 1.f, 0.f}, {0.f, 1.f, 0.f});
        double e = irradiance_numeric({0, 1, 0}, {1, 0, 0}, l, 800);
        Renderer r(committed(std::move(s)), 1, 1, q);
        // Heavy mode jitters the primary ray inside the pixel: a 1x1 frame spans the whole
        // 40 degree view, so compare the centre ray only in fast mode, and allow heavy mode
        // the spread of its 16 hit points.
        Vec3 c = r.radiance(0, 0);
        if (q == Quality::Fast) EXPECT_NEAR(c.x, 0.6 / kPi * e, 1e-4);
        else EXPECT_NEAR(c.x, 0.6 / kPi * e, 0.15 * 0.6 / kPi * e);
    }
}

TEST(Shading, MirrorReflectsTheEmitterBehindTheCamera) {
    auto s = std::make_unique<Scene>();
    s->add_quad({-5, -5, 5}, {-5, 5, 5}, {5, 5, 5}, {5, -5, 5}, s->add_material(Material::mirror({0.8f, 0.7f, 0.6f})));
    // Emitter at z = -1 facing +z (towards the mirror); the camera at z = 0 does not block.
    s->add_quad({-5, -5, -1}, {5, -5, -1}, {5, 5, -1}, {-5, 5, -1}, s->add_material(Material::emissive({0.5f, 0.5f, 0.5f})));
    aim(*s, {0, 0, 0}, {0, 0, 1});
    Vec3 c = radiance_1x1(std::move(s));
    EXPECT_NEAR(c.x, 0.4f, 1e-6f);
    EXPECT_NEAR(c.y, 0.35f, 1e-6f);
    EXPECT_NEAR(c.z, 0.3f, 1e-6f);
}

TEST(Shading, GlassSlabTransmitsTwoFresnelFactors) {
    auto s = std::make_unique<Scene>();
    s->add_box({-10, -10, 1}, {10, 10, 2}, s->add_material(Material::glass({1, 1, 1}, 1.5f)));
    s->add_quad({-20, -20, 5}, {-20, 20, 5}, {20, 20, 5}, {20, -20, 5}, s->add_material(Material::emissive({1.f, 2.f, 3.f})));
    aim(*s, {0, 0, 0}, {0, 0, 1});
    // Normal incidence: R = ((1.5 - 1) / (1.5 + 1))^2 = 0.04 per face, T = 0.96^2 through
    // the slab; the doubly reflected part (0.96^2 * 0.04^2 = 0.15 %) is below the ray cut-off.
    Vec3 c = radiance_1x1(std::move(s));
    EXPECT_NEAR(c.x, 0.9216f * 1.f, 1e-4f);
    EXPECT_NEAR(c.y, 0.9216f * 2.f, 2e-4f);
    EXPECT_NEAR(c.z, 0.9216f * 3.f, 3e-4f);
}

TEST(Shading, GlassBendsRaysBySnellsLaw) {
    // A slab between the planes n.p = 1 and n.p = 2, tilted 40 degrees against the camera ray
    // (+z from the origin). The ray leaves parallel to itself, shifted sideways; a thin
    // emitter strip at z = 10 is seen only where Snell's law (computed here in double) puts
    // the exit point, not on the straight line nor at the mirrored shift.
    const double ia = 40.0 * kPi / 180.0, eta = 1.0 / 1.5;
    const double n[3] = {std::sin(ia), 0.0, std::cos(ia)};
    const double cosi = n[2], cost = std::sqrt(1.0 - eta * eta * (1.0 - cosi * cosi));
    // Inside direction: eta d + (eta cos_i - cos_t) n_f with n_f = -n facing the ray.
    double tin[3];
    for (int k = 0; k < 3; ++k) tin[k] = eta * (k == 2 ? 1.0 : 0.0) - (eta * cosi - cost) * n[k];
    const double p1z = 1.0 / cosi;                           // entry point (0, 0, p1z)
    const double len = 1.0 / (n[0] * tin[0] + n[2] * tin[2]);  // to the plane n.p = 2
    const double x_exit = tin[0] * len;
    ASSERT_GT(std::fabs(x_exit), 0.2);
    (void)p1z;
    auto make = [&](double strip_x) {
        auto s = std::make_unique<Scene>();
        s->add_box({1, -20, -20}, {2, 20, 20}, s->add_material(Material::glass({1, 1, 1}, 1.5f)));
        // Rotate the box frame (x, y, z) onto (n, up, -t): a proper rotation about y.
        Vec3 nn{float(n[0]), 0.f, float(n[2])}, up{0, 1, 0}, w = cross(nn, up);
        for (Vec3 &p : s->meshes.back().pos) p = nn * p.x + up * p.y + w * p.z;
        int e = s->add_material(Material::emissive({1.f, 1.f, 1.f}));
        float x0 = float(strip_x) - 0.05f, x1 = float(strip_x) + 0.05f;
        s->add_quad({x0, -5, 10}, {x0, 5, 10}, {x1, 5, 10}, {x1, -5, 10}, e);
        aim(*s, {0, 0, 0}, {0, 0, 1});
        return s;
    };
    EXPECT_GT(radiance_1x1(make(x_exit)).x, 0.8f);  // ~ (1 - F)^2 through two faces
    EXPECT_LT(radiance_1x1(make(0.0)).x, 1e-3f);
    EXPECT_LT(radiance_1x1(make(-x_exit)).x, 1e-3f);
}

TEST(Shading, SkyGradientOnMiss) {
    auto s = std::make_unique<Scene>();
    s->add_quad({-1, -100, -1}, {-1, -100, 1}, {1, -100, 1}, {1, -100, -1}, s->add_material(Material::diffuse({0.5f, 0.5f, 0.5f})));
    s->sky_zenith = {0.f, 0.f, 1.f};
    s->sky_horizon = {1.f, 0.f, 0.f};
    aim(*s, {0, 0, 0}, {0, 1, 0}, {0, 0, 1});  // straight up: zenith
    Vec3 c = radiance_1x1(std::move(s));
    EXPECT_NEAR(c.x, 0.f, 1e-6f);
    EXPECT_NEAR(c.z, 1.f, 1e-6f);
}

// ---- output transform and elementary functions ----------------------------------------------

TEST(Output, SrgbThresholdsMatchPowOracle) {
    EXPECT_EQ(srgb8(0.f), 0);
    EXPECT_EQ(srgb8(1.f), 255);
    EXPECT_EQ(srgb8(2.f), 255);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    int checked = 0;
    for (int i = 0; i < 200000; ++i) {
        float v = i < 1000 ? float(i) / 999.f : u(rng) * u(rng);
        double c = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(double(v), 1.0 / 2.4) - 0.055;
        double q = c * 255.0;
        if (std::fabs(q - std::floor(q) - 0.5) < 1e-6) continue;  // too close to a tie for the oracle
        ASSERT_EQ(int(srgb8(v)), int(std::floor(q + 0.5))) << "v=" << v;
        ++checked;
    }
    EXPECT_GT(checked, 199000);
}

TEST(Output, EncodeAppliesExposureAcesAndSrgb) {
    for (float v : {0.f, 0.001f, 0.05f, 0.18f, 0.5f, 1.f, 3.f, 50.f}) {
        uint8_t rgb[3];
        Renderer::encode({v, v * 0.5f, v * 0.25f}, 2.f, rgb);
        EXPECT_EQ(rgb[0], expected_code(2.0 * v)) << v;
        EXPECT_EQ(rgb[1], expected_code(1.0 * v)) << v;
        EXPECT_EQ(rgb[2], expected_code(0.5 * v)) << v;
    }
    uint8_t rgb[3];
    Renderer::encode({NAN, -1.f, INFINITY}, 1.f, rgb);
    EXPECT_EQ(rgb[0], 0);
    EXPECT_EQ(rgb[1], 0);
    EXPECT_EQ(rgb[2], 0);
}

TEST(DetMath, AtanAndSincosMatchLibm) {
    for (int i = -200; i <= 200; ++i) {
        double y = std::sin(i * 0.1) * 3.0, x = std::cos(i * 0.37) * 2.0;
        EXPECT_NEAR(det_atan2(y, x), std::atan2(y, x), 1e-9);
        double a = i * (4.0 * kPi / 200.0), s, c;
        det_sincos(a, s, c);
        EXPECT_NEAR(s, std::sin(a), 1e-9);
        EXPECT_NEAR(c, std::cos(a), 1e-9);
    }
}

// ---- C API ------------------------------------------------------------------------------------------

namespace {
struct Ctx {
    msr_render_ctx *p;
    explicit Ctx(msr_render_ctx *c) : p(c) {}
    ~Ctx() { msr_render_destroy(p); }
};
}  // namespace

TEST(CApi, ErrorsAreOneLineAndReturnNull) {
    char err[256];
    struct Bad { const char *scene; int w, h, q; const char *needle; };
    const Bad bad[] = {{"no_such_scene_xyz", 64, 48, 0, "unknown scene"},
                       {"cornell", 0, 48, 0, "outside"},
                       {"cornell", 64, 5000, 0, "outside"},
                       {"cornell", 64, 48, 2, "quality"},
                       {"/proc/self/status", 64, 48, 0, "cannot read model file"}};
    for (const Bad &b : bad) {
        std::memset(err, 'x', sizeof err);
        EXPECT_EQ(msr_render_create(b.scene, b.w, b.h, b.q, err, sizeof err), nullptr) << b.scene;
        EXPECT_NE(std::strstr(err, b.needle), nullptr) << err;
        EXPECT_EQ(std::strchr(err, '\n'), nullptr);
    }
    EXPECT_EQ(msr_render_create(nullptr, 64, 48, 0, err, sizeof err), nullptr);
    EXPECT_EQ(msr_render_create("cornell", 64, 48, 9, nullptr, 0), nullptr);  // no buffer: still safe
    // A tiny buffer is truncated, never overrun.
    char small[8];
    small[7] = 'z';
    EXPECT_EQ(msr_render_create("no_such_scene_xyz", 64, 48, 0, small, 7), nullptr);
    EXPECT_EQ(small[6], '\0');
    EXPECT_EQ(small[7], 'z');
}

TEST(CApi, SceneNamesStartWithCornell) {
    std::string names = msr_render_scene_names();
    EXPECT_EQ(names.rfind("cornell,", 0), 0u);
    EXPECT_NE(names.find("showcase"), std::string::npos);
}

TEST(CApi, DeterministicAcrossOrderBatchesAndThreads) {
    for (int q = 0; q <= 1; ++q) {
        char err[256];
        const int W = 40, H = 30;
        Ctx c(msr_render_create("showcase", W, H, q, err, sizeof err));
        ASSERT_NE(c.p, nullptr) << err;
        std::vector<int32_t> xs, ys;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) { xs.push_back(x); ys.push_back(y); }
        const int n = W * H;
        std::vector<uint8_t> ref(3 * n);
        msr_render_pixels(c.p, n, xs.data(), ys.data(), ref.data());

        // One pixel at a time, in reverse order.
        for (int i = n - 1; i >= 0; --i) {
            uint8_t rgb[3];
            msr_render_pixel(c.p, xs[i], ys[i], rgb);
            ASSERT_EQ(0, std::memcmp(rgb, &ref[3 * i], 3)) << "pixel " << i;
        }
        // Shuffled, in uneven batches on 3 threads at once.
        std::vector<int> perm(n);
        for (int i = 0; i < n; ++i) perm[i] = i;
        std::shuffle(perm.begin(), perm.end(), std::mt19937(q + 11));
        std::vector<int32_t> px(n), py(n);
        for (int i = 0; i < n; ++i) { px[i] = xs[perm[i]]; py[i] = ys[perm[i]]; }
        std::vector<uint8_t> got(3 * n);
        const int cuts[4] = {0, 7, 601, n};
        std::vector<std::thread> th;
        for (int k = 0; k < 3; ++k)
            th.emplace_back([&, k] {
                msr_render_pixels(c.p, cuts[k + 1] - cuts[k], &px[cuts[k]], &py[cuts[k]], &got[3 * cuts[k]]);
            });
        for (auto &t : th) t.join();
        for (int i = 0; i < n; ++i) ASSERT_EQ(0, std::memcmp(&got[3 * i], &ref[3 * perm[i]], 3)) << "pixel " << perm[i];

        // A second context on the same scene gives the same pixels.
        Ctx c2(msr_render_create("showcase", W, H, q, err, sizeof err));
        std::vector<uint8_t> again(3 * n);
        msr_render_pixels(c2.p, n, xs.data(), ys.data(), again.data());
        EXPECT_EQ(ref, again);
    }
}

TEST(CApi, OutsideFrameAndNullAreBlack) {
    char err[256];
    Ctx c(msr_render_create("cornell", 16, 12, 0, err, sizeof err));
    ASSERT_NE(c.p, nullptr) << err;
    uint8_t rgb[3] = {1, 2, 3};
    msr_render_pixel(c.p, 16, 0, rgb);
    EXPECT_EQ(rgb[0] | rgb[1] | rgb[2], 0);
    rgb[0] = 9;
    msr_render_pixel(c.p, 0, -1, rgb);
    EXPECT_EQ(rgb[0] | rgb[1] | rgb[2], 0);
    rgb[0] = 9;
    msr_render_pixel(nullptr, 0, 0, rgb);
    EXPECT_EQ(rgb[0] | rgb[1] | rgb[2], 0);
    msr_render_destroy(nullptr);
}

TEST(CApi, HeavyCostsMoreAndDiffersOnlyModestly) {
    char err[256];
    Ctx f(msr_render_create("cornell", 32, 24, 0, err, sizeof err));
    Ctx h(msr_render_create("cornell", 32, 24, 1, err, sizeof err));
    ASSERT_NE(f.p, nullptr);
    ASSERT_NE(h.p, nullptr);
    std::vector<int32_t> xs, ys;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) { xs.push_back(x); ys.push_back(y); }
    std::vector<uint8_t> a(3 * xs.size()), b(3 * xs.size());
    msr_render_pixels(f.p, int(xs.size()), xs.data(), ys.data(), a.data());
    msr_render_pixels(h.p, int(xs.size()), xs.data(), ys.data(), b.data());
    double diff = 0;
    for (size_t i = 0; i < a.size(); ++i) diff += std::abs(int(a[i]) - int(b[i]));
    diff /= double(a.size());
    EXPECT_GT(diff, 0.5);   // a different estimator (AA, AO, sampled penumbrae)...
    EXPECT_LT(diff, 25.0);  // ...of the same picture
}

TEST(CApi, RayCounter) {
    char err[256];
    Ctx f(msr_render_create("cornell", 64, 48, 0, err, sizeof err));
    Ctx h(msr_render_create("cornell", 64, 48, 1, err, sizeof err));
    ASSERT_NE(f.p, nullptr);
    EXPECT_EQ(msr_render_rays(f.p), 0u);
    uint8_t rgb[3];
    msr_render_pixel(f.p, 0, 24, rgb);  // left of the box: one primary ray into the void
    EXPECT_EQ(msr_render_rays(f.p), 1u);
    msr_render_pixel(f.p, 18, 45, rgb);  // the floor, front left: primary + at least 4 shadow rays
    EXPECT_GE(msr_render_rays(f.p), 1u + 5u);
    EXPECT_LE(msr_render_rays(f.p), 1u + 1u + 20u);
    msr_render_pixel(h.p, 0, 24, rgb);  // heavy: 16 samples, all into the void
    EXPECT_EQ(msr_render_rays(h.p), 16u);
    msr_render_pixel(f.p, 99, 99, rgb);  // outside the frame: nothing cast
    EXPECT_LE(msr_render_rays(f.p), 22u);
    EXPECT_EQ(msr_render_rays(nullptr), 0u);
}

TEST(Scenes, AreaLightsShineAtWhatTheCameraSees) {
    // Every area light of every built-in scene faces the camera's target (an emitter turned
    // the wrong way lights nothing); checked through the scene description itself.
    std::string names = builtin_scene_names();
    size_t start = 0;
    int lights = 0;
    while (start <= names.size()) {
        size_t comma = names.find(',', start);
        std::string name = names.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        start = comma == std::string::npos ? names.size() + 1 : comma + 1;
        std::string err;
        auto s = make_scene(name, err);
        ASSERT_TRUE(s) << name << ": " << err;
        for (const AreaLight &l : s->area_lights) {
            Vec3 centre = l.corner + (l.e1 + l.e2) * 0.5f;
            EXPECT_GT(dot(normalize(s->camera.target - centre), l.normal()), 0.1f) << name;
            ++lights;
        }
    }
    EXPECT_GE(lights, 6);
}

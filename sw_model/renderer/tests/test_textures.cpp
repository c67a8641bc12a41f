// Unit tests of textures, file views and lights against hand-computed values: the sRGB decode
// table, wrap modes, bilinear filtering and its texel-centre convention, mip-map building
// and level selection, UV interpolation and texel density at a ray hit, the texture path
// quirks, the view string, the vertical field of view, spot falloff.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "importer.h"
#include "render.h"
#include "scene.h"
#include "scenes.h"
#include "texture.h"

using namespace msr;

namespace {

RTCDevice device() {
    static RTCDevice d = rtcNewDevice("isa=avx2");
    return d;
}

// A texture of w x h grey texels from 8-bit codes (row 0 = top of the picture).
Texture grey(int w, int h, const std::vector<uint8_t> &codes, Wrap wu = Wrap::Repeat, Wrap wv = Wrap::Repeat) {
    std::vector<uint8_t> rgb;
    for (uint8_t c : codes) rgb.insert(rgb.end(), {c, c, c});
    return Texture(w, h, 3, rgb.data(), wu, wv);
}

}  // namespace

TEST(Texture, SrgbDecodeMatchesTheCurve) {
    // IEC 61966-2-1: c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4, c = code / 255,
    // values worked out by hand (to 10 digits).
    EXPECT_EQ(srgb_to_linear(0), 0.f);
    EXPECT_EQ(srgb_to_linear(255), 1.f);
    EXPECT_NEAR(srgb_to_linear(3), 0.0009105809506f, 1e-10f);   // linear segment
    EXPECT_NEAR(srgb_to_linear(10), 0.003035269835f, 1e-9f);    // linear segment
    EXPECT_NEAR(srgb_to_linear(128), 0.2158605001f, 1e-7f);     // power segment
    EXPECT_NEAR(srgb_to_linear(188), 0.5028864580f, 1e-7f);
    for (int c = 1; c < 256; ++c) EXPECT_GT(srgb_to_linear(uint8_t(c)), srgb_to_linear(uint8_t(c - 1)));
    // Encoding a decoded code gives the code back.
    for (int c = 0; c < 256; ++c) EXPECT_EQ(int(srgb8(srgb_to_linear(uint8_t(c)))), c);
}

TEST(Texture, WrapModes) {
    EXPECT_EQ(wrap_index(-1, 4, Wrap::Repeat), 3);
    EXPECT_EQ(wrap_index(4, 4, Wrap::Repeat), 0);
    EXPECT_EQ(wrap_index(-9, 4, Wrap::Repeat), 3);
    EXPECT_EQ(wrap_index(-1, 4, Wrap::Clamp), 0);
    EXPECT_EQ(wrap_index(7, 4, Wrap::Clamp), 3);
    EXPECT_EQ(wrap_index(-1, 4, Wrap::Mirror), 0);   // ... 1 0 | 0 1 2 3 | 3 2 1 0 | 0 ...
    EXPECT_EQ(wrap_index(4, 4, Wrap::Mirror), 3);
    EXPECT_EQ(wrap_index(5, 4, Wrap::Mirror), 2);
    EXPECT_EQ(wrap_index(8, 4, Wrap::Mirror), 0);
    EXPECT_EQ(wrap_index(-5, 4, Wrap::Mirror), 3);
}

TEST(Texture, BilinearAtTexelCentresAndBetween) {
    // Two texels in a row: black (linear 0) and white (linear 1); centres at u = 0.25, 0.75.
    Texture t = grey(2, 1, {0, 255});
    EXPECT_FLOAT_EQ(t.bilinear(0, 0.25f, 0.5f).x, 0.f);
    EXPECT_FLOAT_EQ(t.bilinear(0, 0.75f, 0.5f).x, 1.f);
    EXPECT_FLOAT_EQ(t.bilinear(0, 0.5f, 0.5f).x, 0.5f);
    EXPECT_FLOAT_EQ(t.bilinear(0, 0.375f, 0.5f).x, 0.25f);
    // u = 0 lies half-way between texel 0 and texel -1: the wrap mode decides.
    EXPECT_FLOAT_EQ(t.bilinear(0, 0.f, 0.5f).x, 0.5f);                                   // repeat: -1 -> 1
    EXPECT_FLOAT_EQ(grey(2, 1, {0, 255}, Wrap::Clamp).bilinear(0, 0.f, 0.5f).x, 0.f);    // clamp: -1 -> 0
    EXPECT_FLOAT_EQ(grey(2, 1, {0, 255}, Wrap::Mirror).bilinear(0, 0.f, 0.5f).x, 0.f);   // mirror: -1 -> 0
    EXPECT_FLOAT_EQ(grey(2, 1, {0, 255}, Wrap::Mirror).bilinear(0, 1.f, 0.5f).x, 1.f);   // mirror: 2 -> 1
    // Repeat: a shift by whole periods changes nothing.
    EXPECT_FLOAT_EQ(t.bilinear(0, 3.375f, -6.5f).x, 0.25f);
    // Clamp far outside: the edge texel.
    EXPECT_FLOAT_EQ(grey(2, 1, {0, 255}, Wrap::Clamp).bilinear(0, 40.f, 0.5f).x, 1.f);
    // v runs upwards, picture rows downwards: row 0 (white) is the top, v = 0.75.
    Texture col = grey(1, 2, {255, 0});
    EXPECT_FLOAT_EQ(col.bilinear(0, 0.5f, 0.75f).x, 1.f);
    EXPECT_FLOAT_EQ(col.bilinear(0, 0.5f, 0.25f).x, 0.f);
    EXPECT_FLOAT_EQ(col.bilinear(0, 0.5f, 0.625f).x, 0.75f);
}

TEST(Texture, MipChainIsBoxFiltered) {
    // 4 x 2: columns alternate black and white; each level halves both sides down to 1 x 1.
    Texture t = grey(4, 2, {0, 255, 0, 255, 0, 255, 0, 255});
    ASSERT_EQ(t.levels(), 3);  // 4x2, 2x1, 1x1
    EXPECT_FLOAT_EQ(t.texel(1, 0, 0).x, 0.5f);
    EXPECT_FLOAT_EQ(t.texel(1, 1, 0).x, 0.5f);
    EXPECT_FLOAT_EQ(t.texel(2, 0, 0).x, 0.5f);
    // Odd sizes: 3 x 1 -> 1 x 1 averages texels 0 and 1 (the last column is dropped).
    Texture odd = grey(3, 1, {0, 255, 255});
    ASSERT_EQ(odd.levels(), 2);
    EXPECT_FLOAT_EQ(odd.texel(1, 0, 0).x, 0.5f);
}

TEST(Texture, MipLevelFromFootprint) {
    int l;
    float f;
    mip_level(0.3f, l, f);  EXPECT_EQ(l, 0); EXPECT_EQ(f, 0.f);   // magnified: level 0
    mip_level(1.f, l, f);   EXPECT_EQ(l, 0); EXPECT_EQ(f, 0.f);
    mip_level(1.5f, l, f);  EXPECT_EQ(l, 0); EXPECT_EQ(f, 0.5f);
    mip_level(2.f, l, f);   EXPECT_EQ(l, 1); EXPECT_EQ(f, 0.f);
    mip_level(3.f, l, f);   EXPECT_EQ(l, 1); EXPECT_EQ(f, 0.5f);
    mip_level(8.f, l, f);   EXPECT_EQ(l, 3); EXPECT_EQ(f, 0.f);
    mip_level(12.f, l, f);  EXPECT_EQ(l, 3); EXPECT_EQ(f, 0.5f);
    mip_level(NAN, l, f);   EXPECT_EQ(l, 0); EXPECT_EQ(f, 0.f);
    // Trilinear: a footprint of 1.5 texels blends levels 0 and 1 half and half; beyond the
    // chain the last level.
    Texture t = grey(2, 1, {0, 255});
    EXPECT_FLOAT_EQ(t.sample(0.25f, 0.5f, 1.f).x, 0.f);
    EXPECT_FLOAT_EQ(t.sample(0.25f, 0.5f, 2.f).x, 0.5f);
    EXPECT_FLOAT_EQ(t.sample(0.25f, 0.5f, 1.5f).x, 0.25f);
    EXPECT_FLOAT_EQ(t.sample(0.25f, 0.5f, 1e6f).x, 0.5f);
}

TEST(Texture, UvInterpolationAndTexelDensityAtAHit) {
    Scene s;
    Material m = Material::diffuse({0.5f, 0.5f, 0.5f});
    std::vector<uint8_t> px(64 * 32 * 3, 128);
    s.textures.push_back(std::make_shared<const Texture>(64, 32, 3, px.data(), Wrap::Repeat, Wrap::Repeat));
    m.texture = 0;
    int mat = s.add_material(m);
    Mesh mesh;
    mesh.pos = {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}};
    mesh.idx = {0, 1, 2};
    mesh.uv = {0.2f, 0.1f, 0.6f, 0.1f, 0.2f, 0.9f};
    mesh.material = mat;
    s.add_mesh(mesh);
    std::string err;
    ASSERT_TRUE(s.commit(device(), err)) << err;
    // Hit at (0.25, 0.5): barycentrics 0.25 (vertex 1) and 0.5 (vertex 2).
    Hit h = s.intersect({0.25f, 0.5f, 1.f}, {0.f, 0.f, -1.f}, 0.f, 10.f);
    ASSERT_TRUE(h.hit);
    ASSERT_TRUE(h.has_uv);
    EXPECT_NEAR(h.tu, 0.2f + 0.4f * 0.25f, 1e-6f);  // 0.3
    EXPECT_NEAR(h.tv, 0.1f + 0.8f * 0.5f, 1e-6f);   // 0.5
    // UV area 0.5 * 0.4 * 0.8 = 0.16 of 64 x 32 texels = 327.68 texels on 0.5 world units^2:
    // sqrt(655.36) = 25.6 texels per unit length.
    EXPECT_NEAR(h.texel_density, 25.6f, 1e-4f);
}

TEST(Texture, TexturedQuadShowsItsTexels) {
    // A 2 x 2 texture (red, green / blue, white), clamped, on a quad facing the camera that
    // fills a 4 x 4 frame: half a texel per pixel (level 0), and the corner pixels see
    // only their corner texel.
    auto s = std::make_unique<Scene>();
    const uint8_t px[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    s->textures.push_back(std::make_shared<const Texture>(2, 2, 3, px, Wrap::Clamp, Wrap::Clamp));
    Material m = Material::diffuse({0.9f, 0.9f, 0.9f});
    m.texture = 0;
    int mat = s->add_material(m);
    Mesh q;
    q.pos = {{-1.f, -1.f, 0.f}, {1.f, -1.f, 0.f}, {1.f, 1.f, 0.f}, {-1.f, 1.f, 0.f}};
    q.idx = {0, 1, 2, 0, 2, 3};
    q.uv = {0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f, 1.f};
    q.material = mat;
    s->add_mesh(q);
    s->ambient = {1.f, 1.f, 1.f};  // unlit but for the ambient term: radiance = albedo
    s->camera.eye = {0.f, 0.f, 10.f};
    s->camera.target = {0.f, 0.f, 0.f};
    s->camera.tan_half = 0.1f;  // the frame spans exactly the quad (2 units at distance 10)
    std::string err;
    ASSERT_TRUE(s->commit(device(), err)) << err;
    Renderer r(std::move(s), 4, 4, Quality::Fast);
    Vec3 tl = r.radiance(0, 0), tr = r.radiance(3, 0), bl = r.radiance(0, 3), br = r.radiance(3, 3);
    EXPECT_NEAR(tl.x, 0.9f, 1e-5f); EXPECT_NEAR(tl.y, 0.f, 1e-5f);    // red (top left)
    EXPECT_NEAR(tr.y, 0.9f, 1e-5f); EXPECT_NEAR(tr.x, 0.f, 1e-5f);    // green
    EXPECT_NEAR(bl.z, 0.9f, 1e-5f); EXPECT_NEAR(bl.x, 0.f, 1e-5f);    // blue
    EXPECT_NEAR(br.x, 0.9f, 1e-5f); EXPECT_NEAR(br.z, 0.9f, 1e-5f);   // white
}

TEST(Texture, FindsFilesDespiteCaseAndBackslashes) {
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / ("msr_tex_" + std::to_string(::getpid()));
    fs::create_directories(dir / "Maps");
    std::ofstream(dir / "Maps" / "Wood Grain.PNG") << "x";
    std::ofstream(dir / "Bark.JPG") << "x";
    const std::string d = dir.string();
    const std::string want = (dir / "Maps" / "Wood Grain.PNG").string();
    EXPECT_EQ(find_texture_file(d, "Maps/Wood Grain.PNG"), want);
    EXPECT_EQ(find_texture_file(d, "maps\\wood grain.png"), want);
    EXPECT_EQ(find_texture_file(d, ".\\MAPS\\Wood%20Grain.png"), want);
    EXPECT_EQ(find_texture_file(d, "C:\\Users\\someone\\textures\\bark.jpg"), (dir / "Bark.JPG").string());  // bare name
    EXPECT_EQ(find_texture_file(d, "file://" + want), want);
    EXPECT_EQ(find_texture_file(d, "missing.png"), "");
    // From the drive's root on Windows ("\\..\\"): relative to the model's folder.
    fs::create_directories(dir / "model");
    const std::string up = find_texture_file((dir / "model").string(), "\\..\\maps\\WOOD GRAIN.png");
    EXPECT_EQ(fs::path(up).lexically_normal(), fs::path(want));
    fs::remove_all(dir);
}

TEST(View, ParsesTheCameraString) {
    float v[7];
    std::string err;
    ASSERT_TRUE(parse_view("1,2,3,4,5,6,40", v, err)) << err;
    EXPECT_EQ(v[0], 1.f); EXPECT_EQ(v[5], 6.f); EXPECT_EQ(v[6], 40.f);
    ASSERT_TRUE(parse_view(" -1.5, +2e1 ,3,0,0,0,0.5", v, err)) << err;
    EXPECT_EQ(v[0], -1.5f); EXPECT_EQ(v[1], 20.f);
    for (const char *bad : {"", "1,2,3", "1,2,3,4,5,6,7,8", "1,2,3,4,5,6,x", "1,2,3,4,5,6,180", "1,2,3,4,5,6,0",
                            "1,2,3,1,2,3,40", "1,2,3,4,5,6,inf", "1,,3,4,5,6,40", "1,2,3,4,5,6,40,"}) {
        err.clear();
        EXPECT_FALSE(parse_view(bad, v, err)) << bad;
        EXPECT_FALSE(err.empty());
        EXPECT_EQ(err.find('\n'), std::string::npos);
    }
}

TEST(View, VerticalFieldOfViewAndModelUnits) {
    // A 90 degree vertical view: the ray through the top edge's middle is 45 degrees up,
    // whatever the frame's aspect; eye and target go through the model placement.
    auto s = std::make_unique<Scene>();
    s->add_quad({-1.f, -1.f, -5.f}, {1.f, -1.f, -5.f}, {1.f, 1.f, -5.f}, {-1.f, 1.f, -5.f}, s->add_material(Material::diffuse({0.5f, 0.5f, 0.5f})));
    s->model_placement.scale = 2.f;
    s->model_placement.offset = {1.f, 0.f, 0.f};
    std::string err;
    ASSERT_TRUE(set_view(*s, "0,0,0,0,0,-1,90", err)) << err;
    EXPECT_EQ(s->camera.eye.x, 1.f);
    EXPECT_EQ(s->camera.target.z, -2.f);
    EXPECT_NEAR(s->camera.tan_half, 1.f, 1e-6f);
    ASSERT_TRUE(s->commit(device(), err)) << err;
    Renderer r(std::move(s), 40, 10, Quality::Fast);
    Vec3 org, dir;
    r.primary_ray(20.f, 0.f, org, dir);
    EXPECT_NEAR(dir.y, std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(dir.z, -std::sqrt(0.5f), 1e-6f);
    r.primary_ray(40.f, 5.f, org, dir);  // right edge: 4 x wider than tall
    EXPECT_NEAR(dir.x / -dir.z, 4.f, 1e-5f);
}

TEST(Lights, SpotFalloffAndIntegerPower) {
    PointLight l;
    l.dir = {0.f, -1.f, 0.f};
    l.cos_inner = 0.9f;
    l.cos_outer = 0.7f;
    EXPECT_EQ(spot_falloff(l, 0.95f), 1.f);
    EXPECT_EQ(spot_falloff(l, 0.6f), 0.f);
    EXPECT_NEAR(spot_falloff(l, 0.8f), 0.5f, 1e-6f);  // smoothstep(0.5) = 0.5
    EXPECT_NEAR(spot_falloff(l, 0.75f), 0.15625f, 1e-6f);  // t = 0.25: 3 t^2 - 2 t^3
    EXPECT_EQ(ipow(0.5f, 0), 1.f);
    EXPECT_EQ(ipow(0.5f, 5), 0.03125f);
    EXPECT_EQ(ipow(3.f, 4), 81.f);
}

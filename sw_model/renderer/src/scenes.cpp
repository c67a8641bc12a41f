#include "scenes.h"

#include <array>
#include <charconv>
#include <cmath>
#include <functional>

#include "detmath.h"
#include "importer.h"

namespace msr {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kTan20 = 0.36397023f;  // tan(20 deg): a 40 degree field of view

// ---- Cornell box ---------------------------------------------------------------------------
// Geometry and camera from the Cornell University Program of Computer Graphics measurements
// (graphics.cornell.edu/online/box/data.html), in millimetres. RGB reflectances are the usual
// fits of the measured spectra. The light sits 0.1 mm below the ceiling (the data puts both in
// one plane, which would z-fight).
const Vec3 kCornellWhite{0.73f, 0.73f, 0.73f}, kCornellRed{0.63f, 0.065f, 0.05f}, kCornellGreen{0.14f, 0.45f, 0.091f};

// The framing of a subject whose bounding box (model units) is b: as framed_model places a model.
Placement framing_of(const Bounds &b) {
    Placement pl;
    Vec3 c = b.center();
    pl.pivot = {c.x, b.lo.y, c.z};
    pl.scale = 1.f / (0.5f * length(b.size()));
    return pl;
}

void cornell_shell(Scene &s) {
    int white = s.add_material(Material::diffuse(kCornellWhite));
    int red = s.add_material(Material::diffuse(kCornellRed));
    int green = s.add_material(Material::diffuse(kCornellGreen));
    s.add_quad({552.8f, 0.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 559.2f}, {549.6f, 0.f, 559.2f}, white);          // floor
    s.add_quad({556.f, 548.8f, 0.f}, {556.f, 548.8f, 559.2f}, {0.f, 548.8f, 559.2f}, {0.f, 548.8f, 0.f}, white);  // ceiling
    s.add_quad({549.6f, 0.f, 559.2f}, {0.f, 0.f, 559.2f}, {0.f, 548.8f, 559.2f}, {556.f, 548.8f, 559.2f}, white); // back
    s.add_quad({0.f, 0.f, 559.2f}, {0.f, 0.f, 0.f}, {0.f, 548.8f, 0.f}, {0.f, 548.8f, 559.2f}, green);            // right
    s.add_quad({552.8f, 0.f, 0.f}, {549.6f, 0.f, 559.2f}, {556.f, 548.8f, 559.2f}, {556.f, 548.8f, 0.f}, red);    // left
    // Light: 130 x 105 mm, emitting downwards (cross(e1, e2) = -y).
    AreaLight l;
    l.corner = {213.f, 548.7f, 227.f};
    l.e1 = {130.f, 0.f, 0.f};
    l.e2 = {0.f, 0.f, 105.f};
    l.radiance = {17.f, 12.f, 4.f};
    s.add_area_light(l);
    s.framing = framing_of(Bounds{{0.f, 0.f, 0.f}, {556.f, 548.8f, 559.2f}});  // the box
    s.camera.eye = {278.f, 273.f, -800.f};
    s.camera.target = {278.f, 273.f, -799.f};
    s.camera.up = {0.f, 1.f, 0.f};
    s.camera.tan_half = 12.5f / 35.f;  // 25 mm film, 35 mm lens
    // Whitted's ambient term stands in for the box's strong interreflection.
    s.ambient = {0.055f, 0.048f, 0.036f};
    s.ao_radius = 180.f;
    s.exposure = 3.2f;
}

void cornell_blocks(Scene &s) {
    int white = s.add_material(Material::diffuse(kCornellWhite));
    // A block of height h over its footprint c[0..3] ((x, z) corners): the top quad, then one
    // side quad per footprint edge, from corner j to the corner before it (bottom, top, top,
    // bottom), for j in the order of `sides` (the quads' order of the published box data).
    auto block = [&](const float (&c)[4][2], float h, const std::array<int, 4> &sides) {
        Mesh m;
        m.material = white;
        auto vertex = [&](int k, float y) { m.pos.push_back({c[k][0], y, c[k][1]}); };
        auto quad = [&](int k0, float y0, int k1, float y1, int k2, float y2, int k3, float y3) {
            uint32_t b = uint32_t(m.pos.size());
            vertex(k0, y0);
            vertex(k1, y1);
            vertex(k2, y2);
            vertex(k3, y3);
            m.idx.insert(m.idx.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
        };
        quad(0, h, 1, h, 2, h, 3, h);
        for (int j : sides) quad(j, 0.f, j, h, (j + 3) % 4, h, (j + 3) % 4, 0.f);
        s.add_mesh(std::move(m));
    };
    static const float short_block[4][2] = {{130, 65}, {82, 225}, {240, 272}, {290, 114}};
    static const float tall_block[4][2] = {{423, 247}, {265, 296}, {314, 456}, {472, 406}};
    block(short_block, 165.f, {3, 0, 1, 2});
    block(tall_block, 330.f, {0, 3, 2, 1});
}

std::unique_ptr<Scene> cornell(std::string &) {
    auto s = std::make_unique<Scene>();
    cornell_shell(*s);
    cornell_blocks(*s);
    return s;
}

// ---- Showcase: mirror and glass over a checker floor ----------------------------------------
std::unique_ptr<Scene> showcase(std::string &) {
    auto s = std::make_unique<Scene>();
    Material floor = Material::diffuse({0.8f, 0.8f, 0.78f});
    floor.albedo2 = {0.12f, 0.13f, 0.2f};
    floor.checker = 1.f;
    int fl = s->add_material(floor);
    s->add_quad({-40.f, 0.f, -40.f}, {-40.f, 0.f, 40.f}, {40.f, 0.f, 40.f}, {40.f, 0.f, -40.f}, fl);
    int glass = s->add_material(Material::glass({0.97f, 0.99f, 0.98f}, 1.5f));
    int mirror = s->add_material(Material::mirror({0.9f, 0.9f, 0.92f}));
    int gold = s->add_material(Material::mirror({0.95f, 0.75f, 0.35f}));
    int orange = s->add_material(Material::diffuse({0.8f, 0.35f, 0.08f}));
    int blue = s->add_material(Material::diffuse({0.1f, 0.25f, 0.7f}));
    int green = s->add_material(Material::diffuse({0.15f, 0.6f, 0.2f}));
    int lamp = s->add_material(Material::emissive({6.f, 5.5f, 4.5f}));
    s->add_sphere({0.9f, 0.9f, 1.0f}, 0.9f, glass);
    s->add_sphere({-1.5f, 1.0f, -0.6f}, 1.0f, mirror);
    s->add_sphere({2.6f, 0.55f, -1.0f}, 0.55f, orange);
    s->add_sphere({-2.6f, 0.4f, 1.2f}, 0.4f, gold);
    s->add_sphere({-0.3f, 0.3f, 2.3f}, 0.3f, green);
    s->add_box({0.2f, 0.f, -2.6f}, {1.4f, 1.6f, -1.4f}, blue);
    s->add_sphere({3.4f, 2.6f, -3.5f}, 0.25f, lamp);
    Bounds objects;  // everything but the floor
    for (size_t i = 1; i < s->meshes.size(); ++i)
        for (Vec3 p : s->meshes[i].pos) objects.add(p);
    s->framing = framing_of(objects);
    AreaLight key;
    key.corner = {-3.f, 7.f, 1.f};
    key.e1 = {2.f, 0.f, 0.f};  // cross(e1, e2) = -y: shines down
    key.e2 = {0.f, 0.f, 2.f};
    key.radiance = {9.f, 8.6f, 8.f};
    s->add_area_light(key);
    s->add_point_light({{6.f, 4.f, 6.f}, {9.f, 9.5f, 11.f}});
    s->camera.eye = {0.f, 2.3f, 7.8f};
    s->camera.target = {0.f, 0.9f, 0.f};
    s->camera.tan_half = 0.3443276f;  // tan(19 deg)
    s->sky_zenith = {0.18f, 0.32f, 0.7f};
    s->sky_horizon = {0.75f, 0.8f, 0.88f};
    s->sky_ground = {0.35f, 0.33f, 0.3f};
    s->ambient = {0.09f, 0.1f, 0.12f};
    s->ao_radius = 1.5f;
    s->exposure = 1.f;
    return s;
}

// ---- Stanford bunny in the Cornell box ---------------------------------------------------------
const char *kBunnyPath = "/usr/share/glmark2/models/bunny.obj";  // Debian glmark2-data

std::unique_ptr<Scene> bunny(std::string &err) {
    Model m;
    if (!load_model(kBunnyPath, m, err)) {
        err += " (the bunny scene needs the Debian package glmark2-data)";
        return nullptr;
    }
    for (Material &mat : m.materials) mat = Material::diffuse(kCornellWhite);
    auto s = std::make_unique<Scene>();
    cornell_shell(*s);
    // 330 mm tall (the tall block's height), standing on the floor at the box's centre.
    Vec3 c = m.bounds.center();
    Vec3 pivot{c.x, m.bounds.lo.y, c.z};
    float scale = 330.f / m.bounds.size().y;
    add_model(*s, m, pivot, scale, -30.f, {290.f, 0.f, 290.f});
    s->model_placement = Placement{};  // a view of this scene is given in the box's millimetres
    return s;
}

// ---- Any model file -------------------------------------------------------------------------
// The model is moved and scaled so that its bounding box sits on the ground plane y = 0,
// centred on the y axis, with a bounding-sphere radius of 1.
std::unique_ptr<Scene> framed_model(const Model &m, float yaw_deg) {
    auto s = std::make_unique<Scene>();
    Vec3 c = m.bounds.center(), size = m.bounds.size();
    float radius = 0.5f * length(size);
    float scale = 1.f / radius;
    add_model(*s, m, {c.x, m.bounds.lo.y, c.z}, scale, yaw_deg, {0.f, 0.f, 0.f});
    s->framing = s->model_placement;
    const Vec3 target{0.f, 0.5f * size.y * scale, 0.f};

    Material ground = Material::diffuse({0.62f, 0.62f, 0.6f});
    ground.albedo2 = {0.5f, 0.5f, 0.49f};
    ground.checker = 0.5f;
    int g = s->add_material(ground);
    const float gy = -2e-3f, ext = 30.f;  // a hair below the model, so its base does not z-fight
    s->add_quad({-ext, gy, -ext}, {-ext, gy, ext}, {ext, gy, ext}, {ext, gy, -ext}, g);

    s->camera.tan_half = kTan20;
    s->camera.target = target;
    // The unit bounding sphere fills the shorter image side, with 8 % margin.
    const float sin_half = kTan20 / std::sqrt(1.f + kTan20 * kTan20);
    const float dist = 1.08f / sin_half;
    s->camera.eye = target + normalize({0.55f, 0.42f, 1.f}) * dist;
    const Placement &pl = s->model_placement;
    if (m.has_camera) {  // the file's own view, in the model's new place
        s->camera.eye = pl.point(m.camera.eye);
        s->camera.target = pl.point(m.camera.target);
        s->camera.up = pl.rotate(m.camera.up);
        s->camera.tan_half = m.camera.tan_half;
        s->camera.vertical = true;
    }

    if (!m.lights.empty()) {
        // The file's point and spot lights instead of the automatic key and fill. Their units
        // vary from file to file (watts, candela, plain colours), so they are scaled together
        // to give the model centre the automatic rig's unoccluded irradiance (4/3 pi).
        float sum = 0.f;
        std::vector<PointLight> ls;
        for (const PointLight &fl : m.lights) {
            PointLight l = fl;
            l.pos = pl.point(fl.pos);
            l.dir = pl.rotate(fl.dir);
            Vec3 dv = target - l.pos;
            float d2 = maxf(dot(dv, dv), 1e-4f);
            sum += (l.intensity.x + l.intensity.y + l.intensity.z) * (1.f / 3.f) / d2;
            ls.push_back(l);
        }
        const float k = sum > 0.f ? (4.f * kPi / 3.f) / sum : 1.f;
        for (PointLight &l : ls) {
            l.intensity = l.intensity * k;
            s->add_point_light(l);
        }
    } else {
        // Key light: a 0.8 x 0.8 square above front-left, facing the model, giving an irradiance
        // of about pi at the model centre (a white surface facing it shows radiance ~ albedo).
        const float d = 3.5f, side = 0.8f;
        Vec3 lc = target + normalize({-0.6f, 1.2f, 0.8f}) * d;
        Vec3 n = normalize(target - lc);
        Vec3 e1 = normalize(cross(n, {0.f, 1.f, 0.f})) * side;
        Vec3 e2 = normalize(cross(n, e1)) * side;  // cross(e1, cross(n, e1)) = n |e1|^2: shines at the model
        AreaLight key;
        key.corner = lc - (e1 + e2) * 0.5f;
        key.e1 = e1;
        key.e2 = e2;
        key.radiance = Vec3{1.f, 0.96f, 0.9f} * (kPi * d * d / (side * side));
        s->add_area_light(key);
        // Fill: a point light right of the camera with a third of the key's irradiance.
        Vec3 fp = target + normalize({1.f, 0.5f, 0.6f}) * 4.f;
        s->add_point_light({fp, Vec3{0.85f, 0.9f, 1.f} * (kPi * 16.f / 3.f)});
    }

    s->sky_zenith = {0.2f, 0.35f, 0.7f};
    s->sky_horizon = {0.78f, 0.82f, 0.9f};
    s->sky_ground = {0.4f, 0.4f, 0.38f};
    s->ambient = {0.1f, 0.11f, 0.13f};
    s->ao_radius = 0.6f;
    s->exposure = 0.7f;  // key + fill + sky give a white surface about 1.4 x its albedo
    return s;
}

std::unique_ptr<Scene> model_builtin(const char *path, const char *package, float yaw_deg, std::string &err) {
    Model m;
    if (!load_model(path, m, err)) {
        err += std::string(" (this built-in scene needs the Debian package ") + package + ")";
        return nullptr;
    }
    return framed_model(m, yaw_deg);
}

struct Builtin {
    const char *name;
    std::function<std::unique_ptr<Scene>(std::string &)> make;
};

const Builtin kBuiltins[] = {
    {"cornell", cornell},
    {"showcase", showcase},
    {"bunny", bunny},
    {"duck", [](std::string &e) { return model_builtin("/usr/share/assimp/models/Collada/duck.dae", "assimp-testmodels", 0.f, e); }},
    {"teapots", [](std::string &e) { return model_builtin("/usr/share/assimp/models/Collada/teapots.DAE", "assimp-testmodels", 0.f, e); }},
    {"engine", [](std::string &e) {
         return model_builtin("/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "assimp-testmodels", 0.f, e);
     }},
};

}  // namespace

const char *builtin_scene_names() { return "cornell,showcase,bunny,duck,teapots,engine"; }

std::unique_ptr<Scene> model_file_scene(const std::string &path, std::string &err) {
    Model m;
    if (!load_model(path, m, err)) return nullptr;
    return framed_model(m, 0.f);
}

bool parse_view(const std::string &text, float v[7], std::string &err) {
    const std::string form = " (want EX,EY,EZ,TX,TY,TZ,FOV: eye, target, vertical field of view in degrees)";
    int n = 0;
    size_t pos = 0;
    while (true) {
        size_t end = text.find(',', pos);
        std::string tok = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        size_t a = tok.find_first_not_of(" \t"), b = tok.find_last_not_of(" \t");
        tok = a == std::string::npos ? std::string() : tok.substr(a, b - a + 1);
        if (!tok.empty() && tok[0] == '+') tok = tok.substr(1);
        float x = 0.f;
        auto r = std::from_chars(tok.data(), tok.data() + tok.size(), x);
        if (tok.empty() || r.ec != std::errc() || r.ptr != tok.data() + tok.size() || !std::isfinite(x)) {
            err = "camera '" + text + "': '" + tok + "' is not a finite number" + form;
            return false;
        }
        if (n == 7) { err = "camera '" + text + "' has more than 7 values" + form; return false; }
        v[n++] = x;
        if (end == std::string::npos) break;
        pos = end + 1;
    }
    if (n != 7) { err = "camera '" + text + "' has " + std::to_string(n) + " values, not 7" + form; return false; }
    if (!(v[6] > 0.f && v[6] < 180.f)) { err = "camera '" + text + "': field of view must be in (0, 180) degrees"; return false; }
    if (v[0] == v[3] && v[1] == v[4] && v[2] == v[5]) { err = "camera '" + text + "': eye and target are the same point"; return false; }
    return true;
}

bool set_view(Scene &s, const std::string &text, std::string &err) {
    float v[7];
    if (!parse_view(text, v, err)) return false;
    const Placement &pl = s.model_placement;
    s.camera.eye = pl.point({v[0], v[1], v[2]});
    s.camera.target = pl.point({v[3], v[4], v[5]});
    s.camera.up = {0.f, 1.f, 0.f};
    double sn, cs;
    det_sincos_deg(0.5 * double(v[6]), sn, cs);
    s.camera.tan_half = float(sn / cs);
    s.camera.vertical = true;
    return true;
}

std::unique_ptr<Scene> make_scene(const std::string &name, std::string &err) {
    for (const Builtin &b : kBuiltins)
        if (name == b.name) return b.make(err);
    if (name.empty()) {
        err = std::string("empty scene name (built-in scenes: ") + builtin_scene_names() + ", or a model file path)";
        return nullptr;
    }
    auto s = model_file_scene(name, err);
    if (!s && err.find("no such file") != std::string::npos)
        err = "unknown scene '" + name + "': not a built-in scene (" + builtin_scene_names() + ") and no such file";
    return s;
}

}  // namespace msr

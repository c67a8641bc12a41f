// Scene description (triangle meshes, materials, lights, camera, environment) and its Embree 3
// acceleration structure. Everything is built once in commit(); afterwards the scene is
// read-only, so intersect()/occluded() may run on any number of threads at once.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <string>
#include <vector>

#include "texture.h"
#include "vec.h"

namespace msr {

enum class MatType { Diffuse, Mirror, Glass, Emissive };

struct Material {
    MatType type = MatType::Diffuse;
    Vec3 albedo{0.73f, 0.73f, 0.73f};  // diffuse reflectance, or mirror/glass tint
    Vec3 albedo2{0.f, 0.f, 0.f};       // second checker colour (used when checker > 0)
    float checker = 0.f;               // checker cell size in world units on x/z, 0 = plain
    Vec3 emission{0.f, 0.f, 0.f};      // radiance of an emissive surface (front side)
    float ior = 1.5f;                  // glass index of refraction
    int texture = -1;                  // diffuse map (Scene::textures), multiplying the albedo; -1 = none
    Vec3 specular{0.f, 0.f, 0.f};      // Blinn-Phong highlight colour from the lights (diffuse only)
    float shininess = 0.f;             // Blinn-Phong exponent (rounded to an integer, 1..1024)

    static Material diffuse(Vec3 a) { Material m; m.albedo = a; return m; }
    static Material mirror(Vec3 tint) { Material m; m.type = MatType::Mirror; m.albedo = tint; return m; }
    static Material glass(Vec3 tint, float ior) {
        Material m; m.type = MatType::Glass; m.albedo = tint; m.ior = ior; return m;
    }
    static Material emissive(Vec3 e) { Material m; m.type = MatType::Emissive; m.emission = e; return m; }
};

struct Mesh {
    std::vector<Vec3> pos;
    std::vector<Vec3> nrm;     // per-vertex shading normals; empty = flat shading
    std::vector<Vec3> col;     // per-vertex colour multiplying the albedo; empty = white
    std::vector<uint32_t> idx; // 3 vertex indices per triangle
    std::vector<float> uv;     // texture coordinates, 2 per vertex; empty = none
    int material = 0;
    // Set by Scene::commit for meshes with uv and a textured material: level-0 texels per
    // world unit along the surface, per triangle (square root of the texel/world area ratio).
    std::vector<float> texel_density;
};

struct PointLight {
    Vec3 pos;
    Vec3 intensity;  // radiant intensity: irradiance = intensity * cos / d^2
    // A spot light when dir is non-zero: full intensity inside cos_inner, none outside
    // cos_outer, smoothstep between (cosines of the angles to the unit axis dir).
    Vec3 dir{0.f, 0.f, 0.f};
    float cos_inner = -1.f, cos_outer = -1.f;
};

// A one-sided parallelogram emitter: corner + s*e1 + t*e2, s, t in [0, 1], emitting towards
// cross(e1, e2). add_area_light() also adds it as visible emissive geometry.
struct AreaLight {
    Vec3 corner, e1, e2;
    Vec3 radiance;
    Vec3 normal() const { return normalize(cross(e1, e2)); }
};

struct Camera {
    Vec3 eye{0.f, 0.f, 0.f}, target{0.f, 0.f, 1.f}, up{0.f, 1.f, 0.f};
    float tan_half = 0.36397f;  // tan(half the field of view across the shorter image side)
    bool vertical = false;      // tan_half spans the image height instead of the shorter side
};

// Placement of an imported model in the scene: p' = R_yaw (p - pivot) * scale + offset. Kept in
// the scene so that a camera given in model units (msr_render_create_view) lands in the same
// place as the model.
struct Placement {
    Vec3 pivot{0.f, 0.f, 0.f}, offset{0.f, 0.f, 0.f};
    float scale = 1.f;
    float cos_yaw = 1.f, sin_yaw = 0.f;
    Vec3 rotate(Vec3 v) const { return {cos_yaw * v.x + sin_yaw * v.z, v.y, -sin_yaw * v.x + cos_yaw * v.z}; }
    Vec3 point(Vec3 p) const { return rotate(p - pivot) * scale + offset; }
};

struct Bounds {
    Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
    void add(Vec3 p) { lo = vmin(lo, p); hi = vmax(hi, p); }
    bool empty() const { return lo.x > hi.x; }
    Vec3 center() const { return (lo + hi) * 0.5f; }
    Vec3 size() const { return hi - lo; }
};

struct Hit {
    bool hit = false;
    float t = 0.f;
    Vec3 p;        // hit point
    Vec3 ng;       // unit geometric normal (as wound, not flipped towards the ray)
    Vec3 ns;       // unit shading normal (interpolated, same hemisphere as ng)
    Vec3 color{1.f, 1.f, 1.f};  // interpolated vertex colour
    bool has_uv = false;
    float tu = 0.f, tv = 0.f;   // interpolated texture coordinates
    float texel_density = 0.f;  // level-0 texels per world unit (Mesh::texel_density)
    int material = -1;
    unsigned geom = RTC_INVALID_GEOMETRY_ID, prim = RTC_INVALID_GEOMETRY_ID;
};

// Ray masks: glass is left out of shadow rays (shading treats it as a tinted occluder).
constexpr unsigned MASK_OPAQUE = 1u, MASK_GLASS = 2u, MASK_ALL = 3u;

class Scene {
public:
    Scene() = default;
    ~Scene();
    Scene(const Scene &) = delete;
    Scene &operator=(const Scene &) = delete;

    int add_material(const Material &m);
    void add_mesh(Mesh m);
    // Quad p0 p1 p2 p3 (counter-clockwise seen from the front side) as two triangles.
    void add_quad(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, int material);
    // Axis-aligned box with outward normals.
    void add_box(Vec3 lo, Vec3 hi, int material);
    // Icosphere (an icosahedron subdivided `levels` times, 20 * 4^levels triangles) with
    // smooth normals.
    void add_sphere(Vec3 c, float r, int material, int levels = 4);
    void add_area_light(const AreaLight &l);
    void add_point_light(const PointLight &l) { point_lights.push_back(l); }

    // Builds the Embree scene. Returns false with a one-line message on failure.
    bool commit(RTCDevice device, std::string &err);

    Hit intersect(Vec3 org, Vec3 dir, float tnear, float tfar, unsigned mask = MASK_ALL) const;
    bool occluded(Vec3 org, Vec3 dir, float tnear, float tfar, unsigned mask) const;

    size_t triangle_count() const;
    // Index of triangle `prim` of mesh `geom` among all the scene's triangles (after commit).
    uint32_t triangle_index(unsigned geom, unsigned prim) const { return tri_base_[geom] + prim; }
    Bounds bounds() const { return bounds_; }
    bool has_glass() const { return has_glass_; }

    std::vector<Material> materials;
    std::vector<Mesh> meshes;
    std::vector<PointLight> point_lights;
    std::vector<AreaLight> area_lights;
    std::vector<std::shared_ptr<const Texture>> textures;  // Material::texture indexes these
    Camera camera;
    Placement model_placement;  // model units -> world (identity for scenes built in world units)
    // Model units -> framed units (the subject on the ground plane y = 0, inside a bounding sphere
    // of radius 1, its bounding-box centre above the origin): a "framed" camera path's space.
    Placement framing;
    Vec3 sky_zenith{0.f, 0.f, 0.f}, sky_horizon{0.f, 0.f, 0.f}, sky_ground{0.f, 0.f, 0.f};
    Vec3 ambient{0.f, 0.f, 0.f};  // constant ambient radiance (times albedo; times AO in heavy mode)
    float ao_radius = 1.f;        // ambient-occlusion ray length (heavy mode)
    float exposure = 1.f;         // linear scale before tone mapping
    float eps = 1e-4f;            // self-intersection offset, set from the scene size in commit()

private:
    RTCScene rtc_ = nullptr;
    std::vector<uint32_t> tri_base_;  // first triangle index of each mesh
    Bounds bounds_;
    bool has_glass_ = false;
};

}  // namespace msr

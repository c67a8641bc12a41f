#include "scene.h"

#include <cmath>
#include <limits>
#include <map>

namespace msr {

Scene::~Scene() {
    if (rtc_) rtcReleaseScene(rtc_);
}

int Scene::add_material(const Material &m) {
    materials.push_back(m);
    return int(materials.size()) - 1;
}

void Scene::add_mesh(Mesh m) { meshes.push_back(std::move(m)); }

void Scene::add_quad(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, int material) {
    Mesh m;
    m.pos = {p0, p1, p2, p3};
    m.idx = {0, 1, 2, 0, 2, 3};
    m.material = material;
    add_mesh(std::move(m));
}

void Scene::add_box(Vec3 lo, Vec3 hi, int material) {
    Mesh m;
    m.material = material;
    // 8 corners, bit 0 = x, bit 1 = y, bit 2 = z.
    for (int i = 0; i < 8; ++i)
        m.pos.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    // Faces counter-clockwise seen from outside.
    const uint32_t f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                              {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto &q : f) m.idx.insert(m.idx.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    add_mesh(std::move(m));
}

void Scene::add_sphere(Vec3 c, float r, int material, int levels) {
    // Icosahedron (vertices from the golden ratio), each subdivision splitting every triangle
    // in four with the new vertices pushed onto the sphere: sqrt and division only.
    const float t = 1.6180339887498949f;
    std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3 &p : v) p = normalize(p);
    std::vector<uint32_t> f = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,
                               11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8,
                               3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back(normalize(v[a] + v[b]));
            return mid[key] = uint32_t(v.size() - 1);
        };
        std::vector<uint32_t> g;
        for (size_t i = 0; i < f.size(); i += 3) {
            uint32_t a = f[i], b = f[i + 1], cc = f[i + 2];
            uint32_t ab = midpoint(a, b), bc = midpoint(b, cc), ca = midpoint(cc, a);
            g.insert(g.end(), {a, ab, ca, b, bc, ab, cc, ca, bc, ab, bc, ca});
        }
        f.swap(g);
    }
    Mesh m;
    m.material = material;
    for (Vec3 d : v) { m.pos.push_back(c + d * r); m.nrm.push_back(d); }
    m.idx = std::move(f);
    add_mesh(std::move(m));
}

void Scene::add_area_light(const AreaLight &l) {
    area_lights.push_back(l);
    int mat = add_material(Material::emissive(l.radiance));
    add_quad(l.corner, l.corner + l.e1, l.corner + l.e1 + l.e2, l.corner + l.e2, mat);
}

size_t Scene::triangle_count() const {
    size_t n = 0;
    for (auto &m : meshes) n += m.idx.size() / 3;
    return n;
}

bool Scene::commit(RTCDevice device, std::string &err) {
    if (rtc_) { err = "scene committed twice"; return false; }
    rtc_ = rtcNewScene(device);
    if (!rtc_) { err = "embree: cannot create a scene"; return false; }
    // Robust traversal: watertight edges, so hit/miss on shared edges does not depend on luck.
    rtcSetSceneFlags(rtc_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(rtc_, RTC_BUILD_QUALITY_HIGH);
    bounds_ = Bounds{};
    has_glass_ = false;
    tri_base_.clear();
    uint32_t tri_total = 0;
    for (const Mesh &m : meshes) {
        tri_base_.push_back(tri_total);
        tri_total += uint32_t(m.idx.size() / 3);
    }
    for (size_t gi = 0; gi < meshes.size(); ++gi) {
        const Mesh &m = meshes[gi];
        if (m.material < 0 || size_t(m.material) >= materials.size()) {
            err = "mesh " + std::to_string(gi) + " has no valid material";
            return false;
        }
        if (m.idx.size() % 3 != 0 || (!m.nrm.empty() && m.nrm.size() != m.pos.size()) ||
            (!m.col.empty() && m.col.size() != m.pos.size()) || (!m.uv.empty() && m.uv.size() != 2 * m.pos.size())) {
            err = "mesh " + std::to_string(gi) + " has inconsistent buffers";
            return false;
        }
        for (uint32_t i : m.idx)
            if (i >= m.pos.size()) { err = "mesh " + std::to_string(gi) + " indexes a missing vertex"; return false; }
        for (Vec3 p : m.pos) bounds_.add(p);
        const int tex = materials[m.material].texture;
        if (tex >= 0 && size_t(tex) >= textures.size()) {
            err = "mesh " + std::to_string(gi) + " uses a missing texture";
            return false;
        }
        meshes[gi].texel_density.clear();
        if (tex >= 0 && !m.uv.empty()) {
            // Texel density per triangle: sqrt(texel area / world area), texels of level 0.
            const Texture &t = *textures[size_t(tex)];
            const float texels = float(t.width()) * float(t.height());
            std::vector<float> dens(m.idx.size() / 3, 0.f);
            for (size_t f = 0; f < dens.size(); ++f) {
                const uint32_t a = m.idx[3 * f], b = m.idx[3 * f + 1], c = m.idx[3 * f + 2];
                float world = length(cross(m.pos[b] - m.pos[a], m.pos[c] - m.pos[a]));
                float du1 = m.uv[2 * b] - m.uv[2 * a], dv1 = m.uv[2 * b + 1] - m.uv[2 * a + 1];
                float du2 = m.uv[2 * c] - m.uv[2 * a], dv2 = m.uv[2 * c + 1] - m.uv[2 * a + 1];
                float tex_area = std::fabs(du1 * dv2 - du2 * dv1) * texels;
                float d = world > 0.f ? std::sqrt(tex_area / world) : 0.f;
                dens[f] = std::isfinite(d) ? d : 0.f;
            }
            meshes[gi].texel_density = std::move(dens);
        }

        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto *vb = static_cast<float *>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                3 * sizeof(float), m.pos.size()));
        auto *ib = static_cast<uint32_t *>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(uint32_t), m.idx.size() / 3));
        if (!vb || !ib) { rtcReleaseGeometry(g); err = "embree: out of memory for a mesh"; return false; }
        for (size_t i = 0; i < m.pos.size(); ++i) { vb[3 * i] = m.pos[i].x; vb[3 * i + 1] = m.pos[i].y; vb[3 * i + 2] = m.pos[i].z; }
        for (size_t i = 0; i < m.idx.size(); ++i) ib[i] = m.idx[i];
        bool glass = materials[m.material].type == MatType::Glass;
        has_glass_ = has_glass_ || glass;
        rtcSetGeometryMask(g, glass ? MASK_GLASS : MASK_OPAQUE);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(rtc_, g, unsigned(gi));
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(rtc_);
    RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) { err = "embree: scene build failed (error " + std::to_string(int(e)) + ")"; return false; }
    if (bounds_.empty()) { err = "scene holds no triangles"; return false; }
    // Offset for secondary-ray origins: a few float ulps of the scene's largest coordinate.
    float extent = std::fmax(max_component(vmax(bounds_.hi, -bounds_.lo)), max_component(bounds_.size()));
    eps = std::fmax(extent * 2e-5f, 1e-6f);
    return true;
}

static void make_ray(RTCRay &r, Vec3 org, Vec3 dir, float tnear, float tfar, unsigned mask) {
    r.org_x = org.x; r.org_y = org.y; r.org_z = org.z;
    r.dir_x = dir.x; r.dir_y = dir.y; r.dir_z = dir.z;
    r.tnear = tnear; r.tfar = tfar;
    r.time = 0.f; r.mask = mask; r.id = 0; r.flags = 0;
}

Hit Scene::intersect(Vec3 org, Vec3 dir, float tnear, float tfar, unsigned mask) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    make_ray(rh.ray, org, dir, tnear, tfar, mask);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtc_, &ctx, &rh);
    Hit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    const Mesh &m = meshes[rh.hit.geomID];
    const uint32_t *tri = &m.idx[3 * rh.hit.primID];
    Vec3 v0 = m.pos[tri[0]], v1 = m.pos[tri[1]], v2 = m.pos[tri[2]];
    float u = rh.hit.u, v = rh.hit.v, w = 1.f - u - v;
    h.hit = true;
    h.t = rh.ray.tfar;
    h.p = org + dir * h.t;
    h.ng = normalize(cross(v1 - v0, v2 - v0));
    h.ns = h.ng;
    if (!m.nrm.empty()) {
        Vec3 n = normalize(m.nrm[tri[0]] * w + m.nrm[tri[1]] * u + m.nrm[tri[2]] * v);
        if (std::isfinite(n.x) && dot(n, n) > 0.5f) h.ns = dot(n, h.ng) < 0.f ? -n : n;
    }
    if (!m.col.empty()) h.color = m.col[tri[0]] * w + m.col[tri[1]] * u + m.col[tri[2]] * v;
    if (!m.uv.empty()) {
        h.has_uv = true;
        h.tu = m.uv[2 * tri[0]] * w + m.uv[2 * tri[1]] * u + m.uv[2 * tri[2]] * v;
        h.tv = m.uv[2 * tri[0] + 1] * w + m.uv[2 * tri[1] + 1] * u + m.uv[2 * tri[2] + 1] * v;
        if (!m.texel_density.empty()) h.texel_density = m.texel_density[rh.hit.primID];
    }
    h.material = m.material;
    h.geom = rh.hit.geomID;
    h.prim = rh.hit.primID;
    return h;
}

bool Scene::occluded(Vec3 org, Vec3 dir, float tnear, float tfar, unsigned mask) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    make_ray(r, org, dir, tnear, tfar, mask);
    rtcOccluded1(rtc_, &ctx, &r);
    return r.tfar < 0.f;  // Embree sets tfar to -inf on a hit
}

}  // namespace msr

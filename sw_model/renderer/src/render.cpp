#include "render.h"

#include "detmath.h"
#include "srgb_table.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace msr {

namespace {

constexpr float kPi = float(kPiD);
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kMinWeight = 1.f / 512.f;  // prune secondary rays that cannot change 8-bit output
constexpr float kGlassShadow = 0.55f;      // light passing a glass occluder (stands in for caustics)

// Purposes of the per-sample random numbers (mixed into the hash with the depth).
enum : uint32_t { R_AA_X = 1, R_AA_Y, R_LIGHT_U, R_LIGHT_V, R_AO_U, R_AO_V };

Vec3 reflect(Vec3 d, Vec3 n) { return d - n * (2.f * dot(d, n)); }

float aces(float x) {
    // Narkowicz's fit of the ACES filmic curve.
    float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    return minf(1.f, maxf(0.f, y));
}

}  // namespace

// Irradiance factor of a uniform parallelogram emitter at point p with normal n, i.e.
// E = L * factor (Lambert's polygon formula, the polygon clipped to the hemisphere above p).
float polygon_irradiance(Vec3 p, Vec3 n, const AreaLight &l) {
    Vec3 in[4] = {l.corner, l.corner + l.e1, l.corner + l.e1 + l.e2, l.corner + l.e2};
    if (dot(p - l.corner, cross(l.e1, l.e2)) <= 0.f) return 0.f;  // behind the emitting side
    Vec3 out[5];
    int k = 0;
    for (int i = 0; i < 4; ++i) {
        Vec3 a = in[i], b = in[(i + 1) % 4];
        float da = dot(n, a - p), db = dot(n, b - p);
        if (da >= 0.f) out[k++] = a;
        if ((da >= 0.f) != (db >= 0.f)) {
            float t = da / (da - db);
            out[k++] = a + (b - a) * t;
        }
    }
    if (k < 3) return 0.f;
    Vec3 u[5];
    for (int i = 0; i < k; ++i) u[i] = normalize(out[i] - p);
    float sum = 0.f;
    for (int i = 0; i < k; ++i) {
        Vec3 a = u[i], b = u[(i + 1) % k];
        Vec3 g = cross(a, b);
        float s = length(g);
        if (s <= 0.f) continue;
        float theta = float(det_atan2(s, dot(a, b)));
        sum += theta * dot(n, g) / s;
    }
    return 0.5f * std::fabs(sum);
}

float ipow(float x, int n) {
    float r = 1.f;
    while (n > 0) {
        if (n & 1) r *= x;
        x *= x;
        n >>= 1;
    }
    return r;
}

float spot_falloff(const PointLight &l, float c) {
    if (l.cos_inner <= l.cos_outer) return c >= l.cos_outer ? 1.f : 0.f;
    float t = (c - l.cos_outer) / (l.cos_inner - l.cos_outer);
    t = minf(1.f, maxf(0.f, t));
    return t * t * (3.f - 2.f * t);
}

namespace {

// Search of the exact thresholds, used to build the bucket table below.
uint8_t srgb8_search(float v) {
    int lo = 0, hi = 255;  // answer in [lo, hi]
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (v >= kSrgbThreshold[mid - 1]) lo = mid; else hi = mid - 1;
    }
    return uint8_t(lo);
}

// Code at the start of each of 4096 equal buckets of [0, 1]; the sRGB curve rises by less
// than one code per bucket, so one or two threshold compares finish the job without the
// unpredictable branches of a full binary search.
constexpr int kBuckets = 4096;
struct SrgbBuckets {
    uint8_t start[kBuckets + 1];
    SrgbBuckets() {
        for (int i = 0; i <= kBuckets; ++i) start[i] = srgb8_search(float(i) / float(kBuckets));
    }
};
const SrgbBuckets kSrgbBuckets;

}  // namespace

uint8_t srgb8(float v) {
    if (!(v > 0.f)) return 0;  // also NaN
    if (v >= 1.f) return 255;
    int code = kSrgbBuckets.start[int(v * float(kBuckets))];  // v * 4096 is exact: v >= bucket start
    while (code < 255 && v >= kSrgbThreshold[code]) ++code;
    return uint8_t(code);
}

struct Renderer::Sample {
    uint32_t pix;  // hash of (x, y, seed)
    int index;     // sample number within the pixel
    mutable uint64_t rays = 0;  // rays cast so far (for the benchmark)
    float rnd(uint32_t purpose, int depth) const {
        return u01(hash_combine(hash_combine(pix, uint32_t(index)), purpose | (uint32_t(depth) << 8)));
    }
};

Renderer::Renderer(std::unique_ptr<Scene> scene, int width, int height, Quality q, int grid, uint32_t seed)
    : scene_(std::move(scene)), width_(width), height_(height), quality_(q),
      grid_(grid > 0 ? std::min(grid, kMaxGrid) : (q == Quality::Heavy ? kHeavyGrid : 1)),
      spp_(grid_ * grid_), seed_(seed) {
    const Camera &c = scene_->camera;
    eye_ = c.eye;
    fwd_ = normalize(c.target - c.eye);
    right_ = normalize(cross(fwd_, c.up));
    up_ = cross(right_, fwd_);
    if (!(dot(right_, right_) > 0.5f)) {  // looking along up: take the world axis least aligned
        Vec3 a = std::fabs(fwd_.z) < 0.9f ? Vec3{0.f, 0.f, 1.f} : Vec3{1.f, 0.f, 0.f};
        right_ = normalize(cross(fwd_, a));
        up_ = cross(right_, fwd_);
    }
    scale_ = c.tan_half / (0.5f * float(c.vertical ? height : std::min(width, height)));
}

void Renderer::primary_ray(float fx, float fy, Vec3 &org, Vec3 &dir) const {
    float px = (fx - 0.5f * float(width_)) * scale_;
    float py = (0.5f * float(height_) - fy) * scale_;
    org = eye_;
    dir = normalize(fwd_ + right_ * px + up_ * py);
}

Vec3 Renderer::sky(Vec3 d) const {
    const Scene &sc = *scene_;
    if (d.y >= 0.f) return sc.sky_horizon + (sc.sky_zenith - sc.sky_horizon) * std::sqrt(d.y);
    float t = minf(1.f, -d.y * 8.f);
    return sc.sky_horizon + (sc.sky_ground - sc.sky_horizon) * t;
}

// Transmission towards a light: 0 behind an opaque occluder, a tint behind glass, else 1.
float Renderer::shadow(Vec3 org, Vec3 dir, float dist, Vec3 &tint, const Sample &s) const {
    const Scene &sc = *scene_;
    float tfar = dist * (1.f - 1e-4f) - sc.eps;
    tint = {1.f, 1.f, 1.f};
    if (tfar <= 0.f) return 1.f;
    ++s.rays;
    if (sc.occluded(org, dir, 0.f, tfar, MASK_OPAQUE)) return 0.f;
    if (sc.has_glass()) {
        ++s.rays;
        Hit g = sc.intersect(org, dir, 0.f, tfar, MASK_GLASS);
        if (g.hit) { tint = sc.materials[g.material].albedo; return kGlassShadow; }
    }
    return 1.f;
}

Vec3 Renderer::shade_diffuse(const Hit &h, Vec3 view, Vec3 nf, Vec3 ngf, Vec3 albedo, const Material &m,
                             const Sample &s) const {
    const Scene &sc = *scene_;
    const Vec3 o = h.p + ngf * sc.eps;
    Vec3 irr{0.f, 0.f, 0.f};
    Vec3 tint;
    // Blinn-Phong highlight (energy-normalised lobe), from point lights and the area lights'
    // centres, weighted by the irradiance each one gives.
    const bool glossy = max_component(m.specular) > 0.f && m.shininess >= 1.f;
    const int shin = glossy ? int(minf(1024.f, m.shininess) + 0.5f) : 0;
    const float spec_norm = (float(shin) + 8.f) / (8.f * kPi);
    Vec3 spec{0.f, 0.f, 0.f};
    auto highlight = [&](Vec3 l, Vec3 e) {
        Vec3 hv = normalize(l - view);
        float c = dot(nf, hv);
        if (c > 0.f) spec += e * (spec_norm * ipow(c, shin));
    };
    for (const PointLight &l : sc.point_lights) {
        Vec3 d = l.pos - h.p;
        float d2 = dot(d, d), dist = std::sqrt(d2);
        Vec3 dir = d / dist;
        float c = dot(nf, dir);
        if (c <= 0.f || dot(ngf, dir) <= 0.f) continue;
        float spot = 1.f;
        if (l.dir.x != 0.f || l.dir.y != 0.f || l.dir.z != 0.f) {
            spot = spot_falloff(l, -dot(dir, l.dir));
            if (spot <= 0.f) continue;
        }
        float v = shadow(o, dir, dist, tint, s);
        if (v > 0.f) {
            Vec3 e = l.intensity * tint * (spot * v * c / d2);
            irr += e;
            if (glossy) highlight(dir, e);
        }
    }
    for (const AreaLight &l : sc.area_lights) {
        float f = polygon_irradiance(h.p, nf, l);
        if (f <= 0.f) continue;
        // Visibility: fraction of shadow rays that reach the emitter, times the exact
        // unoccluded irradiance, so lit areas are noise-free and only penumbrae are sampled.
        Vec3 vis{0.f, 0.f, 0.f};
        int n = 0;
        float tmin = 1.f, tmax = 0.f;  // range of the probes' transmissions
        auto probe = [&](float u, float v) {
            Vec3 q = l.corner + l.e1 * u + l.e2 * v;
            Vec3 d = q - o;
            float dist = length(d);
            // A point below the shading horizon lies outside the clipped polygon that f
            // already integrates: it says nothing about visibility, so it is not counted.
            if (!(dist > 0.f) || dot(nf, d) <= 0.f) return;
            ++n;
            float t = 0.f;
            if (dot(ngf, d) > 0.f) {  // else the surface itself is in the way
                Vec3 dir = d / dist;
                t = shadow(o, dir, dist, tint, s);
                if (t > 0.f) vis += tint * t;
            }
            tmin = minf(tmin, t);
            tmax = maxf(tmax, t);
        };
        if (quality_ == Quality::Fast) {
            // Fixed points, no noise: the 4 corners (if one convex occluder hides them all, it
            // hides the whole light) and the centre (catches a thin occluder, such as an ear,
            // between the corners); where they disagree (a penumbra) a 4x4 grid.
            for (int i = 0; i < 4; ++i) probe(float(i & 1), float(i >> 1));
            probe(0.5f, 0.5f);
            if (tmin != tmax) {
                vis = {0.f, 0.f, 0.f};
                n = 0;
                for (int i = 0; i < 16; ++i) probe((float(i & 3) + 0.5f) * 0.25f, (float(i >> 2) + 0.5f) * 0.25f);
            }
        } else {
            // One stratified point per sample; the strata are shuffled per pixel so that
            // the antialiasing strata and the light strata are not correlated.
            // (grid 4: (index + (h & 15) * 5) % 16, the heavy mode's own shuffle)
            const int g = grid_;
            const uint32_t n = uint32_t(g * g);
            uint32_t st = (uint32_t(s.index) + (hash32(s.pix) % n) * 5u) % n;
            probe((float(st % g) + s.rnd(R_LIGHT_U, 0)) / float(g), (float(st / g) + s.rnd(R_LIGHT_V, 0)) / float(g));
        }
        if (n == 0) vis = {1.f, 1.f, 1.f}, n = 1;  // a sliver above the horizon missed by every probe
        Vec3 e = l.radiance * vis * (f / float(n));
        irr += e;
        if (glossy) highlight(normalize(l.corner + (l.e1 + l.e2) * 0.5f - h.p), e);
    }
    Vec3 amb = sc.ambient;
    if (quality_ == Quality::Heavy && sc.ao_radius > 0.f) {
        // Ambient occlusion: one cosine-weighted ray per sample.
        float r1 = s.rnd(R_AO_U, 0), r2 = s.rnd(R_AO_V, 0);
        double sn, cs;
        det_sincos(2.0 * kPiD * double(r1), sn, cs);
        float sr = std::sqrt(r2);
        Vec3 t, b;
        onb(nf, t, b);
        Vec3 dir = normalize(t * (float(cs) * sr) + b * (float(sn) * sr) + nf * std::sqrt(1.f - r2));
        if (dot(dir, ngf) <= 0.f) {
            amb = {0.f, 0.f, 0.f};
        } else {
            ++s.rays;
            if (sc.occluded(o, dir, 0.f, sc.ao_radius, MASK_ALL)) amb = {0.f, 0.f, 0.f};
        }
    }
    Vec3 c = albedo * (irr * (1.f / kPi) + amb);
    if (glossy) c += m.specular * spec;
    return c;
}

Vec3 Renderer::trace(Vec3 org, Vec3 dir, int depth, float weight, float path, const Sample &s) const {
    const Scene &sc = *scene_;
    ++s.rays;
    Hit h = sc.intersect(org, dir, 0.f, kInf, MASK_ALL);
    if (!h.hit) return sky(dir);
    const Material &m = sc.materials[h.material];
    const bool front = dot(dir, h.ng) < 0.f;
    const Vec3 ngf = front ? h.ng : -h.ng;
    const Vec3 nf = front ? h.ns : -h.ns;
    switch (m.type) {
    case MatType::Emissive:
        return front ? m.emission : Vec3{0.f, 0.f, 0.f};
    case MatType::Diffuse: {
        Vec3 a = m.albedo;
        if (m.checker > 0.f) {
            long cx = long(std::floor(h.p.x / m.checker)), cz = long(std::floor(h.p.z / m.checker));
            if ((cx + cz) & 1) a = m.albedo2;
        }
        if (m.texture >= 0 && h.has_uv) {
            // Footprint: a pixel's width at the ray's path length, widened by the surface's
            // slant (the square root of 1 / cos: the footprint's area grows with 1 / cos).
            float cosv = maxf(1e-3f, std::fabs(dot(dir, ngf)));
            float texels = (path + h.t) * scale_ * h.texel_density / std::sqrt(cosv);
            a = a * sc.textures[size_t(m.texture)]->sample(h.tu, h.tv, texels);
        }
        return shade_diffuse(h, dir, nf, ngf, a * h.color, m, s);
    }
    case MatType::Mirror: {
        float w = weight * max_component(m.albedo);
        if (depth >= kMaxDepth || w < kMinWeight) return sc.ambient * m.albedo;
        Vec3 r = reflect(dir, nf);
        if (dot(r, ngf) <= 0.f) r = reflect(dir, ngf);
        return m.albedo * h.color * trace(h.p + ngf * sc.eps, r, depth + 1, w, path + h.t, s);
    }
    case MatType::Glass: {
        if (depth >= kMaxDepth) return sc.ambient * m.albedo;
        const float eta = front ? 1.f / m.ior : m.ior;  // n_incident / n_transmitted
        const float cosi = minf(1.f, maxf(0.f, -dot(dir, nf)));
        const float sin2t = eta * eta * (1.f - cosi * cosi);
        Vec3 r = reflect(dir, nf);
        if (dot(r, ngf) <= 0.f) r = reflect(dir, ngf);
        if (sin2t >= 1.f)  // total internal reflection
            return trace(h.p + ngf * sc.eps, r, depth + 1, weight, path + h.t, s);
        const float cost = std::sqrt(1.f - sin2t);
        const float rs = (eta * cosi - cost) / (eta * cosi + cost);
        const float rp = (cosi - eta * cost) / (cosi + eta * cost);
        const float F = 0.5f * (rs * rs + rp * rp);  // exact dielectric Fresnel, unpolarised
        Vec3 c{0.f, 0.f, 0.f};
        if (weight * F >= kMinWeight) c += trace(h.p + ngf * sc.eps, r, depth + 1, weight * F, path + h.t, s) * F;
        const float wt = weight * (1.f - F) * max_component(m.albedo);
        if (wt >= kMinWeight) {
            Vec3 t = normalize(dir * eta + nf * (eta * cosi - cost));
            c += m.albedo * trace(h.p - ngf * sc.eps, t, depth + 1, wt, path + h.t, s) * (1.f - F);
        }
        return c;
    }
    }
    return {0.f, 0.f, 0.f};
}

Vec3 Renderer::radiance(int x, int y, uint64_t *rays) const {
    Sample s;
    s.pix = hash_combine(hash_combine(seed_, uint32_t(x)), uint32_t(y));
    Vec3 sum{0.f, 0.f, 0.f};
    for (int i = 0; i < spp_; ++i) {
        s.index = i;
        float fx = float(x) + 0.5f, fy = float(y) + 0.5f;
        if (quality_ == Quality::Heavy || grid_ > 1) {  // stratified, jittered antialiasing
            fx = float(x) + (float(i % grid_) + s.rnd(R_AA_X, 0)) / float(grid_);
            fy = float(y) + (float(i / grid_) + s.rnd(R_AA_Y, 0)) / float(grid_);
        }
        Vec3 org, dir;
        primary_ray(fx, fy, org, dir);
        sum += trace(org, dir, 0, 1.f, 0.f, s);
    }
    if (rays) *rays += s.rays;
    return sum * (1.f / float(spp_));
}

void Renderer::encode(Vec3 c, float exposure, uint8_t rgb[3]) {
    for (int i = 0; i < 3; ++i) {
        float v = c[i] * exposure;
        rgb[i] = std::isfinite(v) ? srgb8(aces(maxf(0.f, v))) : 0;  // NaN -> black
    }
}

void Renderer::gbuffer(int x, int y, uint32_t &prim, uint32_t &material, float &depth) const {
    prim = 0;
    material = 0;
    depth = kInf;
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
    Vec3 org, dir;
    primary_ray(float(x) + 0.5f, float(y) + 0.5f, org, dir);
    Hit h = scene_->intersect(org, dir, 0.f, kInf, MASK_ALL);
    if (!h.hit) return;
    prim = scene_->triangle_index(h.geom, h.prim) + 1u;
    material = uint32_t(h.material) + 1u;
    depth = h.t * dot(dir, fwd_);
}

void Renderer::pixel(int x, int y, uint8_t rgb[3], uint64_t *rays) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    encode(radiance(x, y, rays), scene_->exposure, rgb);
}

}  // namespace msr

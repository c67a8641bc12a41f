#include "texture.h"

#include <cmath>

#include "srgb_table.h"

namespace msr {

float srgb_to_linear(uint8_t code) { return kSrgbDecode[code]; }

int wrap_index(int i, int n, Wrap mode) {
    switch (mode) {
    case Wrap::Clamp:
        return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case Wrap::Mirror: {
        int p = 2 * n;
        int m = ((i % p) + p) % p;
        return m < n ? m : p - 1 - m;
    }
    case Wrap::Repeat:
    default:
        return ((i % n) + n) % n;
    }
}

void mip_level(float texels, int &level, float &frac) {
    level = 0;
    frac = 0.f;
    if (!(texels > 1.f)) return;  // also NaN
    if (!(texels < 1e30f)) { level = 126; return; }
    int e = 0;
    float m = std::frexp(texels, &e);  // texels = m * 2^e, m in [0.5, 1): exact
    level = e - 1;
    frac = 2.f * m - 1.f;              // exact
}

Texture::Texture(int width, int height, int channels, const uint8_t *texels, Wrap wrap_u, Wrap wrap_v)
    : wrap_u_(wrap_u), wrap_v_(wrap_v) {
    Level l0{width, height, std::vector<float>(size_t(width) * size_t(height) * 3)};
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
        for (int c = 0; c < 3; ++c) l0.rgb[3 * i + c] = srgb_to_linear(texels[size_t(channels) * i + size_t(c < channels ? c : 0)]);
    levels_.push_back(std::move(l0));
    // Mip chain down to 1x1: each texel the mean of its (up to) 2x2 parents.
    while (levels_.back().w > 1 || levels_.back().h > 1) {
        const Level &s = levels_.back();
        Level d{s.w > 1 ? s.w / 2 : 1, s.h > 1 ? s.h / 2 : 1, {}};
        d.rgb.resize(size_t(d.w) * size_t(d.h) * 3);
        for (int y = 0; y < d.h; ++y)
            for (int x = 0; x < d.w; ++x) {
                int x0 = s.w > 1 ? 2 * x : 0, x1 = s.w > 1 ? 2 * x + 1 : 0;
                int y0 = s.h > 1 ? 2 * y : 0, y1 = s.h > 1 ? 2 * y + 1 : 0;
                for (int c = 0; c < 3; ++c) {
                    float a = s.rgb[(size_t(y0) * s.w + x0) * 3 + c], b = s.rgb[(size_t(y0) * s.w + x1) * 3 + c];
                    float e = s.rgb[(size_t(y1) * s.w + x0) * 3 + c], f = s.rgb[(size_t(y1) * s.w + x1) * 3 + c];
                    d.rgb[(size_t(y) * d.w + x) * 3 + c] = ((a + b) + (e + f)) * 0.25f;
                }
            }
        levels_.push_back(std::move(d));
    }
}

Vec3 Texture::texel(int level, int x, int y) const {
    const Level &l = levels_[size_t(level)];
    const float *p = &l.rgb[(size_t(y) * size_t(l.w) + size_t(x)) * 3];
    return {p[0], p[1], p[2]};
}

namespace {
// Texture coordinate brought into a small range with the same wrapped result (so that the
// float -> int conversion cannot overflow); exact for |c| < 2^23.
float reduce(float c, Wrap mode) {
    if (!std::isfinite(c)) return 0.f;
    switch (mode) {
    case Wrap::Clamp: return c < -1.f ? -1.f : (c > 2.f ? 2.f : c);
    case Wrap::Mirror: return c - 2.f * std::floor(c * 0.5f);
    case Wrap::Repeat:
    default: return c - std::floor(c);
    }
}
}  // namespace

Vec3 Texture::bilinear(int level, float u, float v) const {
    const Level &l = levels_[size_t(level)];
    u = reduce(u, wrap_u_);
    v = reduce(v, wrap_v_);
    // Texel centres at (i + 0.5) / n; picture rows run top to bottom, v bottom to top.
    float x = u * float(l.w) - 0.5f;
    float y = (1.f - v) * float(l.h) - 0.5f;
    float fx0 = std::floor(x), fy0 = std::floor(y);
    float fx = x - fx0, fy = y - fy0;
    int x0 = int(fx0), y0 = int(fy0);
    int xa = wrap_index(x0, l.w, wrap_u_), xb = wrap_index(x0 + 1, l.w, wrap_u_);
    int ya = wrap_index(y0, l.h, wrap_v_), yb = wrap_index(y0 + 1, l.h, wrap_v_);
    Vec3 top = texel(level, xa, ya) * (1.f - fx) + texel(level, xb, ya) * fx;
    Vec3 bot = texel(level, xa, yb) * (1.f - fx) + texel(level, xb, yb) * fx;
    return top * (1.f - fy) + bot * fy;
}

Vec3 Texture::sample(float u, float v, float texels) const {
    int level;
    float frac;
    mip_level(texels, level, frac);
    const int last = levels() - 1;
    if (level >= last) return bilinear(last, u, v);
    Vec3 a = bilinear(level, u, v);
    if (frac == 0.f) return a;
    Vec3 b = bilinear(level + 1, u, v);
    return a * (1.f - frac) + b * frac;
}

}  // namespace msr

// Diffuse textures: decoded once (stb_image), converted from sRGB to linear on read, mip-mapped
// by 2x2 box filtering, sampled bilinearly between the two mip levels around the footprint
// (trilinear). Plain float arithmetic and table look-ups only: the same texel values and the
// same samples on every machine.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vec.h"

namespace msr {

enum class Wrap { Repeat, Clamp, Mirror };

// Linear value of an 8-bit sRGB code (exact table, no pow).
float srgb_to_linear(uint8_t code);

// Texel index i wrapped into [0, n) by the mode.
int wrap_index(int i, int n, Wrap mode);

// Mip level (integer part and fraction in [0, 1)) for a footprint of `texels` level-0 texels
// per pixel: log2 with its mantissa linearised (exact at powers of two), 0 below one texel.
void mip_level(float texels, int &level, float &frac);

class Texture {
public:
    // From 8-bit sRGB RGB(A) texels, row 0 = the top of the picture (alpha ignored).
    Texture(int width, int height, int channels, const uint8_t *texels, Wrap wrap_u, Wrap wrap_v);

    int width() const { return levels_[0].w; }
    int height() const { return levels_[0].h; }
    int levels() const { return int(levels_.size()); }
    Wrap wrap_u() const { return wrap_u_; }
    Wrap wrap_v() const { return wrap_v_; }

    // Texel (x, y) of a level (no wrapping; in range).
    Vec3 texel(int level, int x, int y) const;
    // Bilinear sample of one level at texture coordinates (u, v): u to the right, v up
    // (assimp's convention: v = 0 is the bottom row of the picture).
    Vec3 bilinear(int level, float u, float v) const;
    // Trilinear sample for a footprint of `texels` level-0 texels.
    Vec3 sample(float u, float v, float texels) const;

private:
    struct Level {
        int w, h;
        std::vector<float> rgb;  // 3 floats per texel, row-major, row 0 at the top
    };
    std::vector<Level> levels_;
    Wrap wrap_u_, wrap_v_;
};

// Decodes a compressed picture (PNG, JPEG, TGA, BMP, ... as stb_image reads them). Returns
// false with a reason when it cannot.
bool decode_image(const uint8_t *data, size_t size, std::vector<uint8_t> &rgba, int &w, int &h, std::string &why);
bool decode_image_file(const std::string &path, std::vector<uint8_t> &rgba, int &w, int &h, std::string &why);

}  // namespace msr

// The one compilation of Debian libstb-dev's stb_image (header-only library): static functions,
// private to this shared library (its exports are only msr_render_*).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_NO_HDR      // 8-bit pictures only
#define STBI_NO_LINEAR
#define STBI_FAILURE_USERMSG
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb/stb_image.h>

#include "texture.h"

#include <climits>

namespace msr {

namespace {
bool take(stbi_uc *px, int w, int h, std::vector<uint8_t> &rgba, int &ow, int &oh, std::string &why) {
    if (!px) {
        const char *r = stbi_failure_reason();
        why = r ? r : "unknown image format";
        return false;
    }
    rgba.assign(px, px + size_t(w) * size_t(h) * 4);
    stbi_image_free(px);
    ow = w;
    oh = h;
    return true;
}
}  // namespace

bool decode_image(const uint8_t *data, size_t size, std::vector<uint8_t> &rgba, int &w, int &h, std::string &why) {
    if (!data || size == 0 || size > size_t(INT_MAX)) { why = "empty or oversized image data"; return false; }
    int n = 0;
    stbi_uc *px = stbi_load_from_memory(data, int(size), &w, &h, &n, 4);
    return take(px, w, h, rgba, w, h, why);
}

bool decode_image_file(const std::string &path, std::vector<uint8_t> &rgba, int &w, int &h, std::string &why) {
    int n = 0;
    stbi_uc *px = stbi_load(path.c_str(), &w, &h, &n, 4);
    return take(px, w, h, rgba, w, h, why);
}

}  // namespace msr

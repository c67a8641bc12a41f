// The C API (msr_render.h) over msr::Renderer.
#include "msr_render.h"

#include <xmmintrin.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <string>

#include "render.h"
#include "scenes.h"

struct msr_render_ctx {
    RTCDevice device = nullptr;
    std::unique_ptr<msr::Renderer> renderer;  // owns the scene; released before the device
    std::atomic<uint64_t> rays{0};            // rays cast by all calls so far
    ~msr_render_ctx() {
        renderer.reset();
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

constexpr int kMaxSize = 4096;
static_assert(MSR_RENDER_DEFAULT_SEED == msr::Renderer::kDefaultSeed, "one default seed");

void set_err(char *err, size_t errlen, const std::string &msg) {
    if (!err || errlen == 0) return;
    std::string one = msg;
    for (char &c : one)
        if (c == '\n' || c == '\r') c = ' ';
    std::snprintf(err, errlen, "%s", one.c_str());
}

// Every pixel is computed with the same SSE state, whatever the caller set: round to
// nearest, all exceptions masked, flush-to-zero and denormals-are-zero (Embree's advice).
class FpState {
public:
    FpState() : saved_(_mm_getcsr()) { _mm_setcsr(0x1F80u | 0x8040u); }
    ~FpState() { _mm_setcsr(saved_); }

private:
    unsigned saved_;
};

struct DeviceError {
    std::string msg;
};

void device_error(void *user, RTCError code, const char *str) {
    auto *e = static_cast<DeviceError *>(user);
    if (e && e->msg.empty()) e->msg = "embree error " + std::to_string(int(code)) + (str ? std::string(": ") + str : "");
}

// The instruction set is pinned so that the same pixel comes out on every machine (the ISA
// Embree picks can flip a hit exactly on a triangle edge). MSR_EMBREE_ISA overrides it.
// Returns "" for an MSR_EMBREE_ISA that Embree does not know (Embree would silently ignore it
// and pick the best ISA, which defeats the pin).
std::string isa_config(bool &from_env) {
    const char *env = std::getenv("MSR_EMBREE_ISA");
    from_env = env && *env;
    std::string isa = from_env ? env : "avx2";
    if (from_env) {
        bool known = false;
        for (const char *k : {"sse2", "sse4.2", "avx", "avx2", "avx512"}) known = known || isa == k;
        if (!known) return "";
    }
    if (!from_env && !__builtin_cpu_supports("avx2")) {
        static std::once_flag warned;
        std::call_once(warned, [] {
            std::fprintf(stderr, "msr_render: CPU without AVX2, using isa=sse4.2 (pixels on exact triangle edges may "
                                 "differ from AVX2 machines)\n");
        });
        isa = "sse4.2";
    }
    return "isa=" + isa;
}

}  // namespace

extern "C" {

msr_render_ctx *msr_render_create(const char *scene, int width, int height, int quality, char *err, size_t errlen) {
    return msr_render_create_view(scene, nullptr, width, height, quality, err, errlen);
}

msr_render_ctx *msr_render_create_view(const char *scene, const char *camera, int width, int height, int quality,
                                       char *err, size_t errlen) {
    return msr_render_create_spp(scene, camera, width, height, quality, 0, msr::Renderer::kDefaultSeed, err, errlen);
}

msr_render_ctx *msr_render_create_spp(const char *scene, const char *camera, int width, int height, int quality,
                                      int grid, uint32_t seed, char *err, size_t errlen) {
    set_err(err, errlen, "");
    if (grid < 0 || grid > msr::Renderer::kMaxGrid) {
        set_err(err, errlen, "antialiasing grid " + std::to_string(grid) + " outside 0.." +
                                 std::to_string(msr::Renderer::kMaxGrid));
        return nullptr;
    }
    if (!scene) { set_err(err, errlen, "scene is NULL"); return nullptr; }
    if (width < 1 || width > kMaxSize || height < 1 || height > kMaxSize) {
        set_err(err, errlen, "frame size " + std::to_string(width) + "x" + std::to_string(height) + " outside 1..4096");
        return nullptr;
    }
    if (quality != 0 && quality != 1) {
        set_err(err, errlen, "quality " + std::to_string(quality) + " is neither 0 (fast) nor 1 (heavy)");
        return nullptr;
    }
    try {
        bool from_env = false;
        std::string cfg = isa_config(from_env);
        if (cfg.empty()) {
            set_err(err, errlen, std::string("MSR_EMBREE_ISA=") + std::getenv("MSR_EMBREE_ISA") +
                                     " is not one of sse2, sse4.2, avx, avx2, avx512");
            return nullptr;
        }
        DeviceError derr;  // outlives ctx: the device reports into it until released
        auto ctx = std::make_unique<msr_render_ctx>();
        ctx->device = rtcNewDevice(cfg.c_str());
        if (!ctx->device) {
            set_err(err, errlen, "embree: cannot create a device with " + cfg +
                                     (from_env ? " (check MSR_EMBREE_ISA)" : " (set MSR_EMBREE_ISA, e.g. sse4.2)"));
            return nullptr;
        }
        rtcSetDeviceErrorFunction(ctx->device, device_error, &derr);
        std::string msg;
        float view[7];
        if (camera && *camera && !msr::parse_view(camera, view, msg)) { set_err(err, errlen, msg); return nullptr; }
        std::unique_ptr<msr::Scene> sc = msr::make_scene(scene, msg);
        if (!sc) { set_err(err, errlen, msg); return nullptr; }
        if (camera && *camera && !msr::set_view(*sc, camera, msg)) { set_err(err, errlen, msg); return nullptr; }
        bool ok = sc->commit(ctx->device, msg);
        rtcSetDeviceErrorFunction(ctx->device, nullptr, nullptr);
        if (!ok || !derr.msg.empty()) {
            set_err(err, errlen, derr.msg.empty() ? msg : derr.msg);
            return nullptr;
        }
        ctx->renderer = std::make_unique<msr::Renderer>(std::move(sc), width, height,
                                                        quality ? msr::Quality::Heavy : msr::Quality::Fast, grid, seed);
        return ctx.release();
    } catch (const std::exception &e) {
        set_err(err, errlen, std::string("renderer: ") + e.what());
    } catch (...) {
        set_err(err, errlen, "renderer: unknown failure while building the scene");
    }
    return nullptr;
}

void msr_render_pixel(msr_render_ctx *ctx, int x, int y, uint8_t rgb[3]) {
    if (!rgb) return;
    if (!ctx || !ctx->renderer) { rgb[0] = rgb[1] = rgb[2] = 0; return; }
    FpState fp;
    uint64_t rays = 0;
    ctx->renderer->pixel(x, y, rgb, &rays);
    ctx->rays.fetch_add(rays, std::memory_order_relaxed);
}

void msr_render_pixels(msr_render_ctx *ctx, int n, const int32_t *xs, const int32_t *ys, uint8_t *rgb_out) {
    if (n <= 0 || !rgb_out) return;
    if (!ctx || !ctx->renderer || !xs || !ys) { std::memset(rgb_out, 0, size_t(n) * 3); return; }
    FpState fp;
    uint64_t rays = 0;
    for (int i = 0; i < n; ++i) ctx->renderer->pixel(xs[i], ys[i], rgb_out + 3 * size_t(i), &rays);
    ctx->rays.fetch_add(rays, std::memory_order_relaxed);
}

void msr_render_gbuffer(msr_render_ctx *ctx, int n, const int32_t *xs, const int32_t *ys, uint32_t *prim_out,
                        uint32_t *material_out, float *depth_out) {
    if (n <= 0) return;
    FpState fp;
    for (int i = 0; i < n; ++i) {
        uint32_t p = 0, m = 0;
        float d = std::numeric_limits<float>::infinity();
        if (ctx && ctx->renderer && xs && ys) ctx->renderer->gbuffer(xs[i], ys[i], p, m, d);
        if (prim_out) prim_out[i] = p;
        if (material_out) material_out[i] = m;
        if (depth_out) depth_out[i] = d;
    }
}

void msr_render_pixels_invz(msr_render_ctx *ctx, int n, const int32_t *xs, const int32_t *ys, uint8_t *rgb_out,
                            uint16_t *invz_out, int invz_exp) {
    if (n <= 0) return;
    if (rgb_out) msr_render_pixels(ctx, n, xs, ys, rgb_out);
    if (!invz_out) return;
    FpState fp;
    const double scale = (ctx && ctx->renderer) ? double(ctx->renderer->scene().model_placement.scale) : 1.0;
    const double k = std::ldexp(1.0, invz_exp < 0 ? 0 : (invz_exp > 40 ? 40 : invz_exp));
    for (int i = 0; i < n; ++i) {
        uint32_t p = 0, m = 0;
        float d = std::numeric_limits<float>::infinity();
        if (ctx && ctx->renderer && xs && ys) ctx->renderer->gbuffer(xs[i], ys[i], p, m, d);
        uint16_t q = 0;  // the sky (and a NULL context): 0
        if (std::isfinite(d) && d > 0.f) {
            // inverse depth in model units: scale / d (d is in world units, scale world per model unit)
            const double w = std::floor(k * scale / double(d) + 0.5);
            q = w >= 65535.0 ? uint16_t(65535) : (w < 1.0 ? uint16_t(1) : uint16_t(w));
        }
        invz_out[i] = q;
    }
}

double msr_render_model_scale(const msr_render_ctx *ctx) {
    return (ctx && ctx->renderer) ? double(ctx->renderer->scene().model_placement.scale) : 0.0;
}

void msr_render_destroy(msr_render_ctx *ctx) { delete ctx; }

const char *msr_render_scene_names(void) { return msr::builtin_scene_names(); }

uint64_t msr_render_rays(const msr_render_ctx *ctx) { return ctx ? ctx->rays.load(std::memory_order_relaxed) : 0; }

int msr_render_view(const msr_render_ctx *ctx, double view[7]) {
    if (!ctx || !ctx->renderer || !view) return 0;
    const msr::Scene &s = ctx->renderer->scene();
    const msr::Placement &pl = s.model_placement;
    // Placement::point inverted: p = R_yaw^-1 ((p' - offset) / scale) + pivot
    auto model = [&](msr::Vec3 q) {
        const double x = (double(q.x) - pl.offset.x) / pl.scale, y = (double(q.y) - pl.offset.y) / pl.scale,
                     z = (double(q.z) - pl.offset.z) / pl.scale;
        return std::array<double, 3>{pl.cos_yaw * x - pl.sin_yaw * z + pl.pivot.x, y + pl.pivot.y,
                                     pl.sin_yaw * x + pl.cos_yaw * z + pl.pivot.z};
    };
    const auto e = model(s.camera.eye), t = model(s.camera.target);
    double tan_v = s.camera.tan_half;  // across the shorter side unless vertical
    const int w = ctx->renderer->width(), h = ctx->renderer->height();
    if (!s.camera.vertical && w < h) tan_v *= double(h) / double(w);
    const double fov = 2.0 * std::atan(tan_v) * 180.0 / 3.14159265358979323846;
    for (int i = 0; i < 3; ++i) {
        view[i] = e[i];
        view[3 + i] = t[i];
    }
    view[6] = fov;
    return 1;
}

int msr_render_framing(const msr_render_ctx *ctx, double framing[9]) {
    if (!ctx || !ctx->renderer || !framing) return 0;
    const msr::Placement &f = ctx->renderer->scene().framing;
    const double v[9] = {f.pivot.x, f.pivot.y, f.pivot.z, f.scale, f.cos_yaw, f.sin_yaw,
                         f.offset.x, f.offset.y, f.offset.z};
    for (int i = 0; i < 9; ++i) framing[i] = v[i];
    return 1;
}

}  // extern "C"

// DPI-C implementation of sim/msr_dpi.h: the Embree rendering library, or a PPM picture.
#include "msr_dpi.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "msr_render.h"
#include "verilated.h"              // Verilated::commandArgsPlusMatch (+camera=)
#include "Vmsr_sim_top__Dpi.h"  // generated prototypes: the compiler checks ours against them

namespace {

struct DpiCtx {
  msr_render_ctx *render = nullptr;  // Embree scene, or
  std::vector<uint8_t> image;        // a PPM picture (image-as-renderer)
  int width = 0;
  int height = 0;
  std::string scene;                 // what it was opened on (msr_dpi_set_view reopens it)
  int quality = 0;
};

DpiCtx *g_last = nullptr;            // the context msr_dpi_set_view moves (one renderer per sim)

bool ends_with(const std::string &s, const char *suffix) {
  const size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

// Binary PPM (P6, maxval 255) of exactly width x height pixels.
bool load_ppm(const std::string &path, int width, int height, std::vector<uint8_t> &out,
              std::string &err) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    err = "cannot open " + path;
    return false;
  }
  std::string magic;
  int w = 0, h = 0, maxval = 0;
  f >> magic >> w >> h >> maxval;
  f.get();  // the single whitespace byte before the raster
  if (!f || magic != "P6" || maxval != 255) {
    err = path + ": not an 8-bit binary PPM (P6)";
    return false;
  }
  if (w != width || h != height) {
    err = path + ": picture is " + std::to_string(w) + "x" + std::to_string(h) + ", frame is " +
          std::to_string(width) + "x" + std::to_string(height);
    return false;
  }
  out.resize(static_cast<size_t>(w) * h * 3);
  f.read(reinterpret_cast<char *>(out.data()), static_cast<std::streamsize>(out.size()));
  if (!f) {
    err = path + ": raster too short";
    return false;
  }
  return true;
}

}  // namespace

extern "C" void *msr_dpi_open(const char *scene, int width, int height, int quality) {
  auto *ctx = new DpiCtx;
  ctx->width = width;
  ctx->height = height;
  const std::string s = scene ? scene : "";
  if (ends_with(s, ".ppm")) {
    std::string err;
    if (!load_ppm(s, width, height, ctx->image, err)) {
      std::fprintf(stderr, "render_dpi: error: %s\n", err.c_str());
      delete ctx;
      return nullptr;
    }
    return ctx;
  }
  char err[512] = {0};
  // +camera=EX,EY,EZ,TX,TY,TZ,FOV: the view, handed to the library unchanged (as the Python
  // flow hands it), so the same string gives the same pixels.
  const char *cam_arg = Verilated::commandArgsPlusMatch("camera=");
  const std::string camera = (cam_arg && std::strncmp(cam_arg, "+camera=", 8) == 0) ? cam_arg + 8 : "";
  ctx->render = msr_render_create_view(s.c_str(), camera.empty() ? nullptr : camera.c_str(), width,
                                       height, quality, err, sizeof err);
  if (!ctx->render) {
    std::fprintf(stderr, "render_dpi: error: %s\n", err[0] ? err : "cannot open the scene");
    delete ctx;
    return nullptr;
  }
  ctx->scene = s;
  ctx->quality = quality;
  g_last = ctx;
  return ctx;
}

extern "C" int msr_dpi_set_view(const char *camera, char *err, int err_len) {
  DpiCtx *ctx = g_last;
  if (ctx == nullptr || ctx->render == nullptr) {
    std::snprintf(err, err_len, "no scene to move the camera in (a picture scene has no view)");
    return 0;
  }
  msr_render_ctx *next = msr_render_create_view(ctx->scene.c_str(), camera, ctx->width, ctx->height,
                                                ctx->quality, err, static_cast<size_t>(err_len));
  if (next == nullptr) return 0;
  msr_render_destroy(ctx->render);
  ctx->render = next;
  return 1;
}

extern "C" int msr_dpi_render(void *handle, int x, int y) {
  auto *ctx = static_cast<DpiCtx *>(handle);
  uint8_t rgb[3] = {0, 0, 0};
  if (ctx == nullptr) return 0;
  if (ctx->render) {
    msr_render_pixel(ctx->render, x, y, rgb);
  } else if (x >= 0 && y >= 0 && x < ctx->width && y < ctx->height) {
    std::memcpy(rgb, &ctx->image[(static_cast<size_t>(y) * ctx->width + x) * 3], 3);
  }
  return (rgb[0] << 16) | (rgb[1] << 8) | rgb[2];
}

extern "C" long long msr_dpi_render_cz(void *handle, int x, int y, int invz_exp) {
  auto *ctx = static_cast<DpiCtx *>(handle);
  uint8_t rgb[3] = {0, 0, 0};
  uint16_t invz = 0;
  if (ctx == nullptr) return 0;
  if (ctx->render) {
    const int32_t xs[1] = {x}, ys[1] = {y};
    msr_render_pixels_invz(ctx->render, 1, xs, ys, rgb, &invz, invz_exp);
  } else if (x >= 0 && y >= 0 && x < ctx->width && y < ctx->height) {
    std::memcpy(rgb, &ctx->image[(static_cast<size_t>(y) * ctx->width + x) * 3], 3);
  }
  return (static_cast<long long>(invz) << 24) | (rgb[0] << 16) | (rgb[1] << 8) | rgb[2];
}

extern "C" void msr_dpi_close(void *handle) {
  auto *ctx = static_cast<DpiCtx *>(handle);
  if (ctx == nullptr) return;
  if (g_last == ctx) g_last = nullptr;
  msr_render_destroy(ctx->render);
  delete ctx;
}

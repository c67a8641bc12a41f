/* msr_render.h: C API of the rendering unit (an Embree 3 Whitted ray tracer).
 *
 * One shared library (build/renderer/libmsr_render.so) paints every pixel in every flow:
 * the Python golden model (ctypes) and the RTL simulation (DPI-C) both call these functions,
 * so they see bit-identical pixels by construction.
 *
 * Determinism: a pixel's colour depends only on (scene, width, height, quality, x, y) (and the
 * grid and seed of msr_render_create_spp), never on
 * call order, batch split or thread. The scene is read-only after msr_render_create, so any
 * number of threads may call msr_render_pixel(s) on one context at the same time.
 */
#ifndef MSR_RENDER_H
#define MSR_RENDER_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct msr_render_ctx msr_render_ctx; /* opaque */

/* scene: built-in name (see msr_render_scene_names) or a model file path (any format the Open
 * Asset Importer reads). width, height: 1..4096. quality 0 = fast (one sample per pixel),
 * 1 = heavy (several deterministic samples: antialiasing, soft shadows, ambient occlusion).
 * Returns NULL on failure, with a one-line message in err (errlen bytes, NUL-terminated;
 * err may be NULL when errlen is 0). */
msr_render_ctx *msr_render_create(const char *scene, int width, int height, int quality,
                                  char *err, size_t errlen);

/* The same, seen from a given view: camera "EX,EY,EZ,TX,TY,TZ,FOV" (eye and target in model
 * units, i.e. the coordinates of the model file or of the built-in scene; vertical field of
 * view in degrees, 0 < FOV < 180; up is +y). NULL or "" keeps the scene's own view (the
 * file's camera, else the automatic framing). A malformed camera is an error like a bad
 * scene. msr_render_create(s, ...) is msr_render_create_view(s, NULL, ...). */
msr_render_ctx *msr_render_create_view(const char *scene, const char *camera, int width, int height,
                                       int quality, char *err, size_t errlen);

/* Extension (converged references): the same with the sampling chosen. grid: grid x grid
 * stratified, jittered samples per pixel, 1..64 (in heavy mode each sample also takes one
 * area-light point, the strata shuffled per pixel, and one ambient-occlusion ray; in fast mode
 * the shading stays noise-free and the samples only antialias; fast with grid 1 samples the
 * pixel centre); 0 = the quality's own (1 fast, 4 heavy). seed: the seed of every pixel hash
 * (MSR_RENDER_DEFAULT_SEED is the fixed one). msr_render_create_view(s, c, w, h, q, e, n) is
 * msr_render_create_spp(s, c, w, h, q, 0, MSR_RENDER_DEFAULT_SEED, e, n), pixel for pixel.
 * Two seeds give independent renders of the same scene (the evaluation's convergence check). */
#define MSR_RENDER_DEFAULT_SEED 0x4d5352u
msr_render_ctx *msr_render_create_spp(const char *scene, const char *camera, int width, int height,
                                      int quality, int grid, uint32_t seed, char *err, size_t errlen);

/* Colour of pixel (x, y), (0, 0) top left, as 8-bit sRGB. A pixel outside the frame (or a NULL
 * context) gives (0, 0, 0). */
void msr_render_pixel(msr_render_ctx *ctx, int x, int y, uint8_t rgb[3]);

/* n pixels at once: rgb_out[3*i .. 3*i+2] is the colour of (xs[i], ys[i]). */
void msr_render_pixels(msr_render_ctx *ctx, int n, const int32_t *xs, const int32_t *ys,
                       uint8_t *rgb_out /* 3*n bytes */);

/* Extension (G-buffer): for each pixel, what the primary ray through its centre hits:
 * prim_out[i] = triangle index + 1 over the whole scene, material_out[i] = material index + 1
 * (both 0 where the ray meets the sky), depth_out[i] = distance along the camera's viewing
 * axis (+inf for the sky). Any output pointer may be NULL. Deterministic like the colours;
 * the rays are not counted by msr_render_rays. */
void msr_render_gbuffer(msr_render_ctx *ctx, int n, const int32_t *xs, const int32_t *ys,
                        uint32_t *prim_out, uint32_t *material_out, float *depth_out);

/* Extension (reuse across frames, docs/spec/reuse.md): the colours of msr_render_pixels (rgb_out may be
 * NULL) and, per pixel, the primary hit's inverse depth in model units as 16-bit fixed point:
 * invz_out[i] = min(65535, max(1, floor(2^invz_exp * s / d + 0.5))) with d the G-buffer depth
 * (world units, along the viewing axis, float) and s the model's placement scale (world units per
 * model unit, msr_render_model_scale), computed in double; 0 for the sky. invz_exp: 0..40. */
void msr_render_pixels_invz(msr_render_ctx *ctx, int n, const int32_t *xs, const int32_t *ys, uint8_t *rgb_out,
                            uint16_t *invz_out, int invz_exp);

/* Extension: world units per model unit of the scene's placement (1 for the built-in scenes); 0 for
 * a NULL context. */
double msr_render_model_scale(const msr_render_ctx *ctx);

void msr_render_destroy(msr_render_ctx *ctx); /* NULL is fine */

/* Comma-separated names of the built-in scenes (static string), default scene first. */
const char *msr_render_scene_names(void);

/* Extension for benchmarks: rays (primary, shadow, secondary, occlusion) cast by all pixel
 * calls on ctx so far. */
uint64_t msr_render_rays(const msr_render_ctx *ctx);

/* Extension for camera paths: the context's view as a camera string would give it: eye and
 * target in model units (the inverse of the model's placement) and the vertical field of view
 * in degrees. Returns 1, or 0 for a NULL context. */
int msr_render_view(const msr_render_ctx *ctx, double view[7]);

/* Extension for camera paths in framed units: the scene's framing, model units -> framed units
 * (the subject on the ground plane y = 0 inside a bounding sphere of radius 1, its bounding-box
 * centre above the origin; for a model file that is where the renderer places it):
 * p' = R_yaw (p - pivot) * scale + offset, R_yaw (x, z) = (c x + s z, -s x + c z).
 * framing = {pivot x, y, z, scale, cos yaw, sin yaw, offset x, y, z}. Returns 1, or 0 for a
 * NULL context. */
int msr_render_framing(const msr_render_ctx *ctx, double framing[9]);

#ifdef __cplusplus
}
#endif

#endif /* MSR_RENDER_H */

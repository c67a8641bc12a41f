/* msr_dpi.h: DPI-C bridge from the SystemVerilog rendering unit (sim/render_dpi.sv) to the
 * rendering library's C API (sw_model/renderer/include/msr_render.h).
 *
 * The SV side holds the context as an opaque chandle, created once in an initial block and
 * freed in a final block. Besides the Embree scenes, a binary PPM file (P6, 8-bit) given as
 * the scene is answered pixel by pixel from the picture (image-as-renderer, for tests).
 */
#ifndef MSR_DPI_H
#define MSR_DPI_H

#ifdef __cplusplus
extern "C" {
#endif

/* Open the rendering unit for a width x height frame; quality 0 fast, 1 heavy. On failure
 * prints one line on stderr and returns NULL. */
void *msr_dpi_open(const char *scene, int width, int height, int quality);

/* Colour of pixel (x, y) as 0x00RRGGBB. */
int msr_dpi_render(void *ctx, int x, int y);

/* Colour and inverse depth of pixel (x, y) in one trace, as (invz << 24) | 0x00RRGGBB: invz the
 * primary hit's inverse depth at exponent invz_exp (msr_render_pixels_invz; 0 for the sky and for
 * every pixel of a picture scene, which has no depth). */
long long msr_dpi_render_cz(void *ctx, int x, int y, int invz_exp);

/* The depth channel's monitor (sim/msr_sim_top.sv with DEPTH_EN): pixel (x, y) of the frame left
 * an engine with inverse depth invz. Implemented by the C++ harness (its --depth plane). */
void msr_dpi_depth_pixel(int x, int y, int invz);

/* Not a DPI function: the C++ harness's. The view of the last opened context becomes `camera`
 * ("EX,EY,EZ,TX,TY,TZ,FOV", as +camera=) for the frames that follow (a sequence in one run).
 * Returns 1, or 0 with the reason in err (a picture scene has no view; a bad camera). */
int msr_dpi_set_view(const char *camera, char *err, int err_len);

/* Free the context (NULL is fine). */
void msr_dpi_close(void *ctx);

#ifdef __cplusplus
}
#endif

#endif /* MSR_DPI_H */

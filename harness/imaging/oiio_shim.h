/* gibench — the one C++ shim around OpenImageIO 2.4 (OIIO has no C API). */
#ifndef GIB_OIIO_SHIM_H
#define GIB_OIIO_SHIM_H

#ifdef __cplusplus
extern "C" {
#endif

/* Reads any image OIIO can read (PNG, JPEG, TGA, ...) into *rgba: width*height*4 floats, row 0 on
 * top, values as stored in the file scaled to [0,1] (8-bit sRGB data is NOT linearised here).
 * Missing channels: gray replicated to RGB, alpha = 1. Returns 0, or -1 with a message naming the
 * file in errbuf (also for a size over GIB_IMAGE_MAX_PIXELS or GIB_IMAGE_MAX_CHANNELS). The caller frees *rgba with free(). */
/* Images (textures) larger than this are refused before their pixels are allocated: 8192^2. */
#define GIB_IMAGE_MAX_PIXELS (1LL << 26)
#define GIB_IMAGE_MAX_CHANNELS 64
int gib_oiio_read_rgba(const char *path, int *width, int *height, float **rgba, char *errbuf,
                       int errbuf_len);

/* Writes 8-bit data (channels 1, 3 or 4; row 0 on top) as PNG. */
int gib_oiio_write_png8(const char *path, int width, int height, int channels,
                        const unsigned char *data, char *errbuf, int errbuf_len);

#ifdef __cplusplus
}
#endif
#endif

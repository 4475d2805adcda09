/* gibench — one pixel of 1-4+ channels as RGBA, shared by the image readers (oiio_shim.cpp and its
 * libstb twin stb_shim.c): gray replicated to RGB, alpha 1 where the image has none. */
#ifndef GIB_RGBA_EXPAND_H
#define GIB_RGBA_EXPAND_H

static inline void gib_rgba_expand(const float *s, int channels, float *d)
{
    if (channels == 1 || channels == 2) { /* gray, or gray + alpha */
        d[0] = d[1] = d[2] = s[0];
        d[3] = channels == 2 ? s[1] : 1.0f;
    } else {
        d[0] = s[0];
        d[1] = s[1];
        d[2] = s[2];
        d[3] = channels >= 4 ? s[3] : 1.0f;
    }
}

#endif

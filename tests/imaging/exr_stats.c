/* exr_stats FILE: what two readers see in an EXR's R, G and B (or Y) samples, for scripts that
 * check a file gibench wrote (tests/reference/ref_exr_readback.sh). Prints one line per reader,
 *   gib  mean=M nonfinite=N maxabs=A      (harness/imaging/exr.c, gib_exr_read)
 *   oiio mean=M nonfinite=N maxabs=A      (OpenImageIO, through harness/imaging/oiio_shim.h)
 * and the header's `mean` attribute (the renderer's, over the same samples) as
 *   header mean=M
 * (`header mean=none` when it has none). Means are over finite samples, in double. Exit 1 if a
 * reader fails. */
#include "harness/imaging/image.h"
#include "harness/imaging/oiio_shim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Prints the mean, non-finite count and largest magnitude of n samples read `stride` apart. */
static void print_stats(const char *reader, const float *px, size_t n, int stride, int used)
{
    double sum = 0, maxabs = 0;
    long nonfinite = 0, finite = 0;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < used; ++k) {
            double v = px[i * stride + k];
            if (!isfinite(v)) {
                ++nonfinite;
                continue;
            }
            sum += v;
            ++finite;
            maxabs = fmax(maxabs, fabs(v));
        }
    printf("%s mean=%.9g nonfinite=%ld maxabs=%.9g\n", reader, finite ? sum / finite : 0.0,
           nonfinite, maxabs);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: exr_stats FILE.exr\n");
        return 2;
    }
    gib_image img;
    gib_kv *attrs = NULL;
    int nattrs = 0;
    gib_error err;
    if (gib_exr_read(argv[1], &img, &attrs, &nattrs, &err) != 0) {
        fprintf(stderr, "exr_stats: %s\n", err.msg);
        return 1;
    }
    print_stats("gib", img.px, (size_t)img.width * img.height, 3, 3);
    const char *mean = gib_kv_get(attrs, nattrs, "mean");
    printf("header mean=%s\n", mean ? mean : "none");
    gib_image_free(&img);
    free(attrs);

    int w = 0, h = 0;
    float *rgba = NULL;
    char msg[512];
    if (gib_oiio_read_rgba(argv[1], &w, &h, &rgba, msg, sizeof msg) != 0) {
        fprintf(stderr, "exr_stats: %s\n", msg);
        return 1;
    }
    print_stats("oiio", rgba, (size_t)w * h, 4, 3);
    free(rgba);
    return 0;
}

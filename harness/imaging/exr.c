/* gibench — EXR write/read through the OpenEXR 3.1 core C API (no C++ in the image path).
 *
 * Row 0 of a gib_image is the top row, and EXR scanlines also run top to bottom (y grows
 * downward in the data window), so rows map one to one without a flip. */
#include "image.h"

#include <openexr.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The library reports details (e.g. "No such file or directory") only through its error callback;
 * keep the last one per thread so our message can carry it. The callback's context has no user
 * pointer we own for file-backed streams, hence thread-local storage. */
static _Thread_local char exr_last_msg[512];

static void exr_error_cb(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(exr_last_msg, sizeof exr_last_msg, "%s (%s)", msg ? msg : "",
             exr_get_error_code_as_string(code));
}

static exr_context_initializer_t exr_init(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_error_cb;
    return init;
}

/* Formats "what 'path': detail" using the library's last message when it has one. */
static int exr_fail(gib_error *err, const char *what, const char *path, exr_result_t rv)
{
    if (exr_last_msg[0])
        return gib_fail(err, "%s '%s': %s", what, path, exr_last_msg);
    return gib_fail(err, "%s '%s': %s", what, path, exr_get_default_error_message(rv));
}

static const char *channel_names(int channels, int k)
{
    static const char *const rgba[4] = {"R", "G", "B", "A"};
    return channels == 1 ? "Y" : rgba[k];
}

/* A ZIP chunk whose zlib stream is exactly as long as its pixels is stored as raw pixels.
 *
 * The format tells a reader that a chunk is stored uncompressed by its size alone: a chunk as long
 * as its raw pixels is read as raw pixels. OpenEXR 3.1's core ZIP compressor (internal_zip.c,
 * apply_zip_impl) falls back to the raw pixels only when the zlib stream is LONGER than them
 * (`compbufsz > packed_bytes`), so a stream of exactly that length is written as it is and read
 * back as raw floats: values up to 3.4e38 and NaNs over the whole chunk. It happens to a chunk of
 * noisy floats now and then (a 16-line chunk of a 64x64 `indirect` reference; small partial chunks
 * of smooth images too). The library's transform itself is sound: it works in a scratch buffer and
 * leaves the packed pixels untouched, so its fallback copies the right bytes. Upstream made the
 * comparison `>=` in 3.4.8; every 3.1 release (Debian's 3.1.5 here) has `>`, so the write path
 * wraps the library's compress step (the pipeline's compress_fn hook) and applies `>=` after it.
 * tests/imaging/test_exr_roundtrip.c builds such chunks on purpose. */
typedef struct exr_writer {
    exr_encode_pipeline_t enc; /* first: the hook receives &enc and finds the rest from it */
    exr_result_t (*library_compress)(exr_encode_pipeline_t *enc);
} exr_writer;

static exr_result_t compress_chunk(exr_encode_pipeline_t *enc)
{
    exr_writer *w = (exr_writer *)enc;
    exr_result_t rv = w->library_compress(enc);
    if (rv != EXR_ERR_SUCCESS || enc->compressed_bytes < enc->packed_bytes)
        return rv;
    /* Not smaller than the pixels: store the pixels, which the reader then takes as they are. */
    if (enc->compressed_buffer != enc->packed_buffer) {
        if (enc->compressed_alloc_size < enc->packed_bytes)
            return EXR_ERR_OUT_OF_MEMORY;
        memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    }
    enc->compressed_bytes = enc->packed_bytes;
    return EXR_ERR_SUCCESS;
}

/* Points the encoder's channels at one chunk's rows of img. The pipeline lists channels
 * alphabetically (A, B, G, R), so they are matched by name. */
static void point_encode_channels(exr_encode_pipeline_t *enc, const gib_image *img, int start_y)
{
    const int c = img->channels;
    const int32_t pixel_stride = (int32_t)(c * sizeof(float));
    const int32_t line_stride = pixel_stride * img->width;
    for (int ch = 0; ch < enc->channel_count; ++ch) {
        exr_coding_channel_info_t *info = &enc->channels[ch];
        int k = 0;
        while (k < c && strcmp(info->channel_name, channel_names(c, k)) != 0)
            ++k;
        info->user_pixel_stride = pixel_stride;
        info->user_line_stride = line_stride;
        info->user_data_type = EXR_PIXEL_FLOAT;
        info->user_bytes_per_element = 4;
        info->encode_from_ptr = (const uint8_t *)(img->px + ((size_t)start_y * img->width) * c + k);
    }
}

/* Every chunk of img encoded and written, through compress_chunk. */
static exr_result_t encode_pixels(exr_context_t ctxt, int part, const gib_image *img)
{
    int32_t lines = 1;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
    exr_writer writer;
    memset(&writer, 0, sizeof writer);
    exr_encode_pipeline_t *const enc = &writer.enc;
    int have_enc = 0;
    for (int y = 0; y < img->height && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctxt, part, y, &cinfo);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = have_enc ? exr_encoding_update(ctxt, part, &cinfo, enc)
                      : exr_encoding_initialize(ctxt, part, &cinfo, enc);
        if (rv != EXR_ERR_SUCCESS)
            break;
        point_encode_channels(enc, img, cinfo.start_y);
        if (!have_enc) {
            rv = exr_encoding_choose_default_routines(ctxt, part, enc);
            have_enc = 1;
            if (rv != EXR_ERR_SUCCESS)
                break;
            if (!enc->compress_fn) { /* every chunk is ZIP: the library always sets one */
                rv = EXR_ERR_INVALID_ARGUMENT;
                break;
            }
            writer.library_compress = enc->compress_fn;
            enc->compress_fn = compress_chunk;
        }
        rv = exr_encoding_run(ctxt, part, enc);
    }
    if (have_enc)
        exr_encoding_destroy(ctxt, enc);
    return rv;
}

int gib_exr_write(const char *path, const gib_image *img, const gib_kv *attrs, int nattrs,
                  gib_error *err)
{
    if (!img || !img->px || img->width <= 0 || img->height <= 0)
        return gib_fail(err, "exr '%s': empty image", path);
    const int c = img->channels;
    if (c != 1 && c != 3 && c != 4)
        return gib_fail(err, "exr '%s': %d channels (need 1, 3 or 4)", path, c);

    exr_last_msg[0] = '\0';
    exr_context_initializer_t init = exr_init();
    exr_context_t ctxt = NULL;
    /* A temp file renamed on success: an interrupted run never leaves a truncated EXR behind. */
    exr_result_t rv = exr_start_write(&ctxt, path, EXR_INTERMEDIATE_TEMP_FILE, &init);
    if (rv != EXR_ERR_SUCCESS)
        return exr_fail(err, "cannot create exr", path, rv);

    int part = 0;
    rv = exr_add_part(ctxt, "", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctxt, part, img->width, img->height,
                                                 EXR_COMPRESSION_ZIP);
    for (int k = 0; k < c && rv == EXR_ERR_SUCCESS; ++k)
        rv = exr_add_channel(ctxt, part, channel_names(c, k), EXR_PIXEL_FLOAT,
                             EXR_PERCEPTUALLY_LINEAR, 1, 1);
    for (int i = 0; i < nattrs && rv == EXR_ERR_SUCCESS; ++i) {
        rv = exr_attr_set_string(ctxt, part, attrs[i].key, attrs[i].value);
        if (rv != EXR_ERR_SUCCESS) {
            gib_fail(err, "exr '%s': cannot set attribute '%s': %s", path, attrs[i].key,
                     exr_last_msg[0] ? exr_last_msg : exr_get_default_error_message(rv));
            exr_finish(&ctxt);
            return -1;
        }
    }
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctxt);
    if (rv != EXR_ERR_SUCCESS) {
        exr_fail(err, "cannot write exr header", path, rv);
        exr_finish(&ctxt);
        return -1;
    }

    rv = encode_pixels(ctxt, part, img);
    if (rv != EXR_ERR_SUCCESS) {
        exr_fail(err, "cannot write exr", path, rv);
        exr_finish(&ctxt);
        return -1;
    }
    rv = exr_finish(&ctxt);
    if (rv != EXR_ERR_SUCCESS)
        return exr_fail(err, "cannot finish exr", path, rv);
    return 0;
}

/* Copies the header's string attributes (keys and values longer than gib_kv's fields are
 * truncated; the harness's own keys are short). */
static int read_string_attrs(exr_context_t ctxt, const char *path, gib_kv **out, int *nout,
                             gib_error *err)
{
    *out = NULL;
    *nout = 0;
    int32_t count = 0;
    exr_result_t rv = exr_get_attribute_count(ctxt, 0, &count);
    if (rv != EXR_ERR_SUCCESS)
        return exr_fail(err, "cannot read exr attributes", path, rv);
    gib_kv *kv = gib_calloc((size_t)(count > 0 ? count : 1), sizeof(gib_kv), err);
    if (!kv)
        return gib_error_prefix(err, "exr '%s'", path);
    int n = 0;
    for (int32_t i = 0; i < count; ++i) {
        const exr_attribute_t *a = NULL;
        if (exr_get_attribute_by_index(ctxt, 0, EXR_ATTR_LIST_FILE_ORDER, i, &a) !=
                EXR_ERR_SUCCESS ||
            !a || a->type != EXR_ATTR_STRING || !a->string)
            continue;
        snprintf(kv[n].key, sizeof kv[n].key, "%s", a->name);
        int len = a->string->length;
        if (len < 0)
            len = 0;
        if ((size_t)len >= sizeof kv[n].value)
            len = (int)sizeof kv[n].value - 1;
        if (len > 0)
            memcpy(kv[n].value, a->string->str, (size_t)len);
        kv[n].value[len] = '\0';
        ++n;
    }
    *out = kv;
    *nout = n;
    return 0;
}

/* File channels that feed output channels 0..2: RGB, or Y replicated afterwards. */
static const char *const read_wanted[4] = {"R", "G", "B", "Y"};

/* Which of R, G, B and Y the file has (half or float, not subsampled); *luminance: Y alone feeds
 * the image. */
static int check_channels(const exr_attr_chlist_t *chl, const char *path, int *luminance,
                          gib_error *err)
{
    int has[4] = {0, 0, 0, 0}; /* R, G, B, Y */
    for (int i = 0; i < chl->num_channels; ++i) {
        const exr_attr_chlist_entry_t *e = &chl->entries[i];
        for (int k = 0; k < 4; ++k) {
            if (strcmp(e->name.str, read_wanted[k]) != 0)
                continue;
            if (e->pixel_type == EXR_PIXEL_UINT || e->x_sampling != 1 || e->y_sampling != 1)
                return gib_fail(err, "exr '%s': channel %s must be half or float, not subsampled",
                                path, read_wanted[k]);
            has[k] = 1;
        }
    }
    *luminance = !(has[0] && has[1] && has[2]);
    if (*luminance && !has[3])
        return gib_fail(err, "exr '%s': needs R, G, B or Y channels", path);
    return 0;
}

/* A header can claim any data window: it is held to sides and a pixel count gibench can hold
 * (2^26 RGB floats: 768 MiB), and to the offset table its chunks need (8 bytes each), before
 * anything is allocated (found by tests/fuzz/fuzz_exr: a 40-byte file claimed 36 GB). */
static int check_window(exr_context_t ctxt, const char *path, const exr_attr_box2i_t *dw,
                        gib_error *err)
{
    const int64_t w64 = (int64_t)dw->max.x - dw->min.x + 1, h64 = (int64_t)dw->max.y - dw->min.y + 1;
    if (w64 < 1 || h64 < 1 || w64 > GIB_EXR_MAX_SIDE || h64 > GIB_EXR_MAX_SIDE ||
        w64 * h64 > GIB_EXR_MAX_PIXELS)
        return gib_fail(err, "exr '%s': data window %lld x %lld outside what gibench reads (sides "
                             "1 to %d, at most %lld pixels)", path, (long long)w64, (long long)h64,
                        GIB_EXR_MAX_SIDE, (long long)GIB_EXR_MAX_PIXELS);
    int32_t chunk_count = 0;
    struct stat file_st;
    if (exr_get_chunk_count(ctxt, 0, &chunk_count) != EXR_ERR_SUCCESS || chunk_count < 1 ||
        stat(path, &file_st) != 0 || (long long)file_st.st_size < 8LL * chunk_count)
        return gib_fail(err, "exr '%s': truncated or inconsistent: %d chunks need an offset table "
                             "of %lld bytes", path, chunk_count, 8LL * chunk_count);
    return 0;
}

/* Points the decoder's channels at one chunk's rows of img (RGB interleaved); channels that feed
 * none are skipped. */
static void point_channels(exr_decode_pipeline_t *dec, float *row, int width, int luminance)
{
    for (int ch = 0; ch < dec->channel_count; ++ch) {
        exr_coding_channel_info_t *info = &dec->channels[ch];
        int k = -1;
        if (!luminance) {
            for (int j = 0; j < 3; ++j)
                if (strcmp(info->channel_name, read_wanted[j]) == 0)
                    k = j;
        } else if (strcmp(info->channel_name, "Y") == 0) {
            k = 0;
        }
        /* A NULL pointer tells the decoder to skip the channel (alpha, extra layers). */
        info->decode_to_ptr = k < 0 ? NULL : (uint8_t *)(row + k);
        info->user_pixel_stride = 3 * (int32_t)sizeof(float);
        info->user_line_stride = 3 * (int32_t)sizeof(float) * width;
        info->user_data_type = EXR_PIXEL_FLOAT; /* converts half on the fly */
        info->user_bytes_per_element = 4;
    }
}

/* Every chunk decoded into img (allocated to the data window); Y replicated into G and B. */
static exr_result_t decode_pixels(exr_context_t ctxt, const exr_attr_box2i_t *dw, int luminance,
                                  gib_image *img)
{
    const int width = img->width;
    int32_t lines = 1;
    exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    exr_decode_pipeline_t dec;
    memset(&dec, 0, sizeof dec);
    int have_dec = 0;
    exr_result_t rv = EXR_ERR_SUCCESS;
    for (int y = dw->min.y; y <= dw->max.y && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_read_scanline_chunk_info(ctxt, 0, y, &cinfo);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = have_dec ? exr_decoding_update(ctxt, 0, &cinfo, &dec)
                      : exr_decoding_initialize(ctxt, 0, &cinfo, &dec);
        if (rv != EXR_ERR_SUCCESS)
            break;
        point_channels(&dec, img->px + (size_t)(cinfo.start_y - dw->min.y) * (size_t)width * 3,
                       width, luminance);
        if (!have_dec) {
            rv = exr_decoding_choose_default_routines(ctxt, 0, &dec);
            have_dec = 1;
            if (rv != EXR_ERR_SUCCESS)
                break;
        }
        rv = exr_decoding_run(ctxt, 0, &dec);
    }
    if (have_dec)
        exr_decoding_destroy(ctxt, &dec);
    if (rv == EXR_ERR_SUCCESS && luminance) {
        for (size_t i = 0; i < (size_t)width * (size_t)img->height; ++i)
            img->px[i * 3 + 1] = img->px[i * 3 + 2] = img->px[i * 3];
    }
    return rv;
}

/* The open file's header checked, its pixels read into img and, when asked, its string
 * attributes into *kv. */
static int read_opened(exr_context_t ctxt, const char *path, gib_image *img, gib_kv **kv,
                       int *nkv, gib_error *err)
{
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *chl = NULL;
    exr_result_t rv;
    if (exr_get_storage(ctxt, 0, &storage) != EXR_ERR_SUCCESS || storage != EXR_STORAGE_SCANLINE)
        return gib_fail(err, "exr '%s': only scanline images are supported (tiled or deep found)",
                        path);
    if ((rv = exr_get_data_window(ctxt, 0, &dw)) != EXR_ERR_SUCCESS ||
        (rv = exr_get_channels(ctxt, 0, &chl)) != EXR_ERR_SUCCESS)
        return exr_fail(err, "cannot read exr header", path, rv);
    int luminance;
    if (check_channels(chl, path, &luminance, err) < 0 || check_window(ctxt, path, &dw, err) < 0)
        return -1;
    const int width = (int)((int64_t)dw.max.x - dw.min.x + 1);
    const int height = (int)((int64_t)dw.max.y - dw.min.y + 1);
    if (gib_image_alloc(img, width, height, 3, err) != 0)
        return gib_error_prefix(err, "exr '%s'", path);
    rv = decode_pixels(ctxt, &dw, luminance, img);
    if (rv != EXR_ERR_SUCCESS)
        return exr_fail(err, "cannot read exr pixels", path, rv);
    if (kv && read_string_attrs(ctxt, path, kv, nkv, err) != 0)
        return -1;
    return 0;
}

int gib_exr_read(const char *path, gib_image *img, gib_kv **attrs, int *nattrs, gib_error *err)
{
    img->px = NULL;
    img->width = img->height = img->channels = 0;
    if (attrs)
        *attrs = NULL;
    if (nattrs)
        *nattrs = 0;

    exr_last_msg[0] = '\0';
    exr_context_initializer_t init = exr_init();
    exr_context_t ctxt = NULL;
    exr_result_t rv = exr_start_read(&ctxt, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        exr_fail(err, "cannot open exr", path, rv);
        exr_finish(&ctxt);
        return -1;
    }
    gib_kv *kv = NULL;
    int nkv = 0;
    int ret = read_opened(ctxt, path, img, attrs ? &kv : NULL, &nkv, err);
    exr_finish(&ctxt);
    if (ret != 0) {
        gib_image_free(img);
        free(kv);
        return -1;
    }
    if (attrs) {
        *attrs = kv;
        if (nattrs)
            *nattrs = nkv;
    } else {
        free(kv);
    }
    return 0;
}

#include "status.h"

#include <string.h>

static const struct {
    const char *name, *doc;
} statuses[GIB_STATUS_COUNT] = {
    [GIB_STATUS_OK] = {"ok", "rendered and scored"},
    [GIB_STATUS_OUT_OF_MEMORY] =
        {"out_of_memory", "a host or GPU allocation failed, or the memory plan exceeds the budget "
                          "(the row keeps the planned bytes)"},
    [GIB_STATUS_SHADER_FAILED] = {"shader_failed", "a shader failed to compile or a program to link"},
    [GIB_STATUS_OVERFLOW] = {"overflow", "a fixed-size buffer or counter of the technique overflowed"},
    [GIB_STATUS_NONFINITE] = {"nonfinite", "the image holds NaN or infinite values (not scored)"},
    [GIB_STATUS_CONTENTION] =
        {"contention", "an LDM insertion lost its atomic races past the retry limit"},
    [GIB_STATUS_NO_PHOTONS] = {"no_photons", "the photon mask emitted no photon: the caustic is black by construction"},
    [GIB_STATUS_NO_LIGHT] = {"no_light", "the scene has no light the technique can use"},
    [GIB_STATUS_ALLOC_FAILED] = {"alloc_failed", "an allocation failed outside the memory plan"},
    [GIB_STATUS_CREATE_FAILED] = {"create_failed", "the technique's create() failed"},
    [GIB_STATUS_RENDER_FAILED] = {"render_failed", "the technique's render() failed"},
    [GIB_STATUS_SCENE_UPDATE_FAILED] =
        {"scene_update_failed", "the animated scene could not be posed or uploaded"},
    [GIB_STATUS_READBACK_FAILED] =
        {"readback_failed", "the images could not be read back (an external renderer's: missing, "
                            "unreadable, of the wrong size, or its timings.json malformed)"},
    [GIB_STATUS_REFERENCE_FAILED] =
        {"reference_failed", "the reference image could not be rendered or read"},
    [GIB_STATUS_SCORING_FAILED] = {"scoring_failed", "the metrics could not be computed"},
    [GIB_STATUS_SEQUENCE_FAILED] = {"sequence_failed", "a frame of the scored sequence failed"},
    [GIB_STATUS_EXTERNAL_FAILED] =
        {"external_failed", "an external renderer's command failed (non-zero exit, a signal, or "
                            "it could not start): the message holds its stderr's tail"},
    [GIB_STATUS_TIMEOUT] = {"timeout", "an external renderer's command ran past its timeout_s and "
                                       "was killed"},
};

const char *gib_status_name(gib_status s)
{
    return (unsigned)s < GIB_STATUS_COUNT ? statuses[s].name : NULL;
}

const char *gib_status_doc(gib_status s)
{
    return (unsigned)s < GIB_STATUS_COUNT ? statuses[s].doc : NULL;
}

int gib_status_find(const char *name)
{
    for (int s = 0; name && s < GIB_STATUS_COUNT; s++)
        if (!strcmp(name, statuses[s].name))
            return s;
    return -1;
}

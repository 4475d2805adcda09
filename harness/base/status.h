/* gibench — the words a result row's `status` column holds: one enumeration, each with what it
 * means. The runner writes them, a technique's status callback returns one, `gibench list` prints
 * them and `gibench describe` exports them for the report's package. */
#ifndef GIB_STATUS_H
#define GIB_STATUS_H

typedef enum gib_status {
    GIB_STATUS_OK = 0,
    GIB_STATUS_OUT_OF_MEMORY,
    GIB_STATUS_SHADER_FAILED,
    GIB_STATUS_OVERFLOW,
    GIB_STATUS_NONFINITE,
    GIB_STATUS_CONTENTION,
    GIB_STATUS_NO_PHOTONS,
    GIB_STATUS_NO_LIGHT,
    GIB_STATUS_ALLOC_FAILED,
    GIB_STATUS_CREATE_FAILED,
    GIB_STATUS_RENDER_FAILED,
    GIB_STATUS_SCENE_UPDATE_FAILED,
    GIB_STATUS_READBACK_FAILED,
    GIB_STATUS_REFERENCE_FAILED,
    GIB_STATUS_SCORING_FAILED,
    GIB_STATUS_SEQUENCE_FAILED,
    GIB_STATUS_EXTERNAL_FAILED,
    GIB_STATUS_TIMEOUT,
    GIB_STATUS_COUNT
} gib_status;

/* The status's word ("out_of_memory") and what it means; NULL past the enumeration. */
const char *gib_status_name(gib_status s);
const char *gib_status_doc(gib_status s);
/* The status a word names, or -1 for a word that is none. */
int gib_status_find(const char *name);

#endif

/* gibench — the reference renderer's sRGB8 mip pyramids shared between the worlds of a process.
 *
 * One process builds many worlds of one scene family (Sponza's variants and instants), each
 * loading the same texture files. An sRGB8 pyramid is a function of its level 0 alone, so a world
 * whose texture packs, texel for texel, to the level 0 of a pyramid already built for the same
 * path and size takes that pyramid, reference counted, instead of building its own: the check
 * reads the texture once and allocates nothing. Pyramids no world holds stay, the longest idle
 * freed first, while they total at most REF_SHARE_IDLE_BYTES; the rest go with the process. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref_internal.h"

#define REF_SHARE_IDLE_BYTES ((size_t)256 << 20)

typedef struct ref_shared {
    struct ref_shared *next;
    char path[512];
    ref_mip mip;
    int refs;
    unsigned long long idle_since; /* ref_share_clock when refs last fell to 0 */
} ref_shared;

/* The memory a pyramid holds: ref_alloc_huge maps whole 2 MB pages, which a small texture's
 * first touch may fill as one huge page. */
static size_t ref_share_bytes(const ref_shared *e)
{
    const size_t page = (size_t)2 << 20;
    return (e->mip.owned8_bytes + page - 1) / page * page;
}

static pthread_mutex_t ref_share_lock = PTHREAD_MUTEX_INITIALIZER;
static ref_shared *ref_share_list; /* newest first; all below under the lock */
static size_t ref_share_idle;      /* bytes of the pyramids with refs == 0 */
static unsigned long long ref_share_clock;

/* Frees idle pyramids, the longest idle first, until they fit the bound. */
static void ref_share_trim(void)
{
    while (ref_share_idle > REF_SHARE_IDLE_BYTES) {
        ref_shared **oldest = NULL;
        for (ref_shared **p = &ref_share_list; *p; p = &(*p)->next)
            if ((*p)->refs == 0 && (!oldest || (*p)->idle_since < (*oldest)->idle_since))
                oldest = p;
        ref_shared *e = *oldest;
        *oldest = e->next;
        ref_share_idle -= ref_share_bytes(e);
        ref_free_huge(e->mip.owned8, e->mip.owned8_bytes);
        free(e);
    }
}

static void ref_share_release(ref_shared *e)
{
    if (--e->refs == 0) {
        ref_share_idle += ref_share_bytes(e);
        e->idle_since = ++ref_share_clock;
        ref_share_trim();
    }
}

/* The newest shared pyramid of t's path and size, held, or NULL. */
static ref_shared *ref_share_find(const gib_texture *t)
{
    pthread_mutex_lock(&ref_share_lock);
    ref_shared *e = ref_share_list;
    while (e && !(e->mip.w[0] == t->width && e->mip.h[0] == t->height &&
                  strcmp(e->path, t->path) == 0))
        e = e->next;
    if (e && e->refs++ == 0)
        ref_share_idle -= ref_share_bytes(e);
    pthread_mutex_unlock(&ref_share_lock);
    return e;
}

int ref_share_take(ref_mip *m, const gib_texture *t)
{
    ref_shared *e = ref_share_find(t);
    if (!e)
        return 0;
    if (ref_mip_same8(t, e->mip.lv8[0])) {
        *m = e->mip;
        return 1;
    }
    pthread_mutex_lock(&ref_share_lock);
    ref_share_release(e);
    pthread_mutex_unlock(&ref_share_lock);
    return 0;
}

void ref_share_put(const ref_mip *m, const char *path)
{
    ref_shared *e = malloc(sizeof *e);
    if (!e)
        return;
    snprintf(e->path, sizeof e->path, "%s", path);
    e->mip = *m;
    e->refs = 1;
    pthread_mutex_lock(&ref_share_lock);
    e->next = ref_share_list;
    ref_share_list = e;
    pthread_mutex_unlock(&ref_share_lock);
}

int ref_share_drop(const uint32_t *p8)
{
    pthread_mutex_lock(&ref_share_lock);
    ref_shared *e = ref_share_list;
    while (e && e->mip.owned8 != p8)
        e = e->next;
    if (e)
        ref_share_release(e);
    pthread_mutex_unlock(&ref_share_lock);
    return e != NULL;
}

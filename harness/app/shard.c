#include "shard.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/base/hash.h"

int gib_shard_parse(const char *opt, const char *s, gib_shard *out, gib_error *err)
{
    char *end;
    long i = strtol(s, &end, 10);
    if (end == s || *end != '/')
        return gib_fail(err, "%s expects I/N (this machine's share I of N shards, e.g. 2/8), got '%s'",
                        opt, s);
    const char *ns = end + 1;
    long n = strtol(ns, &end, 10);
    if (end == ns || *end)
        return gib_fail(err, "%s expects I/N (e.g. 2/8), got '%s'", opt, s);
    if (n < 1 || n > GIB_SHARD_MAX)
        return gib_fail(err, "%s '%s': the shard count N must be 1 to %d", opt, s, GIB_SHARD_MAX);
    if (i < 1 || i > n)
        return gib_fail(err, "%s '%s': the shard index I must be 1 to N (%ld)", opt, s, n);
    out->index = (int)i;
    out->count = (int)n;
    return 0;
}

/* Runs that share a (scene, size, instant) share their references and the scene's upload. */
static int same_group(const gib_matrix_run *a, const gib_matrix_run *b)
{
    return !strcmp(a->scene, b->scene) && a->width == b->width && a->height == b->height &&
           a->time == b->time;
}

typedef struct unit {
    int first;   /* first run of the unit: ties are broken by it, so the split is deterministic */
    int group;   /* group id; -1 = the unit is the single run `first` */
    double cost;
} unit;

static int by_cost_desc(const void *pa, const void *pb)
{
    const unit *a = pa, *b = pb;
    if (a->cost != b->cost)
        return a->cost > b->cost ? -1 : 1;
    return a->first - b->first;
}

/* The split: runs are grouped by (scene, size, instant), so a group's references are rendered, and
 * its scene loaded, on one machine only. A run's cost is estimated as its pixel count: the
 * reference (path tracing, per pixel) dominates on the machines this harness targets, and the
 * technique's frames scale with pixels too; the estimate needs nothing but the matrix. Groups
 * costlier than a fair share (total / N) are split into single runs, so a matrix with one scene
 * and one size still spreads. The units then go, costliest first, to the least-loaded shard
 * (longest-processing-time-first: within 4/3 of the best possible makespan). */
void gib_shard_assign(const gib_matrix *m, int count, int *owner)
{
    int n = m->run_count;
    if (count <= 1) {
        for (int j = 0; j < n; j++)
            owner[j] = 1;
        return;
    }
    int *group = malloc((size_t)n * sizeof *group);
    double *gcost = calloc((size_t)n, sizeof *gcost);
    unit *units = malloc((size_t)n * sizeof *units);
    double *load = calloc((size_t)count, sizeof *load);
    if (!group || !gcost || !units || !load) { /* round robin: still deterministic and balanced */
        for (int j = 0; j < n; j++)
            owner[j] = j % count + 1;
        free(group), free(gcost), free(units), free(load);
        return;
    }
    int ngroups = 0;
    double total = 0;
    for (int j = 0; j < n; j++) {
        int g = -1;
        for (int k = 0; k < j && g < 0; k++)
            if (same_group(&m->runs[k], &m->runs[j]))
                g = group[k];
        group[j] = g >= 0 ? g : ngroups++;
        double c = (double)m->runs[j].width * m->runs[j].height;
        gcost[group[j]] += c;
        total += c;
    }
    int nunits = 0;
    for (int j = 0; j < n; j++) {
        int g = group[j];
        int first_of_group = 1;
        for (int k = 0; k < j && first_of_group; k++)
            first_of_group = group[k] != g;
        if (gcost[g] > total / count)
            units[nunits++] = (unit){j, -1, (double)m->runs[j].width * m->runs[j].height};
        else if (first_of_group)
            units[nunits++] = (unit){j, g, gcost[g]};
    }
    qsort(units, (size_t)nunits, sizeof *units, by_cost_desc);
    for (int u = 0; u < nunits; u++) {
        int best = 0;
        for (int s = 1; s < count; s++)
            if (load[s] < load[best])
                best = s;
        load[best] += units[u].cost;
        if (units[u].group < 0)
            owner[units[u].first] = best + 1;
        else
            for (int j = 0; j < n; j++)
                if (group[j] == units[u].group)
                    owner[j] = best + 1;
    }
    free(group), free(gcost), free(units), free(load);
}

void gib_shard_order(const gib_matrix *m, int *ordinal)
{
    int n = m->run_count, next = 0;
    for (int j = 0; j < n; j++)
        ordinal[j] = -1;
    for (int i = 0; i < n; i++) {
        if (ordinal[i] >= 0)
            continue;
        for (int j = i; j < n; j++)
            if (ordinal[j] < 0 && !strcmp(m->runs[j].scene, m->runs[i].scene))
                ordinal[j] = next++;
    }
}

uint64_t gib_matrix_fingerprint(const gib_matrix *m)
{
    uint64_t h = gib_hash_str(GIB_HASH_INIT, m->name);
    h = gib_hash_str(h, m->profile);
    h = gib_hash_u64(h, (uint64_t)m->camera);
    h = gib_hash_u64(h, (uint64_t)m->frames);
    h = gib_hash_u64(h, (uint64_t)m->warmup);
    h = gib_hash_u64(h, (uint64_t)m->ref_spp_growth);
    if (m->sequence > 1) /* a sequence matrix's rows differ: its shards must agree on it */
        h = gib_hash_u64(h, (uint64_t)m->sequence);
    h = gib_hash_bytes(h, &m->dt, sizeof m->dt);
    for (int c = 0; c < GIB_MATRIX_MAX_COMPONENTS; c++)
        h = gib_hash_u64(h, (uint64_t)m->ref_spp[c]);
    for (int j = 0; j < m->run_count; j++) {
        const gib_matrix_run *r = &m->runs[j];
        h = gib_hash_str(h, r->scene);
        h = gib_hash_str(h, r->technique->name);
        h = gib_hash_str(h, r->params_key);
        h = gib_hash_u64(h, (uint64_t)r->width);
        h = gib_hash_u64(h, (uint64_t)r->height);
        h = gib_hash_bytes(h, &r->time, sizeof r->time);
    }
    return h;
}

/* gibench technique `ispm_caustics`: what tests read of an instance (the photons of its last frame). */
#ifndef GIB_ISPM_CAUSTICS_H
#define GIB_ISPM_CAUSTICS_H

/* One photon as caustics.glsl stores it. */
typedef struct ispm_photon {
    float origin[4]; /* xyz on the specular surface, w distance from the light */
    float dir[4];    /* xyz direction, w t_min */
    float flux[4];   /* rgb flux (W), w footprint at the light */
    float hit[4];    /* xyz second hit, w splat radius (0: none) */
    float hit_n[4];  /* xyz receiver normal facing the photon, w cos of incidence */
} ispm_photon;

/* The photons of the instance's last frame (malloc'd into *out; the caller frees). Returns their
 * count, or -1 when out of memory. */
int ispm_caustics_read_photons(void *self, ispm_photon **out);

#endif

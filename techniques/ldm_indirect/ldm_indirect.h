/* gibench technique `ldm_indirect`: its flux audit.
 *
 * With the audit on, every frame counts where the light's flux goes (W, per colour channel, summed
 * over lights): what the light's view emits, what reaches the first surfaces and leaves them, what
 * the secondary photons carry and why each is discarded, what is stored, and what the splats
 * deposit on the surfaces the camera sees (irradiance times each pixel's patch of surface). The
 * audit is off by default (it adds a read-back and a second splat pass per frame); it is turned on
 * by ldm_indirect_audit_enable(1) or by the environment variable GIBENCH_LDM_AUDIT (any value but
 * "0"), for instances created afterwards; the environment variable also logs the last frame's
 * audit to stderr when the run ends (the status hook). */
#ifndef GIB_LDM_INDIRECT_H
#define GIB_LDM_INDIRECT_H

#include <stddef.h>

/* The order of techniques/ldm_indirect/audit.glsl; SPLATTED is measured by the host. */
typedef enum ldm_audit_fate {
    LDM_AUDIT_EMITTED,       /* I(d) dw over every texel of the light's view */
    LDM_AUDIT_NO_SURFACE,    /* texels where the light sees nothing */
    LDM_AUDIT_BACK_FACING,   /* primary photons at a surface facing away (or zero flux) */
    LDM_AUDIT_REFLECTED,     /* Phi1 rho1: what the first surfaces reflect */
    LDM_AUDIT_CARRIED,       /* secondary photons' flux over all 2N directions */
    LDM_AUDIT_GRAZING,       /* |n1 . v| < 1e-4: not traced */
    LDM_AUDIT_MISS,          /* the LDM trace found nothing (left the scene) */
    LDM_AUDIT_BEHIND_CAMERA, /* x2 behind the camera */
    LDM_AUDIT_OFF_SCREEN,    /* x2 outside the image (Sec. 4.2, step 4b) */
    LDM_AUDIT_ON_SKY,        /* x2 where the camera sees no surface */
    LDM_AUDIT_OCCLUDED,      /* x2 behind the surface the camera sees (Sec. 4.2, step 4b) */
    LDM_AUDIT_IN_FRONT,      /* x2 in front of the surface the camera sees: the match failed */
    LDM_AUDIT_BACK_SIDE,     /* x2 on the side of the surface the camera does not see */
    LDM_AUDIT_DEGENERATE,    /* a footprint of no area or not finite */
    LDM_AUDIT_OVERFLOW,      /* no room in the photon buffer */
    LDM_AUDIT_STORED,        /* stored for splatting */
    LDM_AUDIT_SPLATTED,      /* deposited by the splats on the surfaces the camera sees */
    LDM_AUDIT_FATES
} ldm_audit_fate;

typedef struct ldm_indirect_audit {
    double flux[LDM_AUDIT_FATES][3]; /* W per channel, one frame */
    int valid;                       /* 0 until an audited frame was rendered */
} ldm_indirect_audit;

/* Turns the audit on or off for ldm_indirect instances created afterwards. */
void ldm_indirect_audit_enable(int on);
/* The audit of the last audited frame rendered by any instance in this process. Returns 0 and
 * fills *out, or -1 when there is none. */
int ldm_indirect_audit_last(ldm_indirect_audit *out);
/* The fate's name ("off_screen"). */
const char *ldm_indirect_audit_name(int fate);
/* One line: every fate's flux (the mean of the channels) and its fraction of EMITTED. */
void ldm_indirect_audit_format(const ldm_indirect_audit *a, char *buf, size_t size);

#endif

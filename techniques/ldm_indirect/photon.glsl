// The photon record shared by the tracing and splatting passes of ldm_indirect.
#include "ldm_indirect/ldm_indirect_slots.h"
struct Photon {
    vec4 position; // xyz: where the secondary photon landed (x2)
    vec4 du;       // xyz: positional differential D_u x2
    vec4 dv;       // xyz: positional differential D_v x2
    vec4 flux;     // rgb: radiant flux Phi_p (W)
};
// Indirect draw command for the splat pass: count is the photon counter.
struct DrawCommand {
    uint count;
    uint instance_count;
    uint first;
    uint base_instance;
};

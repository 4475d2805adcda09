// Fates of the flux in the photon trace's audit (the order of enum ldm_audit_fate in
// ldm_indirect.h). Primary photons: EMITTED = NO_SURFACE + BACK_FACING + what reaches x1, of which
// REFLECTED = flux * rho1 leaves x1. Secondary photons: CARRIED (their flux over all 2N directions)
// = GRAZING + MISS + BEHIND_CAMERA + OFF_SCREEN + ON_SKY + OCCLUDED + IN_FRONT + BACK_SIDE +
// DEGENERATE + OVERFLOW + STORED.
const int AUDIT_EMITTED = 0;
const int AUDIT_NO_SURFACE = 1;
const int AUDIT_BACK_FACING = 2;
const int AUDIT_REFLECTED = 3;
const int AUDIT_CARRIED = 4;
const int AUDIT_GRAZING = 5;
const int AUDIT_MISS = 6;
const int AUDIT_BEHIND_CAMERA = 7;
const int AUDIT_OFF_SCREEN = 8;
const int AUDIT_ON_SKY = 9;
const int AUDIT_OCCLUDED = 10;
const int AUDIT_IN_FRONT = 11;
const int AUDIT_BACK_SIDE = 12;
const int AUDIT_DEGENERATE = 13;
const int AUDIT_OVERFLOW = 14;
const int AUDIT_STORED = 15;
const int AUDIT_COUNT = 16;

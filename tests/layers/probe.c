/* One header included with a layer's include directories only (tests/layers/CMakeLists.txt). */
#include PROBE_HEADER

int gib_layer_probe(void);
int gib_layer_probe(void) { return 0; }

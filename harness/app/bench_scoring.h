/* gibench bench scoring (bench_scoring.c) and what it shares with bench reference (cmd_bench.c). */
#ifndef GIB_BENCH_SCORING_H
#define GIB_BENCH_SCORING_H

#include <stddef.h>

/* `gibench bench scoring ...`: argv[0] is "scoring". Returns the exit status. */
int gib_bench_scoring(int argc, char **argv);

/* The CPU's model name and the system ("AMD EPYC / Linux x86_64"), CSV-safe. */
void gib_bench_machine_name(char *out, size_t len);

#endif

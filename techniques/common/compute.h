/* gibench — the dispatch side of the compute passes' work-group sizes (groups_shared.h). */
#ifndef GIB_COMPUTE_H
#define GIB_COMPUTE_H

#include "techniques/common/groups_shared.h"

/* The work groups of `size` invocations that cover n items: ceil(n / size). */
static inline unsigned gib_groups(unsigned n, unsigned size)
{
    return (n + size - 1) / size;
}

#endif

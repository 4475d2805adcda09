/* gibench — command-line entry point. */
#include <stdio.h>

int main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "gibench: usage: gibench list|render|reference|compare|run ...\n");
    return 2;
}

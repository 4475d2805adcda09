/* gibench — command-line entry point: dispatches to the subcommands in harness/app/cmd_*.c. */
#include <stdio.h>
#include <string.h>

#include "app.h"
#include "schema.h"

static const char usage[] =
    "gibench — benchmark real-time global illumination against path-traced references\n"
    "\n"
    "usage: gibench COMMAND [options]   (gibench COMMAND --help for each)\n"
    "\n"
    "  list                         techniques with parameters and defaults, scenes with features\n"
    "  render    --scene S --technique T [--param k=v]... --size WxH --out DIR\n"
    "  reference --scene S --component C --spp N --size WxH (--out F.exr | --cache DIR)\n"
    "  compare   REF.exr TEST.exr [--exposure E] [--json] [--map F.png] [--fail ...]\n"
    "  export    SCENE DIR [--camera NAME|INDEX] [--time T] [--size WxH]   the scene as glTF\n"
    "                                   2.0 + job.json, as an external renderer gets it\n"
    "  run       MATRIX [--profile quick|paper] [--out DIR] [--shard I/N]\n"
    "  merge     SHARD_DIR... --out DIR      the shards' CSVs as one run's table\n"
    "  bench     reference [--scene S] [--size WxH] [--out F.csv]   ray throughput\n"
    "  history   [--metric M] [--scene S] [--technique T] [--find] [--plot F.png]   results history\n"
    "  describe  [--out FILE]           what the binary knows, as JSON: the tables' columns, the\n"
    "                                   techniques (outputs, passes, parameters, presets), the\n"
    "                                   statuses, the references' bindings, the revision (alias: schema)\n"
    "  check-technique NAME [--no-gl]   one technique (built-in or plugin) against the contract:\n"
    "                                   descriptor checks, then create/render/destroy; PASS/FAIL\n"
    "\n"
    "Every command takes --plugin PATH (repeatable): a technique plugin, a shared library\n"
    "exporting " GIB_PLUGIN_ENTRY " (docs/adding-a-technique.md, \"As a plugin\"); so does\n"
    "$GIBENCH_PLUGINS, paths joined by ':'.\n"
    "\n"
    "Scene data (Crytek Sponza, Sibenik, ...) is found through $GIBENCH_SCENES\n"
    "(default ../shared/scenes beside the project); the procedural scenes need none.\n";

int main(int argc, char **argv)
{
    gib_error err;
    if (gib_plugins_from_args(&argc, argv, &err) < 0) {
        fprintf(stderr, "gibench: %s\n", err.msg);
        return 2;
    }
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") ||
        !strcmp(argv[1], "help")) {
        fputs(usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "list"))
        return gib_cmd_list(argc - 1, argv + 1);
    if (!strcmp(cmd, "render"))
        return gib_cmd_render(argc - 1, argv + 1);
    if (!strcmp(cmd, "reference"))
        return gib_cmd_reference(argc - 1, argv + 1);
    if (!strcmp(cmd, "compare"))
        return gib_cmd_compare(argc - 1, argv + 1);
    if (!strcmp(cmd, "export"))
        return gib_cmd_export(argc - 1, argv + 1);
    if (!strcmp(cmd, "run"))
        return gib_cmd_run(argc - 1, argv + 1);
    if (!strcmp(cmd, "merge"))
        return gib_cmd_merge(argc - 1, argv + 1);
    if (!strcmp(cmd, "bench"))
        return gib_cmd_bench(argc - 1, argv + 1);
    if (!strcmp(cmd, "history"))
        return gib_cmd_history(argc - 1, argv + 1);
    if (!strcmp(cmd, "check-technique"))
        return gib_cmd_check(argc - 1, argv + 1);
    if (!strcmp(cmd, "describe") || !strcmp(cmd, "schema"))
        return gib_cmd_schema(argc - 1, argv + 1);
    fprintf(stderr, "gibench: unknown command '%s'\n\n%s", cmd, usage);
    return 2;
}

#!/usr/bin/env python3
"""Sets the papers' own numbers (../shared/paper-values/*.csv, copied into results/paper/) beside
ours: for every row of a paper table that gibench reproduces, the run of ours that matches its
settings best, with our time, memory and error, and the renderer it ran on. One module per paper:

- ldm_tables.py: the LDM paper's figures, RESULTS_DIR/ldm_figures_vs_ours.csv;
- lrsm_tables.py: the LRSM paper's Tables 2 and 3, Figure 7 and SPONZA DRAGON, RESULTS_DIR/
  lrsm_table2.csv, lrsm_table3.csv, lrsm_fig7.csv and lrsm_dynamic.csv, with a row per claim;
- thesis_tables.py: the thesis' (Le 2014) Tables 4.1-4.5, RESULTS_DIR/thesis_tables.csv.

usage: python3 -m reporting.paper_tables RESULTS_DIR [--paper-values DIR]

"Best match" is the run with the paper's settings when the profile ran them (profile `paper`), else
the run closest to them: the `our_settings` column says which, so a reader never takes a
quick-profile number for the paper's configuration. The runs are read through schema.py.
"""
import argparse
import os
import shutil
import sys

from reporting.ldm_tables import ldm_table  # noqa: E402
from reporting.lrsm_tables import lrsm_tables  # noqa: E402
from reporting.thesis_tables import thesis_table  # noqa: E402

from reporting.schema import ROOT  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("--paper-values", default=os.environ.get("GIBENCH_PAPER_VALUES",
                                                             os.path.join(ROOT, "..", "shared", "paper-values")))
    a = ap.parse_args()
    paper_dir = os.path.join(a.results, "paper")
    os.makedirs(paper_dir, exist_ok=True)
    # Keep a copy of the papers' numbers with the results, so the comparison reads on its own.
    if os.path.isdir(a.paper_values):
        for name in os.listdir(a.paper_values):
            if name.endswith(".csv"):
                shutil.copy(os.path.join(a.paper_values, name), os.path.join(paper_dir, name))
    lrsm_tables(a.results, paper_dir)
    thesis_table(a.results, paper_dir)
    ldm_table(a.results, paper_dir, a.paper_values)


if __name__ == "__main__":
    sys.exit(main())

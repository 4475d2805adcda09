"""gibench's results, read and reported: one package for every script that reads the tables
gibench writes (schema: the columns, techniques, passes and statuses the binary exports; the
papers' tables beside ours; the claims; the answer; the energy audit; plots; the report in Markdown
and HTML), and for the studies and benchmarks that drive gibench and write tables of their own.

Run a module from the repository's root as `PYTHONPATH=harness python3 -m reporting.<module>`
(the Makefile's targets do); source_hash.py also runs as a plain script (the build calls it)."""

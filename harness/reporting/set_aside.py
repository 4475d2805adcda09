"""Sets one profile's rows of the given matrices aside before a fresh run of that profile.

`gibench run` skips the runs its tables already hold, so `make reproduce` moves the rows of the
profile it reruns to RESULTS/previous/ (runs and passes tables alike) and keeps every other
profile's rows where they are: a quick smoke reproduction never discards the committed
papers'-settings rows. A table whose header the run would change is restarted by gibench itself,
which moves the whole table aside.

usage: python3 -m reporting.set_aside RESULTS PROFILE MATRIX_FILE...
"""
import csv
import os
import sys


def split_table(path, profile, previous):
    """Moves the rows of `profile` from path to previous/<name>; returns how many moved."""
    if not os.path.exists(path):
        return 0
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        rows = list(reader)
    if not header or "profile" not in header:
        return 0
    col = header.index("profile")
    mine = [r for r in rows if len(r) > col and r[col] == profile]
    if not mine:
        return 0
    keep = [r for r in rows if not (len(r) > col and r[col] == profile)]
    os.makedirs(previous, exist_ok=True)
    for target, body in ((os.path.join(previous, os.path.basename(path)), mine), (path, keep)):
        tmp = target + ".tmp"
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(header)
            w.writerows(body)
        os.replace(tmp, target)
    return len(mine)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    results, profile = sys.argv[1], sys.argv[2]
    previous = os.path.join(results, "previous")
    moved = 0
    for matrix in sys.argv[3:]:
        name = os.path.splitext(os.path.basename(matrix))[0]
        for table in (name + ".csv", name + "_passes.csv"):
            moved += split_table(os.path.join(results, table), profile, previous)
    print(f"set_aside.py: {moved} rows of profile {profile} moved to {previous}/")


if __name__ == "__main__":
    main()

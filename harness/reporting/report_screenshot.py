#!/usr/bin/env python3
"""The report's first screen as a PNG (docs/report.png, the README's picture), taken by headless
Chromium from the page `make report` just wrote, so the picture never shows older numbers than the
committed CSVs. Without Chromium it says so and leaves the old picture.

usage: python3 -m reporting.report_screenshot PAGE OUT_PNG"""
import os
import shutil
import subprocess
import sys


def find_chromium():
    """The Chromium (or Chrome) on PATH, or None."""
    return next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")
                 if shutil.which(n)), None)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: python3 -m reporting.report_screenshot PAGE OUT_PNG")
    page, out = (os.path.abspath(p) for p in sys.argv[1:])
    exe = find_chromium()
    if not exe:
        print(f"report_screenshot: no Chromium here: {out} not refreshed", file=sys.stderr)
        return
    if not os.path.exists(page):
        sys.exit(f"report_screenshot: {page} not found (run `make report` first)")
    tmp = out + ".tmp.png"
    subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                    "--allow-file-access-from-files", "--virtual-time-budget=10000",
                    "--window-size=1280,900", "--screenshot=" + tmp, "file://" + page],
                   check=True, capture_output=True, timeout=120)
    os.replace(tmp, out)
    print(out)


if __name__ == "__main__":
    main()

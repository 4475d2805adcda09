"""The gallery's images as the repository ships them.

A run writes its images (PNG previews, error and FLIP maps) under results/images/, which is not
committed: on a fresh clone, or on the repository's web page, a report that links there shows no
picture. The gallery's cells are therefore copied, as lossy WebP (quality 90: ~43 dB PSNR against
the PNG, a few kB a cell), to results/gallery/ under the same relative path, and the report links
the copy. The numbers never come from these copies: every error is computed from the EXRs.

shipped(results, path) is the copy of an image under results/images (written or refreshed when the
PNG is here and newer, kept as committed where it is not); prune(results) removes the copies that
the report written last no longer shows, so the folder holds the current gallery only."""
import os
import subprocess

QUALITY = 90
FOLDER = "gallery"
_shown = set()


def copy_path(results, path):
    """Where the shipped copy of `path` (a file under results/images) lives."""
    relative = os.path.relpath(path, os.path.join(results, "images"))
    return os.path.join(results, FOLDER, os.path.splitext(relative)[0] + ".webp")


def shipped(results, path):
    """The shipped copy of an image under results/images where there is one (written from the PNG
    when that is here and newer), else path itself (None stays None)."""
    if not path or os.path.relpath(path, os.path.join(results, "images")).startswith(".."):
        return path
    out = copy_path(results, path)
    if os.path.exists(path) and (not os.path.exists(out) or
                                 os.path.getmtime(out) < os.path.getmtime(path)):
        os.makedirs(os.path.dirname(out), exist_ok=True)
        subprocess.run(["oiiotool", path, "--attrib", "compression", "webp:%d" % QUALITY,
                        "-o", out + ".tmp.webp"], check=True)
        os.replace(out + ".tmp.webp", out)
    if os.path.exists(out):
        _shown.add(os.path.abspath(out))
        return out
    return path


def prune(results):
    """Removes the copies under results/gallery that no gallery cell asked for since the module
    was loaded, and the folders left empty."""
    top = os.path.join(results, FOLDER)
    for d, _, files in os.walk(top, topdown=False):
        for f in files:
            if os.path.abspath(os.path.join(d, f)) not in _shown:
                os.remove(os.path.join(d, f))
        if d != top and not os.listdir(d):
            os.rmdir(d)

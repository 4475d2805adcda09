#!/usr/bin/env python3
"""An external renderer for gibench, in plain Python 3 (no numpy): reads the job gibench writes
(job.json beside scene.gltf + scene.bin; README.md here), renders the `direct` component of
Lambertian surfaces lit by point, spot and directional lights and the sky WITHOUT shadows, and
writes direct.exr (uncompressed float RGB, written below) and timings.json.

It ray-casts every pixel centre as gibench's camera does (a triangle's pixels found from its
projected bounds, then an exact ray-triangle test), so on a scene where nothing casts a shadow
(the furnace: a point light inside a closed sphere) it is the reference's answer to float
precision. Elsewhere it is a deliberately simple method (no shadows, no specular, no textures).

    python3 render.py [--mode MODE] JOB.json      (gibench appends the job's path)

--mode is for gibench's tests of failures (tests/external): fail (exit 1 with a message on
stderr), nothing (exit 0, write nothing), wrongsize (half the size), nan (NaN pixels), sleep
(sleep 30 s, past the test's timeout)."""
import json
import math
import os
import struct
import sys
import time


def write_exr(path, width, height, rgb):
    """An uncompressed scanline OpenEXR file, channels B, G, R as 32-bit floats (rgb: a flat list
    of width * height * 3 floats, row 0 on top)."""
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) +
              attr("channels", "chlist", chlist) + attr("compression", "compression", b"\0") +
              attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box) +
              attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    line_bytes = width * 3 * 4
    first = len(header) + 8 * height
    offsets = b"".join(struct.pack("<Q", first + y * (8 + line_bytes)) for y in range(height))
    lines = []
    for y in range(height):
        row = rgb[y * width * 3:(y + 1) * width * 3]
        data = b"".join(struct.pack("<%df" % width, *row[c::3]) for c in (2, 1, 0))
        lines.append(struct.pack("<ii", y, len(data)) + data)
    with open(path, "wb") as f:
        f.write(header + offsets + b"".join(lines))


def load_gltf(job_dir, gltf_name):
    """Positions, normals and per-material triangle lists from gibench's glTF (one shared vertex
    buffer; one mesh a material, its material's gibench index in extras)."""
    with open(os.path.join(job_dir, gltf_name)) as f:
        g = json.load(f)
    with open(os.path.join(job_dir, g["buffers"][0]["uri"]), "rb") as f:
        blob = f.read()

    def accessor(i, width, fmt):
        a = g["accessors"][i]
        view = g["bufferViews"][a["bufferView"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        n = a["count"] * width
        vals = struct.unpack_from("<%d%s" % (n, fmt), blob, start)
        return [vals[k:k + width] for k in range(0, n, width)] if width > 1 else list(vals)

    groups = []
    for mesh in g["meshes"]:
        for prim in mesh["primitives"]:
            pos = accessor(prim["attributes"]["POSITION"], 3, "f")
            nrm = accessor(prim["attributes"]["NORMAL"], 3, "f")
            idx = accessor(prim["indices"], 1, "I")
            mat = g["materials"][prim["material"]]["extras"]["gibench_material"]
            groups.append((mat, idx))
    return pos, nrm, groups


def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def clip_near(cam_pts, near=1e-5):
    """The triangle's polygon (camera-space x, y, z) with z >= near (Sutherland-Hodgman)."""
    out = []
    for i in range(3):
        a, b = cam_pts[i], cam_pts[(i + 1) % 3]
        if a[2] >= near:
            out.append(a)
        if (a[2] >= near) != (b[2] >= near):
            t = (near - a[2]) / (b[2] - a[2])
            out.append(tuple(a[k] + t * (b[k] - a[k]) for k in range(3)))
    return out


def cast(job, pos, groups):
    """Per pixel: the nearest hit (t, triangle's three indices, u, v, material) or None."""
    cam = job["camera"]
    w, h = cam["width"], cam["height"]
    eye, look, up, right = cam["position"], cam["look"], cam["up"], cam["right"]
    th = math.tan(math.radians(cam["vfov_deg"]) / 2)
    aspect = w / h
    dirs = [None] * (w * h)
    for y in range(h):
        sy = (1 - 2 * (y + 0.5) / h) * th
        for x in range(w):
            sx = (2 * (x + 0.5) / w - 1) * th * aspect
            dirs[y * w + x] = tuple(look[k] + sx * right[k] + sy * up[k] for k in range(3))
    best = [math.inf] * (w * h)
    hits = [None] * (w * h)
    cam_v = [(dot(sub(p, eye), right), dot(sub(p, eye), up), dot(sub(p, eye), look)) for p in pos]
    tested = 0
    for mat, idx in groups:
        for k in range(0, len(idx), 3):
            tri = idx[k:k + 3]
            poly = clip_near([cam_v[i] for i in tri])
            if not poly:
                continue
            xs = [((q[0] / (q[2] * th * aspect)) + 1) * w / 2 - 0.5 for q in poly]
            ys = [(1 - q[1] / (q[2] * th)) * h / 2 - 0.5 for q in poly]
            x0, x1 = max(0, math.floor(min(xs)) - 1), min(w - 1, math.ceil(max(xs)) + 1)
            y0, y1 = max(0, math.floor(min(ys)) - 1), min(h - 1, math.ceil(max(ys)) + 1)
            if x0 > x1 or y0 > y1:
                continue
            p0 = pos[tri[0]]
            e1, e2 = sub(pos[tri[1]], p0), sub(pos[tri[2]], p0)
            s = sub(eye, p0)
            q = cross(s, e1)
            for py in range(y0, y1 + 1):
                for px in range(x0, x1 + 1):
                    d = dirs[py * w + px]
                    tested += 1
                    pv = cross(d, e2)
                    det = dot(e1, pv)
                    if abs(det) < 1e-20:
                        continue
                    inv = 1.0 / det
                    u = dot(s, pv) * inv
                    v = dot(d, q) * inv
                    if u < 0 or v < 0 or u + v > 1:
                        continue
                    t = dot(e2, q) * inv
                    if 0 < t < best[py * w + px]:
                        best[py * w + px] = t
                        hits[py * w + px] = (t, tri, u, v, mat)
    return dirs, hits, tested


def light_at(light, p):
    """(wi, E) as gibench's gib_light_eval: E = I falloff / r^2, or the irradiance."""
    if light["type"] == "directional":
        d = light["direction"]
        return (-d[0], -d[1], -d[2]), light["intensity"]
    to = sub(light["position"], p)
    r2 = dot(to, to)
    r = math.sqrt(r2)
    wi = (to[0] / r, to[1] / r, to[2] / r)
    fall = 1.0
    if light["type"] == "spot":
        c = -dot(wi, light["direction"])
        if c < math.cos(math.radians(light["spot_outer_deg"])):
            return wi, (0.0, 0.0, 0.0)
        fall = max(c, 0.0) ** light["spot_exponent"]
    return wi, tuple(i * fall / r2 for i in light["intensity"])


def shade(job, nrm, dirs, hits):
    """Unshadowed Lambertian direct light (and the sky's) at each pixel's hit."""
    eye = job["camera"]["position"]
    mats = job["materials"]
    sky = job["scene"]["sky"]
    out = [0.0] * (len(hits) * 3)
    for i, hit in enumerate(hits):
        if hit is None:
            continue
        t, tri, u, v, mat = hit
        d = dirs[i]
        p = tuple(eye[k] + t * d[k] for k in range(3))
        n = tuple((1 - u - v) * nrm[tri[0]][k] + u * nrm[tri[1]][k] + v * nrm[tri[2]][k]
                  for k in range(3))
        ln = math.sqrt(dot(n, n))
        n = tuple(c / ln for c in n)
        m = mats[mat]
        if dot(n, d) > 0 and m["two_sided"]:
            n = (-n[0], -n[1], -n[2])
        rho = m["albedo"]
        for c in range(3):
            out[3 * i + c] = rho[c] * sky[c]
        for light in job["lights"]:
            wi, e = light_at(light, p)
            cos = dot(n, wi)
            if cos > 0:
                for c in range(3):
                    out[3 * i + c] += rho[c] / math.pi * e[c] * cos
    return out


def main():
    args = sys.argv[1:]
    mode = "ok"
    if args and args[0] == "--mode":
        mode, args = args[1], args[2:]
    job_path = args[-1] if args else os.environ["GIBENCH_JOB"]
    with open(job_path) as f:
        job = json.load(f)
    w, h = job["camera"]["width"], job["camera"]["height"]
    if mode == "fail":
        print("example renderer: failing on purpose (--mode fail)", file=sys.stderr)
        return 1
    if mode == "sleep":
        time.sleep(30)
    if mode == "nothing":
        return 0
    for comp in job["components"]:
        if comp["name"] != "direct":
            print(f"example renderer: component '{comp['name']}' is not supported (direct only)",
                  file=sys.stderr)
            return 2
    if mode in ("wrongsize", "nan"):
        ww, hh = (w // 2, h // 2) if mode == "wrongsize" else (w, h)
        img = [float("nan") if mode == "nan" and k < 30 else 0.1 for k in range(ww * hh * 3)]
        for comp in job["components"]:
            write_exr(comp["output"], ww, hh, img)
        return 0
    job_dir = os.path.dirname(os.path.abspath(job_path))
    pos, nrm, groups = load_gltf(job_dir, job["scene"]["gltf"])
    t0 = time.perf_counter()
    dirs, hits, tested = cast(job, pos, groups)
    t1 = time.perf_counter()
    img = shade(job, nrm, dirs, hits)
    t2 = time.perf_counter()
    for comp in job["components"]:
        write_exr(comp["output"], w, h, img)
    timings = {"gpu_ms": [(t2 - t0) * 1e3],
               "passes": {"cast": (t1 - t0) * 1e3, "shade": (t2 - t1) * 1e3},
               "memory_bytes": (len(pos) * 6 + w * h * 7) * 8,
               "renderer": "example_renderer.py (CPU, Python %d.%d)" % sys.version_info[:2],
               "counters": "ray_triangle_tests=%d" % tested}
    with open(job["timings"], "w") as f:
        json.dump(timings, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Renders a gibench .scene with Blender Cycles, for the comparison in bench_cycles.py.

Run by Blender, headless:

    blender -b --factory-startup -P cycles_scene.py -- JOB.json

JOB.json names the scene file, the image size, spp, the path length, the seeds and the folder to
write into; this script writes seed_<s>.exr per seed (linear RGB, row 0 on top) and result.json
(each render's seconds, the Cycles settings in force, Blender's version and build).

What it builds from the .scene file (and refuses anything else, so that the two renderers never
see different scenes in silence): procedural `room` and `box` meshes with size and translate,
Lambertian albedos (a Diffuse BSDF of that colour, roughness 0), point lights, the first camera.
gibench is y-up and Blender z-up: a point (x, y, z) becomes (x, -z, y), a proper rotation, so
winding and handedness are kept.

Settings, each matched to gibench's `full` or made neutral:
  - CPU, the threads asked for, no denoising, no adaptive sampling (every pixel takes spp);
  - path length: gibench counts surface vertices (max_depth 8: at most 8), Cycles bounces after
    the first hit (max_bounces 0 is direct light alone), so max_bounces = max_depth - 1 for every
    bounce type;
  - no clamping (Cycles' default clamps indirect samples at 10: a bias), no glossy filter;
  - the pixel filter 0.01 px wide (Blackman-Harris; Cycles' box filter is always 1 px wide,
    whatever the width says): gibench samples the pixel centre, Cycles' default filter 1.5 px
    wide would average over neighbours and add the edges' variance;
  - a point light of radius 0 (a delta, as gibench's) whose power P = 4 pi I gives intensity I in
    W/sr (Cycles' point light emits P / (4 pi) per steradian); the world black;
  - the sampling pattern, Russian roulette (min_light_bounces) and light threshold are left at
    Cycles' defaults (its own estimator), and recorded. """
import configparser
import json
import math
import sys
import time

import bpy
import mathutils


def to_blender(v):
    """gibench's y-up (x, y, z) as Blender's z-up (x, -z, y)."""
    return mathutils.Vector((v[0], -v[2], v[1]))


def floats(text, n):
    vals = [float(t) for t in text.replace(",", " ").split()]
    if len(vals) != n:
        raise SystemExit("expected %d numbers, got '%s'" % (n, text))
    return vals


def read_scene(path):
    cp = configparser.ConfigParser(inline_comment_prefixes=(" ;",), comment_prefixes=(";", "#"))
    cp.optionxform = str
    with open(path) as f:
        cp.read_file(f)
    return cp


# The room generator's faces (scenes/procedural.c, build_room): -x, +x, floor, ceiling, -z, +z.
ROOM_FACES = [("room_wall_xneg", 0, -1), ("room_wall_xpos", 0, +1), ("room_floor", 1, -1),
              ("room_ceiling", 1, +1), ("room_wall_zneg", 2, -1), ("room_wall_zpos", 2, +1)]


def box_quads(lo, hi):
    """The six faces of the box [lo, hi] as (axis, side, four corners)."""
    quads = []
    for axis in range(3):
        for side in (-1, +1):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            corners = []
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = lo[axis] if side < 0 else hi[axis]
                p[u] = lo[u] if a == 0 else hi[u]
                p[v] = lo[v] if b == 0 else hi[v]
                corners.append(p)
            quads.append((axis, side, corners))
    return quads


def diffuse_material(name, albedo):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (albedo[0], albedo[1], albedo[2], 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    return m


def add_quads(name, quads):
    """One mesh object from (material, corners) quads, corners in gibench coordinates."""
    verts, faces, mats, slots = [], [], [], {}
    for mat, corners in quads:
        faces.append([len(verts) + k for k in range(4)])
        verts.extend(to_blender(c) for c in corners)
        mats.append(slots.setdefault(mat, len(slots)))
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts, [], faces)
    for mat in slots:
        me.materials.append(mat)
    for poly, slot in zip(me.polygons, mats):
        poly.material_index = slot
    ob = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(ob)


def material_albedos(cp):
    albedo = {}
    for sec in cp.sections():
        if sec.startswith("material."):
            keys = set(cp[sec]) - {"albedo"}
            if keys:
                raise SystemExit("%s: only albedo is supported, not %s" % (sec, sorted(keys)))
            albedo[sec[9:]] = floats(cp[sec]["albedo"], 3)
    return albedo


def build_meshes(cp, albedo):
    mats = {}

    def mat(name):
        if name not in mats:
            mats[name] = diffuse_material(name, albedo.get(name, [0.7, 0.7, 0.7]))
        return mats[name]

    for sec in cp.sections():
        if not sec.startswith("mesh."):
            continue
        m = cp[sec]
        extra = set(m) - {"procedural", "size", "translate", "material"}
        if extra or m.get("procedural") not in ("room", "box"):
            raise SystemExit("%s: only procedural room/box with size, translate, material" % sec)
        room = m["procedural"] == "room"
        size = floats(m["size"], 3) if "size" in m else ([4, 3, 4] if room else [1, 1, 1])
        t = floats(m["translate"], 3) if "translate" in m else [0, 0, 0]
        lo = [-0.5 * size[0] + t[0], t[1], -0.5 * size[2] + t[2]]
        hi = [0.5 * size[0] + t[0], size[1] + t[1], 0.5 * size[2] + t[2]]
        quads = []
        for axis, side, corners in box_quads(lo, hi):
            face = [f for f in ROOM_FACES if f[1] == axis and f[2] == side][0][0]
            name = m.get("material", face if room else "box")
            quads.append((mat(name), corners))
        add_quads(sec[5:], quads)


def build_lights(cp):
    for sec in cp.sections():
        if not sec.startswith("light."):
            continue
        l = cp[sec]
        if l.get("type") != "point" or set(l) - {"type", "position", "intensity"}:
            raise SystemExit("%s: only point lights (position, intensity)" % sec)
        inten = floats(l["intensity"], 3)
        peak = max(inten)
        ld = bpy.data.lights.new(sec[6:], type="POINT")
        ld.color = [c / peak for c in inten]
        ld.energy = 4.0 * math.pi * peak      # W: intensity P / (4 pi) W/sr
        ld.shadow_soft_size = 0.0             # a delta, as gibench's point light
        ob = bpy.data.objects.new(sec[6:], ld)
        ob.location = to_blender(floats(l["position"], 3))
        bpy.context.scene.collection.objects.link(ob)


def build_camera(cp):
    sec = [s for s in cp.sections() if s.startswith("camera.")][0]
    c = cp[sec]
    eye = to_blender(floats(c["eye"], 3))
    fwd = (to_blender(floats(c["target"], 3)) - eye).normalized()
    up = to_blender(floats(c.get("up", "0 1 0"), 3))
    right = fwd.cross(up).normalized()
    up = right.cross(fwd)
    cd = bpy.data.cameras.new("camera")
    cd.sensor_fit = "VERTICAL"
    cd.angle_y = math.radians(float(c.get("fov", "45")))
    ob = bpy.data.objects.new("camera", cd)
    rot = mathutils.Matrix((right, up, -fwd)).transposed()  # columns: the camera's x, y, z
    ob.matrix_world = mathutils.Matrix.Translation(eye) @ rot.to_4x4()
    bpy.context.scene.collection.objects.link(ob)
    bpy.context.scene.camera = ob


def setup_render(job):
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    cy = sc.cycles
    cy.device = "CPU"
    sc.render.threads_mode = "FIXED"
    sc.render.threads = job["threads"]
    sc.render.resolution_x, sc.render.resolution_y = job["width"], job["height"]
    sc.render.resolution_percentage = 100
    cy.samples = job["spp"]
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    bounces = job["max_depth"] - 1
    cy.max_bounces = cy.diffuse_bounces = cy.glossy_bounces = bounces
    cy.transmission_bounces = cy.volume_bounces = cy.transparent_max_bounces = bounces
    cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.pixel_filter_type = "BLACKMAN_HARRIS"
    cy.filter_width = 0.01
    for key, value in job.get("cycles", {}).items():   # bench_cycles.py --cycles-set
        if not hasattr(cy, key):
            raise SystemExit("Cycles has no setting %s" % key)
        setattr(cy, key, type(getattr(cy, key))(value))
    world = bpy.data.worlds.new("black")
    world.use_nodes = False
    world.color = (0.0, 0.0, 0.0)
    sc.world = world
    sc.view_settings.view_transform = "Standard"
    sc.render.image_settings.file_format = "OPEN_EXR"
    sc.render.image_settings.color_mode = "RGB"
    sc.render.image_settings.color_depth = "32"
    sc.render.image_settings.exr_codec = "ZIP"


def settings(sc):
    cy = sc.cycles
    keys = ["samples", "sampling_pattern", "max_bounces", "diffuse_bounces", "min_light_bounces",
            "sample_clamp_direct", "sample_clamp_indirect", "light_sampling_threshold",
            "blur_glossy", "pixel_filter_type", "filter_width", "use_adaptive_sampling",
            "use_denoising", "use_guiding", "direct_light_sampling_type"]
    missing = [k for k in keys if not hasattr(cy, k)]
    if missing:
        raise SystemExit("Cycles has no setting %s" % missing)
    return {k: getattr(cy, k) for k in keys}


def main():
    job = json.load(open(sys.argv[sys.argv.index("--") + 1]))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    cp = read_scene(job["scene"])
    build_meshes(cp, material_albedos(cp))
    build_lights(cp)
    build_camera(cp)
    setup_render(job)
    sc = bpy.context.scene
    sc.cycles.seed = 0
    sc.cycles.samples = 1
    bpy.ops.render.render()                 # a warm-up: first-render costs are not timed
    sc.cycles.samples = job["spp"]
    runs = []
    for s in job["seeds"]:
        sc.cycles.seed = s
        t0 = time.perf_counter()
        bpy.ops.render.render()
        sec = time.perf_counter() - t0
        path = "%s/seed_%d.exr" % (job["dir"], s)
        bpy.data.images["Render Result"].save_render(path)
        runs.append({"seed": s, "seconds": sec, "exr": path})
    out = {"runs": runs, "settings": settings(sc), "blender": bpy.app.version_string,
           "build_hash": bpy.app.build_hash.decode() if isinstance(bpy.app.build_hash, bytes)
           else str(bpy.app.build_hash)}
    with open("%s/result.json" % job["dir"], "w") as f:
        json.dump(out, f, indent=1)


main()

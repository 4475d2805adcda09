"""A small OpenEXR reader in plain Python (no numpy, no OpenEXR module): scanline files with
NONE, ZIPS or ZIP compression and HALF or FLOAT channels, which is what gibench (ZIP, FLOAT) and
Blender (ZIP, FLOAT, as cycles_scene.py asks) write. Returns the R, G, B channels as one flat
list per channel, row 0 on top, and the header's string and float attributes (gibench keeps its
render's seconds there)."""
import struct
import zlib

COMPRESSION_LINES = {0: 1, 2: 1, 3: 16}   # NONE, ZIPS, ZIP: scanlines a chunk


def _cstr(buf, pos):
    end = buf.index(b"\0", pos)
    return buf[pos:end].decode(), end + 1


def _channels(data):
    chans, pos = [], 0
    while data[pos] != 0:
        name, pos = _cstr(data, pos)
        ptype, = struct.unpack_from("<i", data, pos)
        chans.append((name, ptype))
        pos += 16
    return chans


def _header(buf):
    if buf[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("not an OpenEXR file")
    if struct.unpack_from("<i", buf, 4)[0] & 0x200:
        raise ValueError("tiled OpenEXR files are not read here")
    pos, attrs = 8, {}
    while buf[pos] != 0:
        name, pos = _cstr(buf, pos)
        kind, pos = _cstr(buf, pos)
        size, = struct.unpack_from("<i", buf, pos)
        data = buf[pos + 4:pos + 4 + size]
        pos += 4 + size
        if kind == "chlist":
            attrs[name] = _channels(data)
        elif kind == "compression":
            attrs[name] = data[0]
        elif kind == "box2i":
            attrs[name] = struct.unpack("<iiii", data)
        elif kind == "string":
            attrs[name] = data.decode(errors="replace")
        elif kind == "float":
            attrs[name] = struct.unpack("<f", data)[0]
    return attrs, pos + 1


def _unzip(raw, expected):
    if len(raw) == expected:   # stored raw: the compressed stream would not have been shorter
        return raw
    t = bytearray(zlib.decompress(raw))
    for i in range(1, len(t)):  # undo the predictor
        t[i] = (t[i - 1] + t[i] - 128) & 0xFF
    half = (len(t) + 1) // 2
    out = bytearray(len(t))
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return bytes(out)


def read_exr(path):
    """(width, height, {'R': [...], 'G': [...], 'B': [...]}, attrs)."""
    with open(path, "rb") as f:
        buf = f.read()
    attrs, pos = _header(buf)
    x0, y0, x1, y1 = attrs["dataWindow"]
    w, h = x1 - x0 + 1, y1 - y0 + 1
    comp = attrs["compression"]
    if comp not in COMPRESSION_LINES:
        raise ValueError("%s: compression %d is not read here" % (path, comp))
    per = COMPRESSION_LINES[comp]
    chans = sorted(attrs["channels"])
    nchunks = (h + per - 1) // per
    offsets = struct.unpack_from("<%dQ" % nchunks, buf, pos)
    out = {name: [0.0] * (w * h) for name, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from("<ii", buf, off)
        lines = min(per, y1 + 1 - y)
        expected = sum(w * (2 if t == 1 else 4) for _, t in chans) * lines
        data = buf[off + 8:off + 8 + size]
        data = _unzip(data, expected) if comp in (2, 3) else data
        p = 0
        for ly in range(lines):
            row = (y - y0 + ly) * w
            for name, ptype in chans:
                fmt, step = ("<%de" % w, 2) if ptype == 1 else ("<%df" % w, 4)
                out[name][row:row + w] = struct.unpack_from(fmt, data, p)
                p += w * step
    return w, h, out, attrs

"""File formats the property test reads and writes, independently of skinslide's own readers:
OBJ (text kept line by line), glTF binary (positions, triangles, the weld), PC2 and MDD caches,
and full decoders of the EXR and PNG files skinslide writes (so "parseable" means every byte was
read back, not only a header)."""
import json
import math
import struct
import zlib

import numpy as np


class FormatError(Exception):
    """A file skinslide wrote does not parse."""


# ---- OBJ ----------------------------------------------------------------------------------------

class Obj:
    """An OBJ file as lines: `v` lines (their positions, their line numbers) and faces (0-based
    vertex ids, polygons). Every other line is kept as text."""

    def __init__(self, text):
        self.lines = text.split("\n")  # the last entry is "" when the file ends with a newline
        self.v_lines = []
        positions = []
        self.faces = []
        for i, line in enumerate(self.lines):
            tok = line.split()
            if not tok:
                continue
            if tok[0] == "v":
                self.v_lines.append(i)
                positions.append([float(t) for t in tok[1:4]])
            elif tok[0] == "f":
                face = []
                for t in tok[1:]:
                    k = int(t.split("/")[0])
                    face.append(k - 1 if k > 0 else len(positions) + k)
                self.faces.append(face)
        self.positions = np.array(positions, dtype=np.float64).reshape(-1, 3)

    @staticmethod
    def read(path):
        with open(path, "r", encoding="utf-8", errors="surrogateescape", newline="") as f:
            return Obj(f.read())

    def v_line(self, v):
        return self.lines[self.v_lines[v]]

    def with_positions(self, positions):
        """This file's text with the `v` lines' x y z replaced (the rest of each line kept)."""
        lines = list(self.lines)
        for v, i in enumerate(self.v_lines):
            tok = lines[i].split()
            tail = " ".join(tok[4:])
            x, y, z = (repr(float(c)) for c in positions[v])
            end = "\r" if lines[i].endswith("\r") else ""
            lines[i] = f"v {x} {y} {z}" + (" " + tail if tail else "") + end
        return "\n".join(lines)


def write_obj(path, positions, faces, colours=None):
    out = []
    for v, p in enumerate(positions):
        line = "v %r %r %r" % (float(p[0]), float(p[1]), float(p[2]))
        if colours is not None:
            line += " %r %r %r" % tuple(float(c) for c in colours[v])
        out.append(line)
    for f in faces:
        out.append("f " + " ".join(str(v + 1) for v in f))
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")


# ---- glTF binary --------------------------------------------------------------------------------

_COMPONENT = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
_WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


class Glb:
    """A .glb: its JSON, its BIN chunk, the triangles of its one mesh (primitive order) and every
    float POSITION accessor's raw vertices."""

    def __init__(self, data, path="glb"):
        self.data = bytes(data)
        if len(data) < 20 or data[:4] != b"glTF":
            raise FormatError(f"{path}: not a GLB")
        magic, version, length = struct.unpack_from("<4sII", data, 0)
        if version != 2 or length != len(data):
            raise FormatError(f"{path}: GLB header length {length}, file {len(data)} bytes")
        at = 12
        self.json = None
        self.bin = b""
        self.bin_offset = 0
        while at < len(data):
            if at + 8 > len(data):
                raise FormatError(f"{path}: chunk header cut at byte {at}")
            size, kind = struct.unpack_from("<II", data, at)
            if at + 8 + size > len(data):
                raise FormatError(f"{path}: chunk at byte {at} runs past the end")
            body = data[at + 8:at + 8 + size]
            if kind == 0x4E4F534A:
                self.json = json.loads(body.decode("utf-8"), parse_constant=_no_constant)
            elif kind == 0x004E4942:
                self.bin = body
                self.bin_offset = at + 8
            at += 8 + size
        if self.json is None:
            raise FormatError(f"{path}: no JSON chunk")
        self.path = path
        meshes = self.json.get("meshes", [])
        if len(meshes) != 1:
            raise FormatError(f"{path}: {len(meshes)} meshes")
        self.raw_positions = []  # per triangle primitive
        self.position_accessors = []
        tris = []
        base = 0
        for prim in meshes[0]["primitives"]:
            if prim.get("mode", 4) != 4:
                continue
            acc = prim["attributes"]["POSITION"]
            pos = self.accessor(acc).astype(np.float64)
            self.position_accessors.append(acc)
            if "indices" in prim:
                idx = self.accessor(prim["indices"]).astype(np.int64).reshape(-1)
            else:
                idx = np.arange(len(pos))
            tris.append(idx.reshape(-1, 3) + base)
            self.raw_positions.append(pos)
            base += len(pos)
        self.raw = np.concatenate(self.raw_positions) if self.raw_positions else np.zeros((0, 3))
        self.raw_triangles = np.concatenate(tris) if tris else np.zeros((0, 3), dtype=np.int64)

    @staticmethod
    def read(path):
        path = str(path)
        if path.endswith(".gltf"):
            return Glb.read_gltf(path)
        with open(path, "rb") as f:
            return Glb(f.read(), path)

    @staticmethod
    def read_gltf(path):
        """A .gltf and its one buffer (a file beside it or a data URI), as a GLB would hold them."""
        import base64
        import os
        doc = json.loads(open(path, "rb").read().decode("utf-8"), parse_constant=_no_constant)
        buffers = doc.get("buffers", [])
        if len(buffers) != 1:
            raise FormatError(f"{path}: {len(buffers)} buffers (one read here)")
        uri = buffers[0]["uri"]
        if uri.startswith("data:"):
            data = base64.b64decode(uri.split(",", 1)[1])
        else:
            bin_path = os.path.join(os.path.dirname(path), uri)
            if not os.path.exists(bin_path):
                raise FormatError(f"{path}: its buffer {uri} is missing")
            data = open(bin_path, "rb").read()
        if len(data) < buffers[0]["byteLength"]:
            raise FormatError(f"{path}: buffer {uri} holds {len(data)} of "
                              f"{buffers[0]['byteLength']} bytes")
        return Glb(_glb_bytes(doc, data), path)

    def to_gltf(self, raw_positions, bin_name):
        """This document as a .gltf text and its .bin bytes, positions replaced."""
        g = Glb(self.with_positions(raw_positions))
        doc = json.loads(json.dumps(g.json))
        doc["buffers"][0]["uri"] = bin_name
        return json.dumps(doc, indent=1), g.bin

    def accessor_layout(self, index):
        acc = self.json["accessors"][index]
        if "sparse" in acc:
            raise FormatError(f"{self.path}: accessor {index} is sparse (not read here)")
        fmt = _COMPONENT[acc["componentType"]]
        width = _WIDTH[acc["type"]]
        view = self.json["bufferViews"][acc["bufferView"]]
        if view.get("buffer", 0) != 0:
            raise FormatError(f"{self.path}: accessor {index} in buffer {view['buffer']}")
        item = struct.calcsize("<" + fmt) * width
        stride = view.get("byteStride", item)
        start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        count = acc["count"]
        end = start + stride * (count - 1) + item if count else start
        if end > view.get("byteOffset", 0) + view["byteLength"] or end > len(self.bin):
            raise FormatError(f"{self.path}: accessor {index} runs past its view or buffer")
        return fmt, width, stride, start, count

    def accessor(self, index):
        fmt, width, stride, start, count = self.accessor_layout(index)
        dtype = np.dtype("<" + fmt)
        item = dtype.itemsize * width
        if stride == item:
            a = np.frombuffer(self.bin, dtype=dtype, count=count * width, offset=start)
            return a.reshape(count, width) if width > 1 else a
        rows = [np.frombuffer(self.bin, dtype=dtype, count=width, offset=start + k * stride)
                for k in range(count)]
        return np.array(rows).reshape(count, width)

    def with_positions(self, raw_positions):
        """This file's bytes with every POSITION accessor's vertices replaced (float32)."""
        data = bytearray(self.data)
        at = 0
        for acc in self.position_accessors:
            fmt, width, stride, start, count = self.accessor_layout(acc)
            assert fmt == "f" and width == 3
            values = np.asarray(raw_positions[at:at + count], dtype="<f4")
            for k in range(count):
                o = self.bin_offset + start + k * stride
                data[o:o + 12] = values[k].tobytes()
            # min/max must stay exact for validators; the JSON chunk is left as it is (skinslide
            # does not read them), so a validator may warn on these hand-made frames.
            at += count
        return bytes(data)


def _no_constant(name):
    raise FormatError(f"JSON holds {name}")


def _glb_bytes(doc, data):
    body = json.dumps(doc).encode()
    body += b" " * (-len(body) % 4)
    data = data + b"\0" * (-len(data) % 4)
    total = 12 + 8 + len(body) + 8 + len(data)
    return (struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<II", len(body), 0x4E4F534A) +
            body + struct.pack("<II", len(data), 0x004E4942) + data)


def weld(raw):
    """glTF welding as skinslide does it: one vertex per exact position, ids in the order of the
    first raw copy. Returns (welded positions, raw -> welded id)."""
    first = {}
    ids = np.empty(len(raw), dtype=np.int64)
    for k, p in enumerate(map(tuple, raw.tolist())):
        ids[k] = first.setdefault(p, len(first))
    welded = np.zeros((len(first), 3))
    welded[ids] = raw
    return welded, ids


# ---- point caches -------------------------------------------------------------------------------

def write_pc2(path, samples, start=1.0, rate=1.0):
    samples = np.asarray(samples, dtype="<f4")
    with open(path, "wb") as f:
        f.write(struct.pack("<12siiffi", b"POINTCACHE2\0", 1, samples.shape[1], start, rate,
                            samples.shape[0]))
        f.write(samples.tobytes())


def read_pc2(path):
    data = open(path, "rb").read()
    if len(data) < 32 or data[:12] != b"POINTCACHE2\0":
        raise FormatError(f"{path}: not a PC2 file")
    _, version, points, start, rate, count = struct.unpack_from("<12siiffi", data, 0)
    if len(data) != 32 + 12 * points * count:
        raise FormatError(f"{path}: {len(data)} bytes for {count} samples of {points} points")
    samples = np.frombuffer(data, dtype="<f4", offset=32).reshape(count, points, 3)
    return {"header": data[:32], "start": start, "rate": rate, "samples": samples}


def write_mdd(path, samples, times=None):
    samples = np.asarray(samples, dtype=">f4")
    count, points = samples.shape[0], samples.shape[1]
    times = (np.arange(count) / 24.0 if times is None else np.asarray(times)).astype(">f4")
    with open(path, "wb") as f:
        f.write(struct.pack(">ii", count, points))
        f.write(times.tobytes())
        f.write(samples.tobytes())


def read_mdd(path):
    data = open(path, "rb").read()
    if len(data) < 8:
        raise FormatError(f"{path}: not an MDD file")
    count, points = struct.unpack_from(">ii", data, 0)
    if len(data) != 8 + 4 * count + 12 * points * count:
        raise FormatError(f"{path}: {len(data)} bytes for {count} samples of {points} points")
    times = np.frombuffer(data, dtype=">f4", count=count, offset=8)
    samples = np.frombuffer(data, dtype=">f4", offset=8 + 4 * count).reshape(count, points, 3)
    return {"header": data[:8 + 4 * count], "times": times, "samples": samples}


# ---- EXR (single-part scanline, as skinslide writes them) ---------------------------------------

_EXR_PIXEL = {0: (4, "<u4"), 1: (2, "<f2"), 2: (4, "<f4")}
_EXR_LINES = {0: 1, 1: 1, 2: 1, 3: 16}  # NONE, RLE, ZIPS, ZIP


def read_exr(path):
    """Every channel of a scanline EXR (uncompressed, ZIPS or ZIP) as arrays; raises FormatError
    on any inconsistency (header, offsets, chunk sizes, zlib streams, trailing bytes)."""
    data = open(path, "rb").read()
    if len(data) < 8 or data[:4] != b"\x76\x2f\x31\x01":
        raise FormatError(f"{path}: not an EXR file")
    version = struct.unpack_from("<I", data, 4)[0]
    if version & 0xFF != 2 or version & ~0xFF:
        raise FormatError(f"{path}: version/flags {version:#x} (expected single-part scanline)")
    at = 8
    attrs = {}
    while True:
        end = data.index(b"\0", at)
        name = data[at:end].decode()
        at = end + 1
        if not name:
            break
        end = data.index(b"\0", at)
        kind = data[at:end].decode()
        size = struct.unpack_from("<i", data, end + 1)[0]
        attrs[name] = (kind, data[end + 5:end + 5 + size])
        at = end + 5 + size
        if at > len(data):
            raise FormatError(f"{path}: header runs past the end")
    for need in ("channels", "compression", "dataWindow", "displayWindow", "lineOrder"):
        if need not in attrs:
            raise FormatError(f"{path}: no {need} attribute")
    channels = []
    raw = attrs["channels"][1]
    k = 0
    while raw[k] != 0:
        end = raw.index(b"\0", k)
        cname = raw[k:end].decode()
        ptype, _, _, xs, ys = struct.unpack_from("<iB3sii", raw, end + 1)
        if xs != 1 or ys != 1 or ptype not in _EXR_PIXEL:
            raise FormatError(f"{path}: channel {cname} sampling/type")
        channels.append((cname, ptype))
        k = end + 17
    compression = attrs["compression"][1][0]
    if compression not in _EXR_LINES or compression == 1:
        raise FormatError(f"{path}: compression {compression} not decoded here")
    x0, y0, x1, y1 = struct.unpack("<iiii", attrs["dataWindow"][1])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    per_block = _EXR_LINES[compression]
    blocks = -(-height // per_block)
    offsets = struct.unpack_from(f"<{blocks}Q", data, at)
    at += 8 * blocks
    line_bytes = sum(_EXR_PIXEL[t][0] for _, t in channels) * width
    planes = {c: np.zeros((height, width), dtype=_EXR_PIXEL[t][1]) for c, t in channels}
    for b, off in enumerate(offsets):
        if off != at:
            raise FormatError(f"{path}: block {b} at byte {off}, expected {at}")
        y, size = struct.unpack_from("<ii", data, off)
        lines = min(per_block, y1 + 1 - y)
        if y != y0 + b * per_block or off + 8 + size > len(data):
            raise FormatError(f"{path}: block {b} (y {y}, {size} bytes) out of place")
        body = data[off + 8:off + 8 + size]
        want = line_bytes * lines
        if compression and size < want:
            try:
                body = zlib.decompress(body)
            except zlib.error as e:
                raise FormatError(f"{path}: block {b}: {e}")
            if len(body) != want:
                raise FormatError(f"{path}: block {b} inflates to {len(body)} bytes, not {want}")
            t = np.frombuffer(body, dtype=np.uint8).astype(np.int32)
            t = (np.cumsum(t - 128 + np.r_[128, np.zeros(len(t) - 1, np.int32)]) & 0xFF)
            t = t.astype(np.uint8)
            half = (len(t) + 1) // 2
            out = np.empty_like(t)
            out[0::2] = t[:half]
            out[1::2] = t[half:]
            body = out.tobytes()
        elif size != want:
            raise FormatError(f"{path}: block {b} holds {size} bytes, not {want}")
        at = off + 8 + size
        pos = 0
        for j in range(lines):
            for c, t in channels:
                n = _EXR_PIXEL[t][0] * width
                planes[c][y - y0 + j] = np.frombuffer(body, dtype=_EXR_PIXEL[t][1], count=width,
                                                      offset=pos)
                pos += n
    if at != len(data):
        raise FormatError(f"{path}: {len(data) - at} bytes after the last block")
    strings = {n: v.decode("utf-8", "replace") for n, (kind, v) in attrs.items() if kind == "string"}
    return {"width": width, "height": height, "channels": planes, "strings": strings}


# ---- PNG ----------------------------------------------------------------------------------------

def read_png(path):
    """A PNG's size and pixels, every chunk's CRC and the image data's length checked."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise FormatError(f"{path}: not a PNG")
    at = 8
    idat = b""
    header = None
    ended = False
    while at < len(data):
        if ended:
            raise FormatError(f"{path}: bytes after IEND")
        size, kind = struct.unpack_from(">I4s", data, at)
        body = data[at + 8:at + 8 + size]
        if len(body) != size or at + 12 + size > len(data):
            raise FormatError(f"{path}: chunk {kind} cut")
        crc = struct.unpack_from(">I", data, at + 8 + size)[0]
        if zlib.crc32(kind + body) & 0xFFFFFFFF != crc:
            raise FormatError(f"{path}: chunk {kind} CRC")
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            ended = True
        at += 12 + size
    if header is None or not ended:
        raise FormatError(f"{path}: no IHDR or IEND")
    width, height, depth, colour, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace != 0:
        raise FormatError(f"{path}: depth {depth} colour {colour} interlace {interlace}")
    raw = zlib.decompress(idat)
    row = 1 + width * channels
    if len(raw) != height * row:
        raise FormatError(f"{path}: {len(raw)} image bytes for {width}x{height}")
    filters = np.frombuffer(raw, dtype=np.uint8)[::row]
    if filters.max(initial=0) > 4:
        raise FormatError(f"{path}: filter type {filters.max()}")
    return {"width": width, "height": height}


def finite_floats(values):
    return bool(np.all(np.isfinite(np.asarray(values, dtype=np.float64))))


def is_float_text(t):
    try:
        return math.isfinite(float(t))
    except ValueError:
        return False

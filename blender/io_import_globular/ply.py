# PLY files as globular writes them (and any other ascii or binary PLY), read with
# struct alone: Blender's own PLY importer drops every vertex property it does not know
# (vx vy vz radius id temperature material mass), and Debian's Blender has no numpy.
# No bpy here, so that plain python3 can test it.

import struct

_TYPES = {
    "char": "b", "int8": "b", "uchar": "B", "uint8": "B",
    "short": "h", "int16": "h", "ushort": "H", "uint16": "H",
    "int": "i", "int32": "i", "uint": "I", "uint32": "I",
    "float": "f", "float32": "f", "double": "d", "float64": "d",
}


class PlyError(Exception):
    pass


class PlyData:
    """vertex: {property name: list of values}; faces: list of index tuples."""

    def __init__(self):
        self.vertex = {}
        self.vertex_count = 0
        self.faces = []


def _header(data, path):
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise PlyError(f"{path}: not a PLY file")
    stop = data.find(b"\n", end)
    body = stop + 1 if stop >= 0 else len(data)
    lines = data[:end].decode("ascii", "replace").splitlines()
    fmt = None
    elements = []  # (name, count, [(name, type, count type or None)])
    for line in lines[1:]:
        words = line.split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property" and elements:
            if words[1] == "list":
                elements[-1][2].append((words[4], _code(words[3], path), _code(words[2], path)))
            else:
                elements[-1][2].append((words[2], _code(words[1], path), None))
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise PlyError(f"{path}: unknown PLY format {fmt!r}")
    return fmt, elements, body


def _code(name, path):
    if name not in _TYPES:
        raise PlyError(f"{path}: unknown PLY type {name!r}")
    return _TYPES[name]


def read_ply(path):
    """Reads @p path: every scalar vertex property, and the faces' index lists."""
    with open(path, "rb") as f:
        data = f.read()
    fmt, elements, pos = _header(data, path)
    out = PlyData()
    if fmt == "ascii":
        words = data[pos:].split()
        at = 0
        for name, count, props in elements:
            rows = []
            for _ in range(count):
                row = []
                for _pname, code, list_code in props:
                    if list_code:
                        n = int(words[at])
                        row.append(tuple(int(w) for w in words[at + 1:at + 1 + n]))
                        at += 1 + n
                    else:
                        value = words[at]
                        row.append(float(value) if code in "fd" else int(value))
                        at += 1
                rows.append(row)
            _keep(out, name, count, props, rows)
        return out
    order = "<" if fmt == "binary_little_endian" else ">"
    for name, count, props in elements:
        if all(list_code is None for _n, _c, list_code in props):
            row = struct.Struct(order + "".join(code for _n, code, _l in props))
            size = row.size * count
            if pos + size > len(data):
                raise PlyError(f"{path}: truncated in element {name}")
            rows = list(row.iter_unpack(data[pos:pos + size])) if count else []
            pos += size
        elif len(props) == 1:
            # One list (faces): triangles in one go when every row holds three.
            _pname, code, list_code = props[0]
            tri = struct.Struct(order + list_code + code * 3)
            rows = None
            size = tri.size * count
            if pos + size <= len(data) and count:
                rows = list(tri.iter_unpack(data[pos:pos + size]))
                if all(r[0] == 3 for r in rows):
                    rows = [(r[1:],) for r in rows]
                    pos += size
                else:
                    rows = None
            if rows is None:
                rows, pos = _list_rows(data, pos, order, count, list_code, code, path, name)
        else:
            raise PlyError(f"{path}: element {name} mixes lists and scalars")
        _keep(out, name, count, props, rows)
    return out


def _list_rows(data, pos, order, count, list_code, code, path, name):
    head = struct.Struct(order + list_code)
    rows = []
    for _ in range(count):
        if pos + head.size > len(data):
            raise PlyError(f"{path}: truncated in element {name}")
        (n,) = head.unpack_from(data, pos)
        pos += head.size
        item = struct.Struct(order + code * n)
        if pos + item.size > len(data):
            raise PlyError(f"{path}: truncated in element {name}")
        rows.append((item.unpack_from(data, pos),))
        pos += item.size
    return rows, pos


def _keep(out, name, count, props, rows):
    if name == "vertex":
        out.vertex_count = count
        for k, (pname, _code_, list_code) in enumerate(props):
            if list_code is None:
                out.vertex[pname] = [r[k] for r in rows]
    elif name == "face":
        for k, (pname, _code_, list_code) in enumerate(props):
            if list_code is not None and pname in ("vertex_indices", "vertex_index"):
                out.faces = [r[k] for r in rows]


def positions(ply):
    """x y z per vertex, flat."""
    v = ply.vertex
    flat = [0.0] * (3 * ply.vertex_count)
    flat[0::3], flat[1::3], flat[2::3] = v["x"], v["y"], v["z"]
    return flat


def vectors(ply, names):
    """Three vertex properties (vx vy vz, nx ny nz) flat, or None when one is missing."""
    v = ply.vertex
    if not all(n in v for n in names):
        return None
    flat = [0.0] * (3 * ply.vertex_count)
    flat[0::3], flat[1::3], flat[2::3] = (v[n] for n in names)
    return flat

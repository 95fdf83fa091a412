# The add-on's PLY reader (blender/io_import_globular/ply.py) under plain python3, no
# Blender needed: the same cloud written as ascii, binary little and big endian reads the
# same; quads and triangles; a truncated file is an error naming it.
#   python3 tests/blender_ply_test.py
import importlib.util
import os
import struct
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location(
    "globular_ply", os.path.join(here, "..", "blender", "io_import_globular", "ply.py"))
ply = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ply)

VERTICES = [(0.0, 0.0, 0.0, 1.5, -2.0, 0.25, 7, 2.5), (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 9, 1.0),
            (1.0, 1.0, 0.0, 0.5, 0.5, 0.5, 11, 3.0), (0.0, 1.0, 0.5, -1.0, 0.0, 2.0, 13, 0.75)]
FACES = [(0, 1, 2), (0, 2, 3, 1)]  # a triangle and a quad
HEADER = ("element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
          "property float vx\nproperty float vy\nproperty float vz\nproperty int id\n"
          "property float mass\nelement face 2\nproperty list uchar int vertex_indices\n"
          "end_header\n")


def write(path, fmt):
    with open(path, "wb") as f:
        f.write(f"ply\nformat {fmt} 1.0\ncomment test\n{HEADER}".encode())
        if fmt == "ascii":
            for v in VERTICES:
                f.write((" ".join(str(x) for x in v) + "\n").encode())
            for face in FACES:
                f.write((f"{len(face)} " + " ".join(map(str, face)) + "\n").encode())
            return
        order = "<" if fmt == "binary_little_endian" else ">"
        for v in VERTICES:
            f.write(struct.pack(order + "6fif", *v))
        for face in FACES:
            f.write(struct.pack(order + "B" + "i" * len(face), len(face), *face))


def main():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for fmt in ("ascii", "binary_little_endian", "binary_big_endian"):
            path = os.path.join(tmp, fmt + ".ply")
            write(path, fmt)
            data = ply.read_ply(path)
            if data.vertex_count != 4 or [tuple(f) for f in data.faces] != FACES:
                failures.append(f"{fmt}: {data.vertex_count} vertices, faces {data.faces}")
            if ply.vectors(data, ("vx", "vy", "vz"))[:3] != [1.5, -2.0, 0.25]:
                failures.append(f"{fmt}: velocity {ply.vectors(data, ('vx', 'vy', 'vz'))[:3]}")
            if data.vertex["id"] != [7, 9, 11, 13] or data.vertex["mass"] != [2.5, 1.0, 3.0, 0.75]:
                failures.append(f"{fmt}: id {data.vertex['id']}, mass {data.vertex['mass']}")
            if ply.positions(data)[9:12] != [0.0, 1.0, 0.5]:
                failures.append(f"{fmt}: positions {ply.positions(data)}")
            if ply.vectors(data, ("nx", "ny", "nz")) is not None:
                failures.append(f"{fmt}: normals where the file has none")
        cut = os.path.join(tmp, "cut.ply")
        with open(os.path.join(tmp, "binary_little_endian.ply"), "rb") as f:
            whole = f.read()
        with open(cut, "wb") as f:
            f.write(whole[:-20])
        try:
            ply.read_ply(cut)
            failures.append("a truncated file read")
        except ply.PlyError as e:
            if cut not in str(e):
                failures.append(f"the error does not name the file: {e}")
    for failure in failures:
        print("FAIL:", failure)
    print("blender ply test:", "FAILED" if failures else "passed")
    return 1 if failures else 0


sys.exit(main())

# Mesh sequences: objects whose mesh is read from a frame-numbered PLY file on every
# frame change (the surface's topology changes from frame to frame, so no shape keys or
# modifiers can play it back). Each such object carries custom properties: which files
# (globular_kind) and which folder (the scene's globular_dir). The handler is persistent,
# so a saved .blend plays back while the add-on is enabled.

import os

import bpy
from bpy.app.handlers import persistent

from . import ply, scene_files

KIND = "globular_kind"
LOADED = "globular_frame"
DIR = "globular_dir"

# Custom property value -> the files it reads.
KINDS = {
    "surface": scene_files.SURFACE_MESH,
    "globules": scene_files.GLOBULES_PLY,
    "colliders": scene_files.COLLIDER_MESH,
}

# PLY vertex property -> (Blender attribute, type); vectors are built from three.
_SCALARS = {
    "radius": "FLOAT", "temperature": "FLOAT", "mass": "FLOAT",
    "id": "INT", "material": "INT",
}


def mesh_from_ply(name, path):
    """A new mesh of the PLY file @p path: faces with smooth shading and the file's
    normals, the velocity (vx vy vz) as the FLOAT_VECTOR point attribute `velocity` that
    Cycles' motion blur reads, and radius, id, mass, temperature, material."""
    data = ply.read_ply(path)
    mesh = bpy.data.meshes.new(name)
    n = data.vertex_count
    mesh.vertices.add(n)
    mesh.vertices.foreach_set("co", ply.positions(data))
    faces = [f for f in data.faces if len(f) >= 3]
    if faces:
        loops = [i for f in faces for i in f]
        mesh.loops.add(len(loops))
        mesh.loops.foreach_set("vertex_index", loops)
        mesh.polygons.add(len(faces))
        starts, total = [], 0
        for f in faces:
            starts.append(total)
            total += len(f)
        mesh.polygons.foreach_set("loop_start", starts)
        if "loop_total" in mesh.polygons[0].bl_rna.properties and \
                not mesh.polygons[0].bl_rna.properties["loop_total"].is_readonly:
            mesh.polygons.foreach_set("loop_total", [len(f) for f in faces])
        mesh.polygons.foreach_set("use_smooth", [True] * len(faces))
    mesh.update(calc_edges=True)
    mesh.validate(clean_customdata=False)
    normals = ply.vectors(data, ("nx", "ny", "nz"))
    if faces and normals:
        if hasattr(mesh, "use_auto_smooth"):
            mesh.use_auto_smooth = True  # custom normals need it before Blender 4.1
        mesh.normals_split_custom_set_from_vertices(
            [tuple(normals[3 * i:3 * i + 3]) for i in range(n)])
    velocity = ply.vectors(data, ("vx", "vy", "vz"))
    if velocity is not None:
        mesh.attributes.new("velocity", "FLOAT_VECTOR", "POINT").data.foreach_set("vector", velocity)
    for prop, kind in _SCALARS.items():
        if prop in data.vertex:
            values = data.vertex[prop]
            if kind == "INT":
                values = [int(v) for v in values]
            mesh.attributes.new(prop, kind, "POINT").data.foreach_set("value", values)
    return mesh


def load_frame(scene, frame):
    """Gives every sequence object of @p scene the mesh of @p frame (an empty mesh when
    that frame has no file)."""
    out_dir = scene.get(DIR)
    if not out_dir:
        return
    for obj in scene.objects:
        kind = obj.get(KIND)
        if kind not in KINDS or obj.get(LOADED) == frame or obj.type != "MESH":
            continue
        path = scene_files.frame_path(out_dir, KINDS[kind], frame)
        name = f"{obj.name}.{frame:04d}"
        mesh = mesh_from_ply(name, path) if os.path.isfile(path) else bpy.data.meshes.new(name)
        old = obj.data
        for material in old.materials:
            mesh.materials.append(material)
        obj.data = mesh
        obj[LOADED] = frame
        if old.users == 0:
            bpy.data.meshes.remove(old)


@persistent
def on_frame_change(scene, depsgraph=None):
    load_frame(scene, scene.frame_current)


def register():
    if on_frame_change not in bpy.app.handlers.frame_change_pre:
        bpy.app.handlers.frame_change_pre.append(on_frame_change)


def unregister():
    if on_frame_change in bpy.app.handlers.frame_change_pre:
        bpy.app.handlers.frame_change_pre.remove(on_frame_change)

# Runs inside Blender (tests/blender_test.sh), with BLENDER_USER_SCRIPTS a scratch folder:
#   blender -b --factory-startup --python tests/blender_addon_test.py -- \
#       OUT_DIR RENDERED.png ADDON.zip
# Installs and enables the add-on from its zip, imports OUT_DIR (a run of
# tests/data/blender/tiny.toml) through the add-on's operator and checks what arrived
# against what the scene and globular's files hold. Prints one line per failed check;
# exit status 0 when all pass, 1 otherwise.

import math
import os
import sys

argv = sys.argv[sys.argv.index("--") + 1:]
OUT_DIR, RENDERED, ZIP = argv[0], argv[1], argv[2]

import addon_utils  # noqa: E402
import bpy  # noqa: E402

bpy.ops.wm.read_homefile(use_empty=True)
bpy.ops.preferences.addon_install(filepath=ZIP)
addon_utils.enable("io_import_globular", default_set=True, handle_error=None)

import io_import_globular  # noqa: E402  (the installed copy)
from io_import_globular import scene_files  # noqa: E402

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def vertex_count_in_file(path):
    """The count of the PLY header's vertex element, read here independently."""
    with open(path, "rb") as f:
        header = f.read(1024).split(b"end_header")[0].decode("ascii", "replace")
    for line in header.splitlines():
        if line.startswith("element vertex"):
            return int(line.split()[2])
    return -1


def values(mesh, name, field="value"):
    attribute = mesh.attributes.get(name)
    if attribute is None:
        return None
    width = 3 if field == "vector" else 1
    flat = [0.0] * (width * len(attribute.data))
    attribute.data.foreach_get(field, flat)
    return [tuple(flat[i:i + 3]) for i in range(0, len(flat), 3)] if width == 3 else flat


def main():
    installed = os.path.dirname(io_import_globular.__file__)
    check(os.path.dirname(installed) in [p for p in bpy.utils.script_paths(subdir="addons")],
          f"the add-on was not installed from its zip ({installed})")
    result = bpy.ops.import_scene.globular(directory=OUT_DIR)
    check(result == {"FINISHED"}, f"the import operator returned {result}")
    scene = bpy.context.scene
    objects = bpy.data.objects

    # The objects, all below the one Y-up to Z-up root.
    names = ["globular", "globular_surface", "globular_volume", "globular_globules",
             "globular_colliders", "collider ball", "globular_camera", "globular_light0"]
    for name in names:
        check(name in objects, f"no object {name}")
    if failures:
        return
    root = objects["globular"]
    check(abs(root.rotation_euler.x - math.pi / 2) < 1e-6, "the root is not rotated +90 about x")
    for name in names[1:]:
        check(objects[name].parent == root, f"{name} is not parented to the root")
    check((scene.frame_start, scene.frame_end) == (1, 4),
          f"frame range {scene.frame_start}-{scene.frame_end}, not 1-4")
    check(abs(scene.render.fps / scene.render.fps_base - 24) < 1e-6, "fps is not 24")
    check(scene.camera == objects["globular_camera"], "the scene's camera is not globular's")
    check((scene.render.resolution_x, scene.render.resolution_y) == (64, 48),
          "the resolution is not the scene's 64 x 48")

    # The mesh sequence: each frame's file, its vertex count changing, its attributes.
    surface = objects["globular_surface"]
    counts = []
    for frame in (1, 4):
        scene.frame_set(frame)
        mesh = surface.data
        expected = vertex_count_in_file(
            scene_files.frame_path(OUT_DIR, scene_files.SURFACE_MESH, frame))
        counts.append(len(mesh.vertices))
        check(len(mesh.vertices) == expected,
              f"frame {frame}: {len(mesh.vertices)} surface vertices, the file has {expected}")
        velocity = values(mesh, "velocity", "vector")
        check(velocity is not None and len(velocity) == len(mesh.vertices),
              f"frame {frame}: the surface has no per-vertex velocity")
        check(mesh.attributes.get("velocity") is not None and
              mesh.attributes["velocity"].data_type == "FLOAT_VECTOR",
              "the surface's velocity is not a FLOAT_VECTOR attribute")
        temperature = values(mesh, "temperature")
        check(temperature is not None and all(29.0 <= t <= 71.0 for t in temperature),
              f"frame {frame}: the surface's temperature is missing or outside 30..70")
        check(values(mesh, "material") is not None, f"frame {frame}: no surface material")
        check(all(p.use_smooth for p in mesh.polygons), "the surface is not smooth shaded")
    check(counts[0] != counts[1], f"the surface's vertex count is {counts[0]} on both frames")

    # The globules at frame 1, the initial state: the emitters' exact values.
    scene.frame_set(1)
    points = objects["globular_globules"].data
    globule_count = len(points.vertices)
    check(globule_count == 35, f"{globule_count} globules, not 35")
    velocity = values(points, "velocity", "vector")
    check(velocity is not None and all(v == (1.0, 0.0, 0.0) for v in velocity),
          "the globules' velocity is not the emitters' (1, 0, 0)")
    radius = values(points, "radius")
    check(radius is not None and all(abs(r - 0.6) < 1e-6 for r in radius),
          "the globules' radius is not 0.6")
    mass = values(points, "mass")
    check(mass is not None and all(m == 2.5 for m in mass), "the globules' mass is not 2.5")
    temperature = values(points, "temperature")
    material = values(points, "material")
    ids = values(points, "id")
    check(temperature is not None and material is not None and ids is not None,
          "the globules lack temperature, material or id")
    if not failures:
        check(sorted(zip(material, temperature)) == [(0, 30.0)] * 27 + [(1, 70.0)] * 8,
              "the globules' (material, temperature) are not 27 x (0, 30) and 8 x (1, 70)")
        check(len(set(ids)) == 35, "the globules' ids are not unique")
    modifier = objects["globular_globules"].modifiers.get("spheres")
    check(modifier is not None and modifier.type == "NODES" and modifier.node_group,
          "the globules have no geometry-nodes sphere instancer")

    # The volume sequence with its velocity grid.
    volume = objects["globular_volume"].data
    volume.grids.load()
    grids = {grid.name: grid for grid in volume.grids}
    for name in ("surface", "density", "vel", "temperature"):
        check(name in grids, f"the volume has no grid {name} (grids: {sorted(grids)})")
    check(volume.velocity_grid == "vel", f"velocity_grid is {volume.velocity_grid!r}, not 'vel'")
    if "vel" in grids:
        check(grids["vel"].data_type == "VECTOR_FLOAT",
              f"the vel grid is {grids['vel'].data_type}, not VECTOR_FLOAT")

    # The collider's motion, keyed from cache/colliders.NNNN.toml, lands Z-up.
    scene.frame_set(3)
    ball = objects["collider ball"]
    poses = scene_files.collider_poses(OUT_DIR)["ball"]
    lift = next(t for frame, _r, t in poses if frame == 3)[1]
    check(lift > 0.1, f"the ball has not moved up by frame 3 ({lift})")
    check(abs(ball.matrix_world.translation.z - lift) < 1e-4,
          f"the ball's world z is {ball.matrix_world.translation.z}, its pose's y {lift}")

    # The camera of globular's render plan, when the run wrote one.
    if os.path.isfile(os.path.join(OUT_DIR, "render_plan.toml")):
        plan = scene_files.read_toml(os.path.join(OUT_DIR, "render_plan.toml"))["camera"]
        local = objects["globular_camera"].matrix_basis.translation
        check(max(abs(a - b) for a, b in zip(local, plan["position"])) < 1e-4,
              f"the camera is at {tuple(local)}, the plan's at {plan['position']}")
        check(abs(math.degrees(scene.camera.data.angle_y) - plan["fov"]) < 1e-4,
              "the camera's vertical angle is not the plan's fov")

    # The Cycles frame blender/globular_import.py rendered: the liquid's blue (the
    # scene's [render] color; ground and ball are grey) covers part of it.
    check(os.path.isfile(RENDERED), f"no rendered frame {RENDERED}")
    if os.path.isfile(RENDERED):
        image = bpy.data.images.load(RENDERED)
        pixels = list(image.pixels)
        blue = sum(1 for i in range(0, len(pixels), 4)
                   if pixels[i + 3] > 0.5 and pixels[i + 2] > pixels[i] + 0.1)
        check(blue > 50, f"the rendered frame shows {blue} pixels of liquid")
        print(f"blender test: {blue} of {len(pixels) // 4} pixels show the liquid")
    print(f"blender test: surface vertices {counts}, globules {globule_count}")


try:
    main()
except Exception as e:  # a failed check of its own kind
    import traceback

    traceback.print_exc()
    failures.append(f"exception: {e}")
print("blender test:", "FAILED" if failures else "passed")
sys.stdout.flush()
os._exit(1 if failures else 0)

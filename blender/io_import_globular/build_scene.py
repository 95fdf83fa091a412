# A globular output folder as a Blender scene. Everything globular writes is Y-up;
# Blender is Z-up. One conversion for everything: every object is parented to the empty
# "globular", rotated +90 degrees about X, and keeps globular's own coordinates (and
# velocities) below it.

import math
import os

import bpy
from mathutils import Matrix, Vector

from . import scene_files, sequences

ROOT = "globular"


def _root(collection):
    root = bpy.data.objects.new(ROOT, None)
    root.rotation_euler = (math.pi / 2, 0.0, 0.0)
    root.empty_display_size = 2.0
    collection.objects.link(root)
    return root


def _add(collection, root, name, data):
    obj = bpy.data.objects.new(name, data)
    collection.objects.link(obj)
    obj.parent = root
    return obj


def _color(output):
    material = output.scene.get("material", {})
    if isinstance(material, list):  # named [[material]]s: the first one's
        material = material[0] if material else {}
    colour = material.get("color", [0, 0, 0])
    if not any(colour):
        colour = output.section("render").get("color", [0.16, 0.42, 0.82])
    return tuple(colour) + (1.0,)


def _liquid_material(output):
    material = bpy.data.materials.new("globular_liquid")
    material.use_nodes = True
    bsdf = material.node_tree.nodes.get("Principled BSDF")
    if bsdf:
        bsdf.inputs["Base Color"].default_value = _color(output)
        bsdf.inputs["Roughness"].default_value = 0.25
    return material


def _volume_material(output):
    material = bpy.data.materials.new("globular_volume")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    for node in list(nodes):
        if node.type != "OUTPUT_MATERIAL":
            nodes.remove(node)
    volume = nodes.new("ShaderNodeVolumePrincipled")  # density from the grid "density"
    volume.inputs["Color"].default_value = _color(output)
    volume.inputs["Density"].default_value = 5.0
    out = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
    material.node_tree.links.new(volume.outputs["Volume"], out.inputs["Volume"])
    return material


def _volume(output, collection, root, first):
    frames = scene_files.frames_of(output.dir, scene_files.SURFACE_VDB)
    if not frames:
        return None
    volume = bpy.data.volumes.new("globular_surface_vdb")
    volume.filepath = scene_files.frame_path(output.dir, scene_files.SURFACE_VDB, frames[0])
    volume.is_sequence = len(frames) > 1
    volume.frame_start = frames[0]
    volume.frame_duration = frames[-1] - frames[0] + 1
    volume.frame_offset = frames[0] - 1  # scene frame f reads file f
    volume.sequence_mode = "CLIP"
    volume.grids.load()
    names = {grid.name for grid in volume.grids}
    if "vel" in names and not volume.velocity_grid:
        volume.velocity_grid = "vel"  # Blender detects it by name too
    volume.velocity_unit = "SECOND"  # globular's velocities are units per second
    volume.materials.append(_volume_material(output))
    return _add(collection, root, "globular_volume", volume)


def _sphere_instancer(material):
    """Geometry nodes: an ico sphere on every point, scaled by its `radius` attribute."""
    group = bpy.data.node_groups.new("globular_spheres", "GeometryNodeTree")
    if hasattr(group, "interface"):  # Blender 4
        group.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
        group.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    else:
        group.inputs.new("NodeSocketGeometry", "Geometry")
        group.outputs.new("NodeSocketGeometry", "Geometry")
    nodes, links = group.nodes, group.links
    inp = nodes.new("NodeGroupInput")
    out = nodes.new("NodeGroupOutput")
    sphere = nodes.new("GeometryNodeMeshIcoSphere")
    sphere.inputs["Radius"].default_value = 1.0
    sphere.inputs["Subdivisions"].default_value = 2
    set_material = nodes.new("GeometryNodeSetMaterial")
    set_material.inputs["Material"].default_value = material
    smooth = nodes.new("GeometryNodeSetShadeSmooth")
    radius = nodes.new("GeometryNodeInputNamedAttribute")
    radius.data_type = "FLOAT"
    radius.inputs["Name"].default_value = "radius"
    instance = nodes.new("GeometryNodeInstanceOnPoints")
    links.new(sphere.outputs["Mesh"], smooth.inputs["Geometry"])
    links.new(smooth.outputs["Geometry"], set_material.inputs["Geometry"])
    links.new(inp.outputs[0], instance.inputs["Points"])
    links.new(set_material.outputs["Geometry"], instance.inputs["Instance"])
    attribute = next(o for o in radius.outputs if o.enabled)
    links.new(attribute, instance.inputs["Scale"])
    links.new(instance.outputs["Instances"], out.inputs[0])
    return group


def _sequence(collection, root, name, kind, material=None):
    obj = _add(collection, root, name, bpy.data.meshes.new(name))
    obj[sequences.KIND] = kind
    if material:
        obj.data.materials.append(material)
    return obj


def _collider_keys(output, collection, root):
    """An empty per collider, keyframed with its pose on every frame (world = rotation *
    local + translation): the colliders' motion for constraints and motion blur."""
    empties = []
    for name, poses in scene_files.collider_poses(output.dir).items():
        empty = _add(collection, root, f"collider {name}", None)
        empty.empty_display_type = "ARROWS"
        empty.rotation_mode = "QUATERNION"
        for frame, rotation, translation in poses:
            m = Matrix([list(rotation[0]) + [translation[0]], list(rotation[1]) + [translation[1]],
                        list(rotation[2]) + [translation[2]], [0, 0, 0, 1]])
            empty.matrix_basis = m
            empty.keyframe_insert("location", frame=frame)
            empty.keyframe_insert("rotation_quaternion", frame=frame)
        empties.append(empty)
    return empties


def _look_at(obj, position, target):
    """Points @p obj's -Z at @p target with +Y up (in the root's Y-up space)."""
    position, target = Vector(position), Vector(target)
    forward = (target - position).normalized()
    side = forward.cross(Vector((0, 1, 0)))
    if side.length < 1e-6:
        side = Vector((1, 0, 0))
    side.normalize()
    up = side.cross(forward)
    rotation = Matrix((side, up, -forward)).transposed()
    obj.matrix_basis = Matrix.Translation(position) @ rotation.to_4x4()


def _camera(output, collection, root, scene):
    render = output.section("render")
    width, height = int(render.get("width", 1280)), int(render.get("height", 720))
    position, target, fov = output.camera(width / height)
    data = bpy.data.cameras.new("globular_camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(fov)
    span = math.dist(position, target)
    data.clip_start = max(1e-3, span * 1e-3)
    data.clip_end = span * 100
    camera = _add(collection, root, "globular_camera", data)
    _look_at(camera, position, target)
    scene.camera = camera
    scene.render.resolution_x, scene.render.resolution_y = width, height
    return camera


def _lights(output, collection, root):
    lights = []
    for i, light in enumerate(output.scene.get("light", [])):
        data = bpy.data.lights.new(f"globular_light{i}", "SUN")
        data.color = tuple(light.get("color", [1, 1, 1]))
        data.energy = 3.0 * float(light.get("intensity", 1.0))
        data.use_shadow = bool(light.get("shadows", True))
        obj = _add(collection, root, f"globular_light{i}", data)
        # A sun shines along its -Z: point -Z along the light's direction.
        direction = Vector(light.get("direction", [0, -1, 0])).normalized()
        obj.matrix_basis = direction.to_track_quat("-Z", "Y").to_matrix().to_4x4()
        lights.append(obj)
    return lights


def _ground(output, collection, root):
    """globular's ground plane ([ground] enabled, [render] ground), 20 times the content's
    size, in [render] ground_color."""
    height = output.ground_height()
    if height is None or not output.section("render").get("ground", True):
        return None
    bounds = output.bounds()
    low, high = bounds if bounds else ([-2, 0, -2], [2, 1, 2])
    centre = [(a + b) / 2 for a, b in zip(low, high)]
    half = 10 * max(high[0] - low[0], high[2] - low[2], 1.0)
    mesh = bpy.data.meshes.new("globular_ground")
    mesh.from_pydata([(centre[0] + x * half, height, centre[2] + z * half)
                      for x, z in ((-1, -1), (-1, 1), (1, 1), (1, -1))], [], [(0, 1, 2, 3)])
    material = bpy.data.materials.new("globular_ground")
    material.use_nodes = True
    bsdf = material.node_tree.nodes.get("Principled BSDF")
    if bsdf:
        colour = output.section("render").get("ground_color", [0.72, 0.7, 0.66])
        bsdf.inputs["Base Color"].default_value = tuple(colour) + (1.0,)
        bsdf.inputs["Roughness"].default_value = 0.8
    mesh.materials.append(material)
    return _add(collection, root, "globular_ground", mesh)


def _world(output, scene):
    world = scene.world or bpy.data.worlds.new("globular_world")
    scene.world = world
    world.use_nodes = True
    background = world.node_tree.nodes.get("Background")
    if background:
        colour = output.section("render").get("background", [0.86, 0.88, 0.91])
        background.inputs["Color"].default_value = tuple(colour) + (1.0,)
        background.inputs["Strength"].default_value = 0.5


def import_output(context, out_dir, show="mesh", globules=True, volume=True):
    """Builds the scene of the output folder @p out_dir in @p context.scene.
    @param show which of the liquid's forms renders: "mesh", "volume" or "globules" (the
           others are kept, hidden from the render).
    @return a dict of the objects made, and "messages" for whatever was missing."""
    output = scene_files.Output(out_dir)
    scene = context.scene
    collection = bpy.data.collections.new("globular")
    scene.collection.children.link(collection)
    root = _root(collection)
    made = {"root": root, "messages": []}

    if output.frames:
        scene.frame_start, scene.frame_end = output.frames[0], output.frames[-1]
    fps = output.fps
    scene.render.fps = max(1, round(fps))
    scene.render.fps_base = scene.render.fps / fps
    scene[sequences.DIR] = output.dir

    liquid = _liquid_material(output)
    made["surface"] = _sequence(collection, root, "globular_surface", "surface", liquid)
    if volume:
        made["volume"] = _volume(output, collection, root, output.frames[0] if output.frames else 1)
    if globules:
        if scene_files.frames_of(output.dir, scene_files.GLOBULES_PLY):
            obj = _sequence(collection, root, "globular_globules", "globules")
            modifier = obj.modifiers.new("spheres", "NODES")
            modifier.node_group = _sphere_instancer(liquid)
            made["globules"] = obj
        else:
            made["messages"].append(
                "no cache/globules.NNNN.ply: run the scene with [output] ply = true "
                "(--set output.ply=true) to import the globules as points")
    if scene_files.frames_of(output.dir, scene_files.COLLIDER_MESH):
        made["colliders"] = _sequence(collection, root, "globular_colliders", "colliders")
        made["collider_keys"] = _collider_keys(output, collection, root)
    made["camera"] = _camera(output, collection, root, scene)
    made["lights"] = _lights(output, collection, root)
    made["ground"] = _ground(output, collection, root)
    _world(output, scene)

    for key, form in (("surface", "mesh"), ("volume", "volume"), ("globules", "globules")):
        obj = made.get(key)
        if obj is not None:
            obj.hide_render = form != show
    scene.render.use_lock_interface = True  # the handler swaps meshes while rendering
    sequences.load_frame(scene, scene.frame_current)
    return made


def render_frames(scene, frames, directory, samples=16, percent=100, transparent=False):
    """Renders @p frames with Cycles (CPU) into @p directory/frame.NNNN.png.
    @return the paths written."""
    scene.render.engine = "CYCLES"
    scene.cycles.samples = samples
    scene.cycles.device = "CPU"
    if hasattr(scene.cycles, "use_denoising"):
        scene.cycles.use_denoising = False
    scene.render.resolution_percentage = percent
    scene.render.film_transparent = transparent
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    os.makedirs(directory, exist_ok=True)
    written = []
    for frame in frames:
        scene.frame_set(frame)
        path = os.path.join(directory, f"frame.{frame:04d}.png")
        scene.render.filepath = path
        bpy.ops.render.render(write_still=True)
        written.append(path)
    return written

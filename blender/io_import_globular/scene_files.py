# What a globular output folder holds, read without bpy: the resolved scene.toml, the
# render plan, the frame-numbered files, the colliders' poses, and a camera framing the
# caches when no plan gives one (the same view as globular's automatic camera: azimuth
# 30 degrees, elevation 20, the content filling 90 % of the frame).

import math
import os
import re
import tomllib

from . import ply

SURFACE_VDB = ("surface", "surface", ".vdb")
SURFACE_MESH = ("mesh", "surface", ".ply")
GLOBULES_PLY = ("cache", "globules", ".ply")
GLOBULES_VDB = ("cache", "globules", ".vdb")
COLLIDER_MESH = ("mesh", "colliders", ".ply")
COLLIDER_POSES = ("cache", "colliders", ".toml")


def frame_path(out_dir, kind, frame):
    folder, stem, ext = kind
    return os.path.join(out_dir, folder, f"{stem}.{frame:04d}{ext}")


def frames_of(out_dir, kind):
    """The frame numbers of @p kind's files in @p out_dir, sorted."""
    folder, stem, ext = kind
    pattern = re.compile(re.escape(stem) + r"\.(\d{4,})" + re.escape(ext) + "$")
    try:
        names = os.listdir(os.path.join(out_dir, folder))
    except FileNotFoundError:
        return []
    return sorted(int(m.group(1)) for m in map(pattern.match, names) if m)


def read_toml(path):
    with open(path, "rb") as f:
        return tomllib.load(f)


class Output:
    """An output folder: its scene, its plan (or None), its frames."""

    def __init__(self, out_dir):
        self.dir = os.path.abspath(out_dir)
        scene_path = os.path.join(self.dir, "scene.toml")
        if not os.path.isfile(scene_path):
            raise FileNotFoundError(f"{self.dir} holds no scene.toml: not a globular output folder")
        self.scene = read_toml(scene_path)
        plan_path = os.path.join(self.dir, "render_plan.toml")
        self.plan = read_toml(plan_path) if os.path.isfile(plan_path) else None
        frames = set()
        for kind in (GLOBULES_VDB, GLOBULES_PLY, SURFACE_VDB, SURFACE_MESH):
            frames.update(frames_of(self.dir, kind))
        self.frames = sorted(frames)

    def section(self, name):
        return self.scene.get(name, {})

    @property
    def fps(self):
        return float(self.section("simulation").get("fps", 25.0))

    def camera(self, aspect):
        """(position, target, vertical fov in degrees), world Y-up: the render plan's,
        else the scene's fixed [camera], else a framing of the caches."""
        if self.plan and "camera" in self.plan:
            c = self.plan["camera"]
            return tuple(c["position"]), tuple(c["target"]), float(c["fov"])
        c = self.section("camera")
        fov = float(c.get("fov", 40.0))
        if not c.get("auto_frame", True):
            return tuple(c["position"]), tuple(c["target"]), fov
        return frame_bounds(self.bounds(), fov, aspect, self.ground_height())

    def ground_height(self):
        ground = self.section("ground")
        return float(ground.get("height", 0.0)) if ground.get("enabled", True) else None

    def bounds(self):
        """(min, max) over the globules of the first, middle and last PLY caches (or the
        surface meshes), padded by the largest radius; None when there is nothing."""
        low, high = [math.inf] * 3, [-math.inf] * 3
        for kind in (GLOBULES_PLY, SURFACE_MESH):
            frames = frames_of(self.dir, kind)
            if not frames:
                continue
            for frame in {frames[0], frames[len(frames) // 2], frames[-1]}:
                data = ply.read_ply(frame_path(self.dir, kind, frame))
                pad = max(data.vertex.get("radius", [0.0]) or [0.0])
                for a, name in enumerate("xyz"):
                    values = data.vertex.get(name, [])
                    if values:
                        low[a] = min(low[a], min(values) - pad)
                        high[a] = max(high[a], max(values) + pad)
            break
        return None if low[0] == math.inf else (low, high)


def frame_bounds(bounds, fov, aspect, ground):
    """A camera looking at the box @p bounds from azimuth 30, elevation 20 degrees, far
    enough that the box's bounding sphere fills 90 % of the frame's smaller side."""
    if bounds is None:
        bounds = ([-2.0, 0.0, -2.0], [2.0, 1.0, 2.0])
    low, high = list(bounds[0]), list(bounds[1])
    if ground is not None:
        low[1] = min(low[1], ground)
    target = [(a + b) / 2 for a, b in zip(low, high)]
    radius = max(1e-3, 0.5 * math.dist(low, high))
    half = math.radians(fov) / 2
    half = min(half, math.atan(math.tan(half) * aspect))  # the narrower side
    distance = radius / math.sin(half) / 0.9
    az, el = math.radians(30), math.radians(20)
    to_eye = (math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az))
    position = tuple(t + distance * e for t, e in zip(target, to_eye))
    return position, tuple(target), fov


def collider_poses(out_dir):
    """{name: [(frame, rotation 3x3 rows, translation)]} from cache/colliders.NNNN.toml."""
    poses = {}
    for frame in frames_of(out_dir, COLLIDER_POSES):
        data = read_toml(frame_path(out_dir, COLLIDER_POSES, frame))
        for i, c in enumerate(data.get("collider", [])):
            name = c.get("name") or f"collider{i}"
            poses.setdefault(name, []).append((frame, c["rotation"], c["translation"]))
    return poses

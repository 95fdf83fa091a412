# globular: import an output folder of the globular pipeline (surface VDB volumes, the
# surface mesh sequence with velocity, the globules as instanced spheres, the colliders,
# camera, lights, frame range and fps) as a Blender scene. File > Import > globular.

bl_info = {
    "name": "globular output folder",
    "author": "globular",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > globular output folder",
    "description": "Imports a globular simulation's output folder: volumes, meshes, "
                   "globules, colliders, camera and lights",
    "category": "Import-Export",
}

if "bpy" in locals():
    import importlib

    for _module in (ply, scene_files, sequences, build_scene):  # noqa: F821
        importlib.reload(_module)

import bpy
from bpy.props import BoolProperty, EnumProperty, StringProperty

from . import build_scene, ply, scene_files, sequences  # noqa: F401


class ImportGlobular(bpy.types.Operator):
    """Import a globular output folder (the --out DIR of `globular run`)"""

    bl_idname = "import_scene.globular"
    bl_label = "Import globular output folder"
    bl_options = {"REGISTER", "UNDO"}

    directory: StringProperty(name="Output folder", subtype="DIR_PATH")
    filter_folder: BoolProperty(default=True, options={"HIDDEN"})
    show: EnumProperty(
        name="Render",
        description="Which form of the liquid renders (the others are kept, hidden)",
        items=(("mesh", "Surface mesh", "mesh/surface.NNNN.ply, with motion blur"),
               ("volume", "Volume", "surface/surface.NNNN.vdb, grid density"),
               ("globules", "Globules", "cache/globules.NNNN.ply as spheres")),
        default="mesh")
    globules: BoolProperty(name="Globules", default=True,
                           description="Import cache/globules.NNNN.ply as instanced spheres")
    volume: BoolProperty(name="Volume", default=True,
                         description="Import surface/surface.NNNN.vdb as a volume sequence")

    def execute(self, context):
        try:
            made = build_scene.import_output(context, self.directory, show=self.show,
                                             globules=self.globules, volume=self.volume)
        except (OSError, ValueError, KeyError, ply.PlyError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        for message in made["messages"]:
            self.report({"WARNING"}, message)
        return {"FINISHED"}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


def _menu(self, context):
    self.layout.operator(ImportGlobular.bl_idname, text="globular output folder")


def register():
    bpy.utils.register_class(ImportGlobular)
    bpy.types.TOPBAR_MT_file_import.append(_menu)
    sequences.register()


def unregister():
    sequences.unregister()
    bpy.types.TOPBAR_MT_file_import.remove(_menu)
    bpy.utils.unregister_class(ImportGlobular)

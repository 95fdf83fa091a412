# Headless import (and render) of a globular output folder, without installing the
# add-on:
#   blender -b --python blender/globular_import.py -- OUT_DIR [--render N|A-B]
#           [--samples S] [--percent P] [--show mesh|volume|globules] [--transparent]
#           [--save FILE.blend]
# --render renders those frames with Cycles into OUT_DIR/blender/frame.NNNN.png.
# Exit status 0 on success, 1 when the import or a render failed, 2 for bad arguments.

import argparse
import os
import sys
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402

import io_import_globular  # noqa: E402
from io_import_globular import build_scene  # noqa: E402


def frames_of(text):
    first, _, last = text.partition("-")
    return list(range(int(first), int(last or first) + 1))


def main(argv):
    parser = argparse.ArgumentParser(prog="blender -b --python globular_import.py --")
    parser.add_argument("out_dir")
    parser.add_argument("--render", type=frames_of, metavar="N|A-B")
    parser.add_argument("--samples", type=int, default=16)
    parser.add_argument("--percent", type=int, default=100)
    parser.add_argument("--show", choices=("mesh", "volume", "globules"), default="mesh")
    parser.add_argument("--transparent", action="store_true")
    parser.add_argument("--save", metavar="FILE.blend")
    args = parser.parse_args(argv)

    # An empty scene: the default cube, light and camera are not part of the shot. (Before
    # registering: reading the home file may reset the add-ons to the preferences'.)
    bpy.ops.wm.read_homefile(use_empty=True)
    io_import_globular.register()
    made = build_scene.import_output(bpy.context, args.out_dir, show=args.show)
    for message in made["messages"]:
        print("globular:", message)
    scene = bpy.context.scene
    print(f"globular: imported {args.out_dir}, frames {scene.frame_start}-{scene.frame_end}")
    if args.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save))
    if args.render:
        for path in build_scene.render_frames(scene, args.render,
                                              os.path.join(args.out_dir, "blender"),
                                              args.samples, args.percent, args.transparent):
            print("globular: wrote", path)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    try:
        main(argv)
    except SystemExit as e:
        sys.stdout.flush()
        os._exit(2 if e.code else 0)
    except Exception:  # Blender's -b --python exits 0 after an uncaught error
        traceback.print_exc()
        sys.stdout.flush()
        os._exit(1)
    sys.stdout.flush()
    os._exit(0)

# Manual check that a crowd file opens in Blender (not part of CI; Blender is not a dependency):
#   blender -b --factory-startup --python scripts/check_glb_in_blender.py -- CROWD.glb [frame.png]
# Imports the .glb with Blender's own glTF importer and prints what it made: armatures (24 bones each),
# skinned meshes (vertex counts, armature modifier), actions (frame ranges), and the world position of
# one character's head bone at the first and last frame (so you can see that it moves). With a PNG path
# it also renders one frame with Workbench from a camera framing the crowd.
import sys

import bpy
import numpy

if not hasattr(numpy, "bool"):  # Debian 12: Blender 3.4's importer uses np.bool, removed in numpy 1.24
    numpy.bool = bool

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not args:
    sys.exit("usage: blender -b --python check_glb_in_blender.py -- CROWD.glb [frame.png]")
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=args[0])
arms = [o for o in bpy.data.objects if o.type == "ARMATURE"]
meshes = [o for o in bpy.data.objects if o.type == "MESH"]
skinned = [o for o in meshes if any(m.type == "ARMATURE" for m in o.modifiers)]
print("armatures:", len(arms), "bones per armature:", sorted({len(a.data.bones) for a in arms}))
print("meshes:", len(meshes), "skinned:", len(skinned),
      "vertex counts:", sorted({len(o.data.vertices) for o in skinned}))
print("actions:", len(bpy.data.actions),
      "frame ranges:", sorted({tuple(int(x) for x in a.frame_range) for a in bpy.data.actions}))
scene = bpy.context.scene
if arms:
    arm = arms[0]
    if arm.animation_data and arm.animation_data.action:
        first, last = (int(x) for x in arm.animation_data.action.frame_range)
        for f in (first, last):
            scene.frame_set(f)
            head = arm.pose.bones.get("head")
            if head:
                print("frame", f, arm.name, "head at", tuple(round(v, 3) for v in (arm.matrix_world @ head.head)))
if len(args) > 1:
    import mathutils
    lo = mathutils.Vector((1e9, 1e9, 1e9))
    hi = -lo
    for o in skinned:
        for c in o.bound_box:
            w = o.matrix_world @ mathutils.Vector(c)
            lo = mathutils.Vector(map(min, lo, w))
            hi = mathutils.Vector(map(max, hi, w))
    centre = (lo + hi) / 2
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    scene.collection.objects.link(cam)
    size = max((hi - lo).length, 2.0)
    cam.location = centre + mathutils.Vector((0.0, -1.2 * size, 0.5 * size))
    cam.rotation_euler = (centre - cam.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x, scene.render.resolution_y = 640, 360
    scene.render.filepath = args[1]
    scene.frame_set(scene.frame_start)
    bpy.ops.render.render(write_still=True)
    print("rendered", args[1])

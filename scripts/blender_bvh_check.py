# Usage: KLAW_BVH_OUT=DIR cargo test --release --test export bvh_forward
#        blender -b --factory-startup --python scripts/blender_bvh_check.py -- DIR
# Import walk.bvh with Blender's own BVH importer (scale 1, no axis conversion: forward Y, up Z
# maps the file's axes to Blender's unchanged) and compare the posed bone heads with expected.json.
import bpy, json, sys, builtins
# Debian's Blender 3.4 runs on Python 3.11, which removed the 'U' open mode its BVH importer still
# passes ('rU'); drop the 'U' (universal newlines are the default anyway).
_open = builtins.open
builtins.open = lambda f, mode="r", *a, **k: _open(f, mode.replace("U", ""), *a, **k)
d = (sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else ".").rstrip("/") + "/"
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_anim.bvh(filepath=d + "walk.bvh", global_scale=1.0, axis_forward='Y', axis_up='Z',
                        rotate_mode='NATIVE', frame_start=1, use_fps_scale=False, update_scene_fps=True)
arm = [o for o in bpy.data.objects if o.type == 'ARMATURE'][0]
exp = json.load(open(d + "expected.json"))
scene = bpy.context.scene
print("scene fps", scene.render.fps, scene.render.fps_base, "frames", scene.frame_start, scene.frame_end)
print("rest bone lengths:", {b.name: round(b.length, 4) for b in arm.data.bones if b.name in ("RightLeg", "RightUpLeg", "RightFoot", "RightToeBase", "Hips", "Spine")})
worst = (0.0, None)
for i, e in enumerate(exp):
    scene.frame_set(1 + i)
    for name, want in e.items():
        bone, _, part = name.partition(".")
        pb = arm.pose.bones[bone]
        p = arm.matrix_world @ (pb.tail if part == "tail" else pb.head)
        err = max(abs(p[k] - want[k]) for k in range(3))
        if err > worst[0]:
            worst = (err, (i, name, tuple(p), want))
print("BLENDER max |error| over %d frames: %.3e m at %s" % (len(exp), worst[0], worst[1]))

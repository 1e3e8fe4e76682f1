# Renders a glTF with Cycles and writes its Vector pass (multilayer EXR). Blender 3.4 (Debian 12):
#   blender -b --factory-startup -t 1 --python blender_vector_pass.py -- FRAME OUT.exr W H SCENE.gltf
# Blender frame F is glTF time F/24 (its importer maps time 0 to frame 0): kiln --frame F+1.
import bpy, sys
import numpy as np
if not hasattr(np, "bool_alias_fix"): np.bool = bool  # Debian blender 3.4 importer uses removed np.bool
argv=sys.argv[sys.argv.index('--')+1:]
frame=int(argv[0]); out=argv[1]; W=int(argv[2]); H=int(argv[3]); scene_file=argv[4]
for o in list(bpy.data.objects): bpy.data.objects.remove(o)
sc=bpy.context.scene
sc.render.fps=24; sc.render.fps_base=1.0
bpy.ops.import_scene.gltf(filepath=scene_file)
for a in bpy.data.actions:
    print('ACTION',a.name,tuple(a.frame_range))
    for fc in a.fcurves:
        k=fc.keyframe_points; print('  fc',fc.data_path,fc.array_index,k[0].co[:],k[1].co[:],k[-1].co[:],k[0].interpolation)
for o in bpy.data.objects: print('OBJ',o.name,o.type,tuple(o.location),tuple(o.rotation_euler), o.rotation_mode, o.parent.name if o.parent else None)
cam=[o for o in bpy.data.objects if o.type=='CAMERA'][0]
sc.camera=cam
print('CAM',cam.data.type,cam.data.sensor_fit,cam.data.angle_y,cam.data.angle_x)
sc.frame_start=1
sc.render.engine='CYCLES'
sc.cycles.device='CPU'; sc.cycles.samples=1; sc.cycles.use_denoising=False
sc.cycles.pixel_filter_type='BOX'; sc.cycles.filter_width=1.0
sc.cycles.use_adaptive_sampling=False
sc.render.threads_mode='FIXED'; sc.render.threads=1
sc.render.resolution_x=W; sc.render.resolution_y=H; sc.render.resolution_percentage=100
sc.render.use_motion_blur=False
sc.render.film_transparent=True
vl=sc.view_layers[0]; vl.use_pass_vector=True; vl.use_pass_z=True
sc.render.image_settings.file_format='OPEN_EXR_MULTILAYER'
sc.render.image_settings.color_depth='32'
sc.frame_set(frame)
sc.render.filepath=out
bpy.ops.render.render(write_still=True)
print('WROTE',out)

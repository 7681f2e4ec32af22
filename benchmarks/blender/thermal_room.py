# Blender's Cycles as a peer renderer for hoilcd's frames: builds a rendered dataset's room (its
# scene.json: room, tables, chairs and one seated person per seat, from the repo's glTF assets)
# with emission-only materials whose strength follows each glTF material's temperature_c, then
# renders the dataset's camera poses (poses.csv) at the dataset's size with Cycles on the CPU,
# 1 sample, no denoising, N threads, and prints frames per second of the render calls alone.
# Run: blender -b --factory-startup --python benchmarks/blender/thermal_room.py -- DATASET [--frames N] [--threads N]
# (benchmarks/blender/run.sh wraps it).
import argparse
import csv
import json
import math
import os
import shutil
import sys
import tempfile
import time

import bpy
import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which Debian's numpy 1.24 removed.
if "bool" not in vars(numpy):
    numpy.bool = bool

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="thermal_room.py")
    p.add_argument("dataset", help="a hoilcd dataset folder (scene.json, poses.csv)")
    p.add_argument("--frames", type=int, default=200, help="frames to render (evenly spread over poses.csv)")
    p.add_argument("--threads", type=int, default=2, help="Cycles CPU threads")
    p.add_argument("--warmup", type=int, default=3, help="frames rendered before timing starts")
    p.add_argument("--still", metavar="PNG", help="render only the pose of frame --still-frame to PNG (to compare "
                   "with the dataset's thermal frame), no timing")
    p.add_argument("--still-frame", type=int, default=0, help="frame of poses.csv for --still")
    a = p.parse_args(argv)
    if a.frames < 1 or a.threads < 1 or a.warmup < 0:
        p.error("--frames and --threads must be positive, --warmup non-negative")
    return a


def fail(message):
    print("thermal_room.py: " + message, file=sys.stderr)
    sys.exit(2)


def emission_material(name, temperature_c, display_min_c, display_max_c):
    # Emission only: strength linear over the display window, as the 8-bit thermal frame.
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    level = (temperature_c - display_min_c) / (display_max_c - display_min_c)
    emission.inputs["Strength"].default_value = min(max(level, 0.0), 1.0)
    out = nodes.new("ShaderNodeOutputMaterial")
    mat.node_tree.links.new(emission.outputs["Emission"], out.inputs["Surface"])
    return mat


def asset_template(name, window):
    # Imports assets/NAME.gltf once, swaps its materials for emission-only ones, hides it.
    path = os.path.join(REPO, "assets", name + ".gltf")
    if not os.path.exists(path):
        fail("missing asset " + path)
    with open(path) as f:
        gltf = json.load(f)
    temps = {m.get("name", ""): m.get("extras", {}).get("temperature_c", 22.0) for m in gltf.get("materials", [])}
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=path)
    objects = [o for o in bpy.data.objects if o not in before]
    for o in objects:
        if o.type != "MESH":
            continue
        for slot in o.material_slots:
            base = slot.material.name.split(".")[0] if slot.material else ""
            slot.material = emission_material(name + ":" + base, temps.get(base, 22.0), *window)
    meshes = [o for o in objects if o.type == "MESH"]
    for o in objects:
        o.hide_render = True
        o.hide_viewport = True
    return meshes


def place(template, x, y, yaw_rad):
    # A linked copy of the asset's meshes at (x, y) on the floor, turned by yaw (asset +x forward).
    for source in template:
        copy = source.copy()  # shares the mesh data
        copy.hide_render = False
        copy.hide_viewport = False
        bpy.context.scene.collection.objects.link(copy)
        # The glTF importer turns glTF +Y up into Blender +Z up; the asset's front (+Z in glTF)
        # becomes Blender -Y, so a further -90 deg makes it face +x before the seat's yaw.
        copy.matrix_world = source.matrix_world.copy()
        copy.rotation_mode = "XYZ"
        copy.location = (x, y, 0.0)
        copy.rotation_euler[2] += yaw_rad + math.pi / 2


def main():
    args = parse_args()
    scene_path = os.path.join(args.dataset, "scene.json")
    poses_path = os.path.join(args.dataset, "poses.csv")
    for p in (scene_path, poses_path):
        if not os.path.exists(p):
            fail(p + " does not exist: DATASET must be a hoilcd dataset folder")
    with open(scene_path) as f:
        scene = json.load(f)
    with open(poses_path) as f:
        poses = list(csv.DictReader(f))
    if not poses:
        fail(poses_path + " has no poses")
    camera = scene["camera"]
    window = (camera["display_min_c"], camera["display_max_c"])
    furniture = scene["furniture"]

    bpy.ops.wm.read_factory_settings(use_empty=True)
    s = bpy.context.scene
    s.render.engine = "CYCLES"
    s.cycles.device = "CPU"
    s.cycles.samples = 1
    s.cycles.use_adaptive_sampling = False
    s.cycles.use_denoising = False
    s.cycles.max_bounces = 0  # emission only: no bounce can add anything
    s.render.threads_mode = "FIXED"
    s.render.threads = args.threads
    s.render.resolution_x = camera["width_px"]
    s.render.resolution_y = camera["height_px"]
    s.render.resolution_percentage = 100
    s.render.use_persistent_data = True  # keep the BVH between frames: only the camera moves
    s.render.film_transparent = False
    s.world = bpy.data.worlds.new("room")
    s.view_settings.view_transform = "Raw"  # linear strength -> grey level, as the 8-bit frame

    # The room: an inward-facing box at the environment temperature.
    sx, sy, sz = scene["room"]["size_m"]
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(sx / 2, sy / 2, sz / 2))
    room = bpy.context.active_object
    room.scale = (sx, sy, sz)
    room.data.materials.append(emission_material("room", scene["room"]["environment_temperature_c"], *window))

    table = asset_template(furniture["table_asset"], window)
    chair = asset_template(furniture["chair_asset"], window)
    person = asset_template("person_seated_upright", window)
    per_table = scene["crowd"]["people_per_table"]
    per_side = 3 if per_table > 4 else 2
    spacing = furniture["seat_spacing_6_m"] if per_side == 3 else furniture["seat_spacing_4_m"]
    half_depth = 0.75 / 2  # table.gltf: 0.75 m along its y
    seats = 0
    for t in scene["tables"]:
        cx, cy = t["center_m"]
        yaw = math.radians(t["yaw_deg"])
        place(table, cx, cy, yaw)
        for side in (0, 1):
            for k in range(per_side):
                along = (k - 0.5 * (per_side - 1)) * spacing
                across = (-1.0 if side == 0 else 1.0) * (half_depth + furniture["seat_setback_m"])
                x = cx + math.cos(yaw) * along - math.sin(yaw) * across
                y = cy + math.sin(yaw) * along + math.cos(yaw) * across
                seat_yaw = yaw + (math.pi / 2 if side == 0 else -math.pi / 2)
                place(chair, x, y, seat_yaw)
                if seats < per_table * len(scene["tables"]) and k + side * per_side < per_table:
                    place(person, x, y, seat_yaw)
                    seats += 1

    cam_data = bpy.data.cameras.new("thermal")
    cam_data.sensor_fit = "HORIZONTAL"
    cam_data.angle_x = math.radians(camera["hfov_deg"])
    cam = bpy.data.objects.new("thermal", cam_data)
    s.collection.objects.link(cam)
    s.camera = cam
    cam.rotation_mode = "XYZ"

    def set_pose(row):
        cam.location = (float(row["cam_x"]), float(row["cam_y"]), float(row["cam_z"]))
        # A Blender camera looks along its -Z with +Y up: x 90 deg looks along +Y, then pitch
        # (positive = down) and yaw (counter-clockwise from +x) as hoilcd's camera.
        cam.rotation_euler = (math.pi / 2 - float(row["cam_pitch"]), float(row["cam_roll"]),
                              float(row["cam_yaw"]) - math.pi / 2)

    if args.still:
        set_pose(poses[min(max(args.still_frame, 0), len(poses) - 1)])
        s.render.image_settings.file_format = "PNG"
        s.render.filepath = os.path.abspath(args.still)
        bpy.ops.render.render(write_still=True)
        return

    picks = [poses[(2 * i + 1) * len(poses) // (2 * args.frames)] for i in range(args.frames)]
    # One animation render over the keyframed camera, as `blender -a` renders a sequence (a
    # render call per frame re-syncs the scene and is ~20x slower). Frames are written as
    # uncompressed BMP to a temporary folder, the cheapest output Blender has, then deleted.
    for i, row in enumerate([picks[0]] * args.warmup + picks):
        set_pose(row)
        cam.keyframe_insert("location", frame=i + 1)
        cam.keyframe_insert("rotation_euler", frame=i + 1)
    out_dir = tempfile.mkdtemp(prefix="hoilcd-blender-")
    s.render.image_settings.file_format = "BMP"
    s.render.filepath = os.path.join(out_dir, "f")
    times, cpu = [], []  # wall and process CPU (all threads) at each frame's start
    bpy.app.handlers.render_pre.append(lambda *_: (times.append(time.perf_counter()), cpu.append(time.process_time())))
    s.frame_start, s.frame_end = 1, args.warmup + args.frames
    bpy.ops.render.render(animation=True)
    times.append(time.perf_counter())
    cpu.append(time.process_time())
    shutil.rmtree(out_dir)
    seconds = times[-1] - times[args.warmup]
    cpu_seconds = cpu[-1] - cpu[args.warmup]
    tris = sum(len(o.data.polygons) for o in s.objects if o.type == "MESH" and not o.hide_render)
    print("blender %s cycles cpu: %d frames %dx%d, %d thread(s), 1 sample, no denoise, %d people, "
          "%d polygons: %.2f s (%.1f ms per frame, process CPU %.1f ms), %.1f fps" % (
              bpy.app.version_string, args.frames, camera["width_px"], camera["height_px"], args.threads, seats,
              tris, seconds, 1e3 * seconds / args.frames, 1e3 * cpu_seconds / args.frames, args.frames / seconds))


main()

# Renders an animated glTF binary of a run (`up export-gltf`) with Cycles on
# the CPU, headless, as `make render` does:
#
#   blender -b --factory-startup --python-exit-code 1 --python tools/render/render_gltf.py -- \
#     --glb run.glb --out DIR [--frames N | A-B] [--samples 64] [--size 960x600] [--fps 30]
#
# Blender's own glTF importer reads the file; the lights and the world are
# then the page's photo mode's (web/src/render/photo/photoLights.ts, with the
# numbers of web/src/render/roomLights.ts): an area lamp above the ceiling, the
# warm fill lamp, a sky graded from warm above to dim below, and the page's
# background colour behind the room. The room's faces are one-sided, as the
# page draws them (seen from outside, the near walls vanish; the lamp above
# the ceiling shines through it): Cycles has no one-sided faces, so their
# backs are made transparent, and they cast no shadow, as on the page. The camera is the file's. Each frame is written
# as DIR/frame_NNNN.png with one progress line; several frames are also
# encoded into DIR/clip.mp4 (H.264, by Blender's own FFmpeg).

import argparse
import json
import math
import os
import struct
import sys
import time
from array import array
from contextlib import contextmanager

import bpy
from mathutils import Vector

# The numbers the page lights its room with (web/src/render/roomLights.ts).
BACKGROUND_COLOR = 0x1D2230
SKY_ABOVE, SKY_BELOW = 0xFFF6E8, 0x40362C
SKY_EXPONENT = 2
ENVIRONMENT_INTENSITY = 0.55
LAMP_COLOR = 0xFFF1DC
AREA_LAMP_RADIANCE = 9
FILL_COLOR = 0xFFE2C0

# Objects the exporter names for what moves; everything else is the room or its furniture.
MOVING_PREFIXES = ("balloon-", "ribbon-", "weight-")


def parse_args(argv):
    parser = argparse.ArgumentParser(prog="render_gltf.py", description="Render an animated .glb with Cycles on the CPU.")
    parser.add_argument("--glb", required=True, help="the animated glTF binary")
    parser.add_argument("--out", required=True, help="directory for frame_NNNN.png (and clip.mp4)")
    parser.add_argument("--frames", default="0", help="a frame N, or frames A-B, at --fps from the animation's start")
    parser.add_argument("--samples", type=int, default=64, help="Cycles samples per pixel")
    parser.add_argument("--size", default="960x600", help="WIDTHxHEIGHT in pixels")
    parser.add_argument("--fps", type=int, default=30, help="frames per second of the animation's clock")
    parser.add_argument("--threads", type=int, default=0, help="render threads (0: every core)")
    parser.add_argument("--camera", choices=("file", "home"), default="file",
                        help="the file's camera, or the page's home view (outside the room, looking in)")
    parser.add_argument("--keep-file-lights", action="store_true", help="keep the file's own lights as well as the page's")
    parser.add_argument("--verbose", action="store_true", help="show Blender's own per-sample output")
    args = parser.parse_args(argv)
    try:
        first, _, last = args.frames.partition("-")
        args.first, args.last = int(first), int(last or first)
        width, _, height = args.size.partition("x")
        args.width, args.height = int(width), int(height)
    except ValueError:
        parser.error(f"--frames takes N or A-B and --size WIDTHxHEIGHT (got {args.frames!r}, {args.size!r})")
    if args.first < 0 or args.last < args.first:
        parser.error(f"--frames {args.frames}: frames count up from 0")
    if args.samples < 1 or args.width < 1 or args.height < 1 or args.fps < 1:
        parser.error("--samples, --size and --fps take positive numbers")
    if args.last > args.first and (args.width % 2 or args.height % 2):
        parser.error(f"--size {args.size}: the clip of several frames (H.264) needs an even width and height")
    return args


def say(text):
    """A line of our own on the terminal, even while Blender's output is silenced."""
    os.write(say.fd, (text + "\n").encode())


say.fd = os.dup(1)


@contextmanager
def quiet(enabled):
    """Blender's renderer prints a line per sample: sends stdout to /dev/null meanwhile."""
    if not enabled:
        yield
        return
    sys.stdout.flush()
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    try:
        yield
    finally:
        os.dup2(say.fd, 1)
        os.close(devnull)


def linear(hex_color):
    """A three.js colour (sRGB hex) in the linear space both renderers light in."""
    def channel(c):
        c /= 255
        return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4

    return tuple(channel((hex_color >> s) & 0xFF) for s in (16, 8, 0))


def to_blender(x, y, z):
    """glTF's y-up axes to Blender's z-up ones (as the importer turns them)."""
    return Vector((x, -z, y))


def gltf_cameras(path):
    """The file's cameras' vertical fields of view, radians, in file order."""
    with open(path, "rb") as f:
        header = f.read(20)
        magic, _, _, length, kind = struct.unpack("<4sIII4s", header)
        if magic != b"glTF" or kind != b"JSON":
            raise SystemExit(f"{path} is not a glTF binary")
        doc = json.loads(f.read(length))
    return [c["perspective"]["yfov"] for c in doc.get("cameras", []) if c.get("type") == "perspective"]


def import_glb(path, fps):
    try:
        import numpy
    except ImportError:
        raise SystemExit("Blender's glTF importer needs numpy: apt-get install python3-numpy (make render does)")
    # Debian's Blender 3.4 importer still spells numpy.bool, which numpy 1.24 removed.

    if "bool" not in vars(numpy):
        numpy.bool = bool
    bpy.ops.wm.read_factory_settings(use_empty=True)
    # The importer turns the file's seconds into frames at the scene's rate.
    bpy.context.scene.render.fps = fps
    bpy.context.scene.render.fps_base = 1
    bpy.ops.import_scene.gltf(filepath=path)


def animation_range():
    """First and last keyed frame over every imported action, or (0, 0) for a still scene."""
    ranges = [a.frame_range for a in bpy.data.actions]
    if not ranges:
        return 0, 0
    return round(min(r[0] for r in ranges)), round(max(r[1] for r in ranges))


def is_moving(obj):
    while obj is not None:
        if obj.name.startswith(MOVING_PREFIXES) or obj.animation_data or obj.type == "ARMATURE":
            return True
        obj = obj.parent
    return False


def room_box(scene):
    """Half-width, half-depth and top of the static meshes (the room is centred on the origin), m."""
    corners = [
        obj.matrix_world @ Vector(c)
        for obj in scene.objects
        if obj.type == "MESH" and not is_moving(obj)
        for c in obj.bound_box
    ]
    if not corners:
        raise SystemExit("the file has no room: no mesh that stays still")
    half_width = max(abs(c.x) for c in corners)
    half_depth = max(abs(c.y) for c in corners)
    top = max(c.z for c in corners)
    return half_width, half_depth, top


def one_sided_room(scene):
    """The room's one-sided faces (glTF doubleSided false) as the page has them: sight and light
    pass through their backs, and they cast no shadow (room.ts), so the lamp above the ceiling
    and the sky light the room inside."""
    done = set()
    for obj in scene.objects:
        if obj.type != "MESH" or is_moving(obj):
            continue
        one_sided = [m for m in obj.data.materials if m is not None and m.use_backface_culling and m.use_nodes]
        if not one_sided:
            continue
        obj.visible_shadow = False
        for mat in one_sided:
            if mat.name in done:
                continue
            done.add(mat.name)
            nodes, links = mat.node_tree.nodes, mat.node_tree.links
            output = next(n for n in nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output)
            surface = output.inputs["Surface"]
            if not surface.links:
                continue
            front = surface.links[0].from_socket
            mix = nodes.new("ShaderNodeMixShader")
            backs = nodes.new("ShaderNodeNewGeometry")
            clear = nodes.new("ShaderNodeBsdfTransparent")
            links.new(backs.outputs["Backfacing"], mix.inputs["Fac"])
            links.new(front, mix.inputs[1])
            links.new(clear.outputs["BSDF"], mix.inputs[2])
            links.new(mix.outputs["Shader"], surface)


def add_lights(scene, half_width, half_depth, top, keep_file_lights):
    if not keep_file_lights:
        for obj in [o for o in scene.objects if o.type == "LIGHT"]:
            bpy.data.objects.remove(obj)

    # roomLights.ts areaLamp(): above the ceiling, facing down (Blender's area lights face -z).
    width, depth = half_width * 1.2, half_depth * 1.2
    lamp = bpy.data.lights.new("ceiling lamps", "AREA")
    lamp.shape = "RECTANGLE"
    lamp.size, lamp.size_y = width, depth
    lamp.color = linear(LAMP_COLOR)
    # The page's lamp is a radiance; Cycles takes an area light's power, and a lamp of power P
    # and area A shines as an emitting surface of radiance P / 4A (measured: a white floor
    # under either, 1 m below a 1 m² lamp).
    lamp.energy = AREA_LAMP_RADIANCE * 4 * width * depth
    lamp_obj = bpy.data.objects.new("ceiling lamps", lamp)
    lamp_obj.location = to_blender(half_width * 0.3, top + 1.5, half_depth * 0.45)
    scene.collection.objects.link(lamp_obj)

    # roomLights.ts placeFillLamp(): warm, low in the far corner, brighter in a larger room.
    # Its intensity is in candela; a Cycles point light's power is 4π times its intensity
    # (measured as the area lamp's).
    # (The page's light fades as distance^-1.6, Cycles' as distance^-2.)
    fill = bpy.data.lights.new("fill lamp", "POINT")
    fill.color = linear(FILL_COLOR)
    fill.energy = 4 * math.pi * 2 * max(1.0, half_width * half_depth / 9)
    fill.shadow_soft_size = 0.1
    fill_obj = bpy.data.objects.new("fill lamp", fill)
    fill_obj.location = to_blender(-half_width * 0.4, top * 0.8, -half_depth * 0.3)
    scene.collection.objects.link(fill_obj)


def add_world(scene):
    """photoLights.ts: the graded sky lights the room; camera rays see the page's background colour."""
    world = bpy.data.worlds.new("room")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    coords = nodes.new("ShaderNodeTexCoord")
    xyz = nodes.new("ShaderNodeSeparateXYZ")
    links.new(coords.outputs["Generated"], xyz.inputs["Vector"])
    # t = (up · 0.5 + 0.5)^exponent, as three-gpu-pathtracer's GradientEquirectTexture.
    half = nodes.new("ShaderNodeMath")
    half.operation = "MULTIPLY_ADD"
    half.inputs[1].default_value = 0.5
    half.inputs[2].default_value = 0.5
    links.new(xyz.outputs["Z"], half.inputs[0])
    power = nodes.new("ShaderNodeMath")
    power.operation = "POWER"
    power.inputs[1].default_value = SKY_EXPONENT
    links.new(half.outputs["Value"], power.inputs[0])
    grade = nodes.new("ShaderNodeMixRGB")
    grade.inputs["Color1"].default_value = (*linear(SKY_BELOW), 1)
    grade.inputs["Color2"].default_value = (*linear(SKY_ABOVE), 1)
    links.new(power.outputs["Value"], grade.inputs["Fac"])
    sky = nodes.new("ShaderNodeBackground")
    sky.inputs["Strength"].default_value = ENVIRONMENT_INTENSITY
    links.new(grade.outputs["Color"], sky.inputs["Color"])
    backdrop = nodes.new("ShaderNodeBackground")
    backdrop.inputs["Color"].default_value = (*linear(BACKGROUND_COLOR), 1)
    path = nodes.new("ShaderNodeLightPath")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    links.new(sky.outputs["Background"], mix.inputs[1])
    links.new(backdrop.outputs["Background"], mix.inputs[2])
    output = nodes.new("ShaderNodeOutputWorld")
    links.new(mix.outputs["Shader"], output.inputs["Surface"])
    scene.world = world


def pick_camera(scene, yfovs, box, which):
    cameras = [o for o in scene.objects if o.type == "CAMERA"]
    if cameras and which == "file":
        cam = cameras[0]
        if len(cameras) == len(yfovs):
            # The file's vertical field of view, whatever the picture's shape (the page keeps it too).
            cam.data.sensor_fit = "VERTICAL"
            cam.data.angle_y = yfovs[0]
        scene.camera = cam
        return "the file's camera"
    # None in the file: the page's home view (controls.ts), outside the room looking at its centre.
    half_width, half_depth, top = box
    size = max(half_width * 2, half_depth * 2, top)
    distance, azimuth, elevation = size * 1.3 + 1, 0.6, 0.03
    centre = (0, top * 0.55, 0)
    horizontal = distance * math.cos(elevation)
    eye = to_blender(
        centre[0] + horizontal * math.sin(azimuth),
        centre[1] + distance * math.sin(elevation),
        centre[2] + horizontal * math.cos(azimuth),
    )
    data = bpy.data.cameras.new("home view")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(45)
    cam = bpy.data.objects.new("home view", data)
    cam.location = eye
    cam.rotation_euler = (to_blender(*centre) - eye).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(cam)
    scene.camera = cam
    return "the page's home view" + ("" if cameras else " (the file has no camera)")


def set_up_cycles(scene, args):
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = args.samples
    # Debian's Blender is built without OpenImageDenoise: the samples alone clear the noise.
    scene.cycles.use_denoising = False
    # Light focused through the balloons' thin latex and off the foil shows as speckles long
    # before it converges: no caustics, and glossy bounces blurred (the page's tracer filters
    # them as well, filterGlossyFactor).
    scene.cycles.caustics_reflective = False
    scene.cycles.caustics_refractive = False
    scene.cycles.blur_glossy = 1.0
    scene.render.resolution_x, scene.render.resolution_y = args.width, args.height
    scene.render.resolution_percentage = 100
    scene.render.fps, scene.render.fps_base = args.fps, 1
    if args.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = args.threads
    # The page tone-maps with ACES filmic; Blender's Filmic is its counterpart.
    scene.view_settings.view_transform = "Filmic"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.film_transparent = False


def mean_level(path):
    """Mean of the PNG's RGB values, 0–1: a black or blown-out frame shows in the progress line."""
    image = bpy.data.images.load(path)
    pixels = array("f", bytes(4 * len(image.pixels)))
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    total = sum(pixels) - sum(pixels[3::4])
    return total / max(1, len(pixels) * 3 // 4)


def render_frames(scene, args):
    paths = []
    count = args.last - args.first + 1
    for k, frame in enumerate(range(args.first, args.last + 1)):
        scene.frame_set(frame)
        path = os.path.join(args.out, f"frame_{frame:04d}.png")
        scene.render.filepath = path
        started = time.monotonic()
        with quiet(not args.verbose):
            bpy.ops.render.render(write_still=True)
        seconds = time.monotonic() - started
        say(f"frame {frame} ({k + 1}/{count}, t = {frame / args.fps:.2f} s): {seconds:.1f} s, "
            f"{os.path.getsize(path) / 1024:.0f} kB, mean level {mean_level(path):.3f} -> {path}")
        paths.append(path)
    return paths


def encode_clip(paths, args):
    """The frames as an H.264 MP4 beside them, through Blender's sequencer (no new render)."""
    video = bpy.data.scenes.new("clip")
    video.render.resolution_x, video.render.resolution_y = args.width, args.height
    video.render.resolution_percentage = 100
    video.render.fps, video.render.fps_base = args.fps, 1
    # The frames are already tone-mapped: shown as they are.
    video.view_settings.view_transform = "Standard"
    video.sequence_editor_create()
    strip = video.sequence_editor.sequences.new_image("frames", paths[0], channel=1, frame_start=1)
    for path in paths[1:]:
        strip.elements.append(os.path.basename(path))
    video.frame_start, video.frame_end = 1, len(paths)
    settings = video.render.image_settings
    settings.file_format = "FFMPEG"
    video.render.ffmpeg.format = "MPEG4"
    video.render.ffmpeg.codec = "H264"
    video.render.ffmpeg.constant_rate_factor = "HIGH"
    out = os.path.join(args.out, "clip.mp4")
    video.render.filepath = out
    video.render.use_file_extension = False
    started = time.monotonic()
    with quiet(not args.verbose):
        bpy.ops.render.render(animation=True, scene=video.name)
    say(f"clip: {len(paths)} frames at {args.fps} fps in {time.monotonic() - started:.1f} s, "
        f"{os.path.getsize(out) / 1024:.0f} kB -> {out}")


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    args = parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    started = time.monotonic()
    with quiet(not args.verbose):
        import_glb(args.glb, args.fps)
    scene = bpy.context.scene
    first, last = animation_range()
    if args.last > last:
        raise SystemExit(f"frame {args.last} is past the animation's end (frames {first}-{last} at {args.fps} fps): export more seconds")
    box = room_box(scene)
    one_sided_room(scene)
    add_lights(scene, *box, args.keep_file_lights)
    add_world(scene)
    camera = pick_camera(scene, gltf_cameras(args.glb), box, args.camera)
    set_up_cycles(scene, args)
    say(f"{args.glb}: frames {first}-{last}, room {2 * box[0]:.1f} x {2 * box[1]:.1f} x {box[2]:.1f} m, {camera}; "
        f"imported in {time.monotonic() - started:.1f} s; rendering {args.width}x{args.height}, {args.samples} samples, Cycles on the CPU")
    paths = render_frames(scene, args)
    if len(paths) > 1:
        encode_clip(paths, args)


main()

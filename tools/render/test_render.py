# The render script's test (make test-render, where Blender is installed): a
# short export of the default room (`up export-gltf`), rendered by Blender
# through render_gltf.py at a tiny size and a few samples. Each frame must come
# with its progress line, be a PNG of the size asked for and be neither black
# nor blown out; the frames must differ (the balloons move); several frames
# make an MP4 beside them; a frame past the run's end is refused, naming it.
#
#   python3 tools/render/test_render.py --blender blender --up target/release/up

import argparse
import os
import re
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SCRIPT = os.path.join(HERE, "render_gltf.py")
WIDTH, HEIGHT = 64, 40
FRAMES = (0, 5)
PROGRESS = re.compile(r"^frame (\d+) \((\d+)/(\d+), t = [\d.]+ s\): [\d.]+ s, \d+ kB, mean level ([\d.]+) -> (\S+)$", re.M)
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def fail(message, output=""):
    sys.stderr.write(f"test-render: FAILED: {message}\n")
    if output:
        sys.stderr.write(output[-4000:] + "\n")
    sys.exit(1)


def png_pixels(path):
    """A PNG's compressed pixels (its IDAT chunks): equal for equal pictures, whatever the
    metadata (Blender stamps each file with the time it was rendered)."""
    with open(path, "rb") as f:
        data = f.read()
    pixels, at = b"", 8
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        if kind == b"IDAT":
            pixels += data[at + 8:at + 8 + length]
        at += 12 + length
    return pixels


def render(blender, glb, out, frames):
    # Blender takes its Python's prefix from the first python3.x on PATH: one of the user's own
    # (this script's, under pyenv or a venv) would hide the system's numpy from its glTF importer.
    env = dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", ""))
    command = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", SCRIPT, "--",
               "--glb", glb, "--out", out, "--frames", frames, "--samples", "4", "--size", f"{WIDTH}x{HEIGHT}"]
    return subprocess.run(command, capture_output=True, text=True, timeout=900, env=env)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--up", default=os.path.join(ROOT, "target", "release", "up"))
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="up-render-test-") as tmp:
        glb = os.path.join(tmp, "run.glb")
        scene = os.path.join(ROOT, "assets", "scenes", "default.toml")
        subprocess.run([args.up, "export-gltf", scene, glb, "--seconds", "0.5", "--fps", "10"], check=True,
                       stdout=subprocess.DEVNULL)

        out = os.path.join(tmp, "frames")
        run = render(args.blender, glb, out, f"{FRAMES[0]}-{FRAMES[1]}")
        output = run.stdout + run.stderr
        if run.returncode != 0:
            fail(f"Blender exited {run.returncode}", output)
        lines = PROGRESS.findall(run.stdout)
        count = FRAMES[1] - FRAMES[0] + 1
        if [int(f) for f, *_ in lines] != list(range(FRAMES[0], FRAMES[1] + 1)):
            fail(f"expected a progress line for each of frames {FRAMES[0]}-{FRAMES[1]}", output)
        levels = []
        for frame, k, n, level, path in lines:
            if int(n) != count:
                fail(f"progress line of frame {frame} counts {n} frames, not {count}", output)
            with open(path, "rb") as f:
                head = f.read(24)
            if head[:8] != PNG_SIGNATURE:
                fail(f"{path} is not a PNG")
            size = struct.unpack(">II", head[16:24])
            if size != (WIDTH, HEIGHT):
                fail(f"{path} is {size[0]}x{size[1]}, not {WIDTH}x{HEIGHT}")
            levels.append(float(level))
        # A room lit by the page's lights: neither black (no light reached it) nor white.
        if not all(0.03 < level < 0.9 for level in levels):
            fail(f"frames' mean levels {levels} are not those of a lit room", output)
        clip = os.path.join(out, "clip.mp4")
        if not os.path.exists(clip):
            fail("no clip.mp4 beside several frames", output)
        with open(clip, "rb") as f:
            if f.read(8)[4:8] != b"ftyp":
                fail("clip.mp4 is not an MP4 (no ftyp box)")

        # Half a second apart the balloons have risen: Cycles' noise is the same each frame
        # (one seed), so only the motion tells the pictures apart.
        if png_pixels(lines[0][4]) == png_pixels(lines[-1][4]):
            fail("the first and last frames are the same picture: the animation did not play")

        past = render(args.blender, glb, os.path.join(tmp, "past"), "900")
        if past.returncode == 0 or "past the animation's end" not in past.stderr + past.stdout:
            fail("a frame past the run's end was not refused", past.stdout + past.stderr)

    print(f"test-render: ok, {count} frames {WIDTH}x{HEIGHT} (mean levels {', '.join(f'{v:.3f}' for v in levels)}), "
          "clip.mp4, a frame past the end refused")


main()

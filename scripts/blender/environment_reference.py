"""Holds the exported environment light's conventions to Cycles without phongcl: from the scene JSON (its
{"type": "environment"} light: colour or equirectangular file, rotation, strength) and Cycles' render of
environment_scene.py (DiffDir, Position, Normal, IndexOB), the diffuse light Cycles should have at a few
surface points, by brute force over the map (every texel with its solid angle):

    DiffDir = (1/pi) * sum over texels of L * max(0, n.w) * V(w) * dw

V: the ground (the 14 m square at z = 0 that environment_scene.py builds) blocks w. The points: the
ground's farthest pixel (the other objects, a few metres off and near its horizon, are left out: they
hide about 0.3% of its cosine-weighted sky) and red-sphere pixels above every other object (z > 1.25 m),
whose hemisphere only the ground can block. Pixels next to a silhouette are skipped.
The map's orientation, Cycles': +Z at the top row, the centre column towards +X, columns to its right
turning towards -Y (map_direction), and "rotation" the Z rotation of the Mapping node Cycles looks the
map up through. Prints each point's ratio Cycles / expected; exits 1 where the median
|ratio - 1| exceeds --tolerance.

    python3 scripts/blender/environment_reference.py --scene DIR/scene.json --render DIR/render.exr [--tolerance 0.03]
"""
import argparse
import json
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exr_file  # noqa: E402

GROUND_HALF_SIZE = 7.0  # environment_scene.py's (shadow_scene.py's) 14 m ground
GROUND_INDEX, SPHERE_INDEX, ABOVE_THE_REST_Z = 1, 2, 1.25
SPHERE_POINTS = 12
UNIFORM_GRID = (128, 64)
# Cycles' passes by their 3.x/4.x names, and the full names Blender 5 writes instead.
PASSES = {"DiffDir": ("DiffDir", "Diffuse Direct"), "IndexOB": ("IndexOB", "Object Index"), "Position": ("Position",),
          "Normal": ("Normal",)}


def map_direction(u, v, rotation_deg):
    """The world direction whose light is at image point (u, v) (v from the top row). Cycles reads a direction
    w at u = (pi - atan2(w.y, w.x)) / 2pi, v = acos(w.z) / pi from the top (kernel/camera/projection.h,
    direction_to_equirectangular), after the Mapping node's Z rotation of w: the map turns by -rotation."""
    elevation = math.pi / 2.0 - math.pi * v
    azimuth = math.pi - 2.0 * math.pi * u - math.radians(rotation_deg)
    return (math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth), math.sin(elevation))


def environment_samples(scene_path):
    """(direction, radiance * solid angle) per texel of the map (a uniform colour: of a 128x64 grid)."""
    scene = json.load(open(scene_path))
    lights = [light for light in scene["lights"] if light["type"] == "environment"]
    if len(lights) != 1:
        raise SystemExit("environment_reference: %s has %d environment lights, not one" % (scene_path, len(lights)))
    light = lights[0]
    strength = light.get("strength", 1.0)
    if "color" in light:
        width, height = UNIFORM_GRID
        images = {c: [[light["color"][i]] * width for _ in range(height)] for i, c in enumerate("RGB")}
    else:
        path = os.path.join(os.path.dirname(os.path.abspath(scene_path)), light["file"])
        images, (width, height) = exr_file.read(path, ["R", "G", "B"])
    samples = []
    texel = (2.0 * math.pi / width) * (math.pi / height)
    for y in range(height):
        v = (y + 0.5) / height
        weight = texel * math.sin(math.pi * v) * strength
        for x in range(width):
            direction = map_direction((x + 0.5) / width, v, light.get("rotation", 0.0))
            samples.append((direction, [images[c][y][x] * weight for c in "RGB"]))
    return samples


def ground_blocks(point, w):
    if w[2] >= 0.0:
        return False
    t = -point[2] / w[2]
    return abs(point[0] + t * w[0]) <= GROUND_HALF_SIZE and abs(point[1] + t * w[1]) <= GROUND_HALF_SIZE


def expected_diffdir(samples, point, normal):
    total = [0.0, 0.0, 0.0]
    for w, radiance in samples:
        cosine = normal[0] * w[0] + normal[1] * w[1] + normal[2] * w[2]
        if cosine > 0.0 and not ground_blocks(point, w):
            for c in range(3):
                total[c] += radiance[c] * cosine
    return [t / math.pi for t in total]


def chosen_pixels(passes, width, height):
    index = passes["IndexOB.X"]

    def inside(x, y):
        return all(index[y + j][x + i] == index[y][x] for j in (-1, 0, 1) for i in (-1, 0, 1))

    ground = next(((x, y) for y in range(1, height - 1) for x in range(1, width - 1)
                   if index[y][x] == GROUND_INDEX and inside(x, y)), None)
    chosen = [("ground, farthest", ground)] if ground else []
    sphere = [(x, y) for y in range(1, height - 1) for x in range(1, width - 1)
              if index[y][x] == SPHERE_INDEX and inside(x, y) and passes["Position.Z"][y][x] > ABOVE_THE_REST_Z]
    step = max(1, len(sphere) // SPHERE_POINTS)
    chosen += [("sphere", p) for p in sphere[::step][:SPHERE_POINTS]]
    return chosen


def main():
    parser = argparse.ArgumentParser(prog="environment_reference.py")
    parser.add_argument("--scene", required=True)
    parser.add_argument("--render", required=True)
    parser.add_argument("--tolerance", type=float, default=0.03)
    args = parser.parse_args()
    samples = environment_samples(args.scene)
    present = exr_file.channel_names(args.render)
    wanted = {}
    for short, channels in (("DiffDir", "RGB"), ("Position", "XYZ"), ("Normal", "XYZ"), ("IndexOB", "X")):
        name = next((n for n in PASSES[short] if "ViewLayer.%s.%s" % (n, channels[0]) in present), PASSES[short][0])
        wanted.update({"ViewLayer.%s.%s" % (name, c): "%s.%s" % (short, c) for c in channels})
    read, (width, height) = exr_file.read(args.render, list(wanted))
    passes = {wanted[name]: rows for name, rows in read.items()}
    errors = []
    for what, (x, y) in chosen_pixels(passes, width, height):
        point = [passes["Position." + c][y][x] for c in "XYZ"]
        normal = [passes["Normal." + c][y][x] for c in "XYZ"]
        cycles = [passes["DiffDir." + c][y][x] for c in "RGB"]
        expected = expected_diffdir(samples, point, normal)
        ratio = sum(cycles) / sum(expected)
        errors.append(abs(ratio - 1.0))
        print("environment_reference: %-16s (%3d, %3d) n (%.2f, %.2f, %.2f): Cycles %.4f, expected %.4f, ratio %.4f"
              % (what, x, y, *normal, sum(cycles) / 3, sum(expected) / 3, ratio))
    if not errors:
        raise SystemExit("environment_reference: no pixel to hold in " + args.render)
    median = statistics.median(errors)
    print("environment_reference: %d points, median |Cycles / expected - 1| %.4f, largest %.4f" % (len(errors), median, max(errors)))
    return 0 if median <= args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())

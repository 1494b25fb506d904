"""What a node graph costs per hit: a textured plane filling a 256 x 256 picture (one camera
ray per pixel, lit by a sun), rendered with seven materials, interleaved
(the machine is shared and noisy), each time the median of several runs:

    table          the report's texture path (an image replacing the diffuse colour)
    folded         a node graph with nothing varying (folded into the table at compile)
    image          the same image through a program: Image Texture on UV into a Diffuse BSDF
    mapped_chain   Texture Coordinate -> Mapping -> Image -> Hue/Saturation -> Mix Color ->
                   Color Ramp on its brightness, screened in: 7 value steps
    mixed_shaders  a Checker's factor mixing a Principled and a Glossy BSDF per hit
    noise          a Noise texture's Color (Detail 2: three octaves, for each of its three
                   channels) into a Diffuse BSDF
    brick          a Brick texture's Color into a Diffuse BSDF

Prints shader_<name>_ns_per_hit (render time over camera rays, which all hit) and
shader_<name>_ratio against the table path; writes results/shader_graph.png (bars) and .csv.
"""

import csv
import time

import numpy as np

from core import (
    Box,
    Camera,
    Link,
    Material,
    RenderSettings,
    Scene,
    ShaderNode,
    SunLight,
    Texture,
    render,
)
from tests.benchmarks.__main__ import RESULTS

SIZE = 256
ROUNDS = 5


def _texture():
    rng = np.random.default_rng(5)
    return Texture(pixels=rng.uniform(0.0, 1.0, (64, 64, 3)), srgb=False)


def _materials():
    texture = _texture()
    image = ShaderNode("image", settings={"texture": texture})
    coords = ShaderNode("tex_coord")
    mapping = ShaderNode("mapping", {"Vector": Link(coords, "UV"), "Scale": (2.0, 2.0, 1.0),
                                     "Rotation": (0.0, 0.0, 0.3)})  # fmt: skip
    mapped = ShaderNode("image", {"Vector": Link(mapping, "Vector")}, {"texture": texture})
    hsv = ShaderNode("hsv", {"Hue": 0.6, "Color": Link(mapped, "Color")})
    multiply = ShaderNode("mix_color", {"Fac": 0.7, "A": Link(hsv, "Color"),
                                        "B": (0.9, 0.5, 0.3)}, {"blend": "MULTIPLY"})  # fmt: skip
    bw = ShaderNode("to_bw", {"Color": Link(mapped, "Color")})
    ramp = ShaderNode("color_ramp", {"Fac": Link(bw, "Val")})
    screen = ShaderNode("mix_color", {"Fac": 0.5, "A": Link(multiply, "Color"),
                                      "B": Link(ramp, "Color")}, {"blend": "SCREEN"})  # fmt: skip
    checker = ShaderNode("checker", {"Scale": 8.0})
    noise = ShaderNode("noise", {"Scale": 3.0})
    brick = ShaderNode("brick", {"Scale": 3.0})
    principled = ShaderNode("principled", {"Base Color": Link(image, "Color")})
    glossy = ShaderNode("glossy", {"Color": (0.9, 0.8, 0.5), "Roughness": 0.0})
    mixed = ShaderNode("mix_shader", {"Fac": Link(checker, "Fac"), "Shader A": Link(principled),
                                      "Shader B": Link(glossy)})  # fmt: skip
    return {
        "table": Material(texture=texture),
        "folded": Material(surface=ShaderNode("diffuse", {"Color": (0.5, 0.4, 0.3)})),
        "image": Material(surface=ShaderNode("diffuse", {"Color": Link(image, "Color")})),
        "mapped_chain": Material(surface=ShaderNode("diffuse", {"Color": Link(screen, "Color")})),
        "mixed_shaders": Material(surface=mixed),
        "noise": Material(surface=ShaderNode("diffuse", {"Color": Link(noise, "Color")})),
        "brick": Material(surface=ShaderNode("diffuse", {"Color": Link(brick, "Color")})),
    }


def _scene(material):
    plane = Box("Plane", material, np.diag([2.0, 2.0, 0.01, 1.0]))
    camera = Camera(eye=(0.0, 0.0, 5.0), view=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0),
                    projection="orthographic", ortho_height=3.0)  # fmt: skip
    sun = SunLight(direction=(0.3, 0.2, -1.0), irradiance=(3.0, 3.0, 3.0))
    return Scene(camera, [plane], [sun])


def main():
    settings = RenderSettings(SIZE, SIZE, pixel_samples=1, max_depth=2)
    materials = _materials()
    for material in materials.values():  # compile every kernel first
        render(_scene(material), RenderSettings(8, 8, pixel_samples=1))
    times = {name: [] for name in materials}
    for _ in range(ROUNDS):
        for name, material in materials.items():
            start = time.perf_counter()
            output = render(_scene(material), settings)
            times[name].append(output.stats.render_s or time.perf_counter() - start)
    hits = SIZE * SIZE
    rows = []
    for name in materials:
        seconds = float(np.median(times[name]))
        ns = seconds / hits * 1e9
        ratio = seconds / float(np.median(times["table"]))
        print(f"shader_{name}_ns_per_hit: {ns:.0f}")
        print(f"shader_{name}_ratio: {ratio:.2f}")
        rows.append((name, ns, ratio))
    _write(rows)


def _write(rows):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    RESULTS.mkdir(exist_ok=True)
    with open(RESULTS / "shader_graph.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["material", "ns_per_hit", "ratio_to_table"])
        writer.writerows(rows)
    figure, axes = plt.subplots(figsize=(7, 3.5))
    axes.bar([r[0] for r in rows], [r[1] for r in rows], color="#4477aa")
    axes.set_ylabel("render ns per camera-ray hit")
    axes.set_title("What a node graph costs per hit (textured plane, sun, 256 x 256)")
    for k, (_, ns, ratio) in enumerate(rows):
        axes.text(k, ns, f"{ratio:.2f}x", ha="center", va="bottom")
    figure.tight_layout()
    figure.savefig(RESULTS / "shader_graph.png", dpi=100)


if __name__ == "__main__":
    main()

"""Every numeric Blender setting the export reads, fed random and edge values (each within
what Blender's own field accepts: it clamps the rest): the render must end with a message
naming the setting's owner (`Whitted: camera 'Camera': Camera Properties > ...`) or a
picture of finite values, never Whitted's own failure ("the render failed: ZeroDivisionError",
as an orthographic scale of 0 and a lens shift of 1e30 gave before).

The settings are Whitted's own (every numeric field of the scene's, object's, material's,
light's and world's `whitted`, found by introspection) and Blender's that the export reads:
render size and pixel aspect, the camera's lens, sensor, shift, clipping and depth of field,
each light type's power, size, angle and spot shape, the World's colour and strength, the
objects' transforms and the Principled BSDF's inputs. A fixed sample of examples in `make
test`; WHITTED_FUZZ_EXAMPLES raises their number (`make fuzz`)."""

import math
import os
import random
import sys

import numpy as np
import pytest

from tests.blender.conftest import clear_scene
from tests.support.exr import read_exr

pytestmark = pytest.mark.bpy

EXAMPLES = int(os.environ.get("WHITTED_FUZZ_EXAMPLES", "300"))
SEED = int(os.environ.get("WHITTED_FUZZ_SEED", "40"))
# Blender's own settings the export reads, by the datablock that holds them
BLENDER_READ = {
    "render": ["resolution_x", "resolution_y", "resolution_percentage", "pixel_aspect_x",
               "pixel_aspect_y"],
    "camera": ["lens", "ortho_scale", "shift_x", "shift_y", "sensor_width", "sensor_height",
               "clip_start", "clip_end"],
    "dof": ["focus_distance", "aperture_fstop", "aperture_blades", "aperture_rotation",
            "aperture_ratio"],
    "units": ["scale_length"],
    "point": ["energy", "shadow_soft_size", "exposure"],
    "spot": ["energy", "shadow_soft_size", "spot_size", "spot_blend", "exposure"],
    "area": ["energy", "size", "size_y", "exposure"],
    "sun": ["energy", "angle", "exposure"],
    "world": ["color"],
}  # fmt: skip
# Blender's own refusals, made before any engine runs
BLENDER_REFUSES = ("Image too small",)
# Fields a value can make slow rather than wrong: kept to small values beyond their edges
SLOW = ("samples", "resolution", "depth", "bounces", "rays", "_size")
FINE_MOST = 4


def add_scene(bpy):
    scene = clear_scene(bpy)
    scene.render.engine = "WHITTED"
    scene.render.resolution_x, scene.render.resolution_y = 8, 6
    scene.render.resolution_percentage = 100
    bpy.ops.object.camera_add(location=(0, -8, 1), rotation=(math.radians(85), 0, 0))
    camera = scene.camera = bpy.context.active_object
    camera.data.dof.use_dof = True
    bpy.ops.mesh.primitive_uv_sphere_add(location=(-1, 0, 0), segments=12, ring_count=6)
    ball = bpy.context.active_object
    ball.whitted.shape = "SPHERE"
    bpy.ops.mesh.primitive_cube_add(location=(1.5, 0, 0))
    cube = bpy.context.active_object
    material = bpy.data.materials.new("Fuzzed")
    if hasattr(material, "use_nodes"):
        material.use_nodes = True
    cube.data.materials.append(material)
    ball.data.materials.append(material)
    lights = {}
    for kind, place in (("POINT", (2, -2, 3)), ("SPOT", (-2, -3, 3)), ("AREA", (0, -2, 4)),
                        ("SUN", (0, 0, 6))):  # fmt: skip
        bpy.ops.object.light_add(type=kind, location=place)
        lights[kind.lower()] = bpy.context.active_object
    world = scene.world = bpy.data.worlds.new("Fuzzed world")  # fresh: no earlier test's
    if hasattr(world, "use_nodes"):
        world.use_nodes = True
    return scene, camera, (ball, cube), material, lights, world


def numeric(struct):
    """Each writable number (or array of numbers) of an RNA struct."""
    for prop in struct.bl_rna.properties:
        if prop.type in ("FLOAT", "INT") and not prop.is_readonly and prop.identifier != "rna_type":
            yield prop.identifier


def targets(bpy, scene, camera, shapes, material, lights, world):
    """(the struct, the property name) of every setting fuzzed."""
    found = [(scene.render, n) for n in BLENDER_READ["render"]]
    found += [(camera.data, n) for n in BLENDER_READ["camera"]]
    found += [(camera.data.dof, n) for n in BLENDER_READ["dof"]]
    found += [(scene.unit_settings, n) for n in BLENDER_READ["units"]]
    found += [(world, n) for n in BLENDER_READ["world"]]
    for kind, obj in lights.items():
        found += [(obj.data, n) for n in BLENDER_READ[kind] if hasattr(obj.data, n)]
        found += [(obj.data.whitted, n) for n in numeric(obj.data.whitted)]
        found += [(obj, n) for n in ("location", "rotation_euler", "scale")]
    for struct in (scene.whitted, world.whitted, material.whitted):
        found += [(struct, n) for n in numeric(struct)]
    for obj in (*shapes, camera):
        found += [(obj, n) for n in ("location", "rotation_euler", "scale")]
        found += [(obj.whitted, n) for n in numeric(obj.whitted)]
    tree = getattr(world, "node_tree", None)
    for node in tree.nodes if tree else ():
        if node.type == "BACKGROUND":
            found += [(socket, "default_value") for socket in node.inputs]
    for node in material.node_tree.nodes if material.node_tree else ():
        if node.type == "BSDF_PRINCIPLED":
            found += [(s, "default_value") for s in node.inputs if s.type in ("VALUE", "RGBA")]
    return found


def edge_values(prop, name: str, rng: random.Random) -> list:
    low, high = prop.hard_min, prop.hard_max
    soft_low, soft_high = prop.soft_min, prop.soft_max
    if any(part in name for part in SLOW):
        high = min(high, max(low, FINE_MOST))
    values = [low, high, soft_low, min(soft_high, high), 0, 1, -1]
    if prop.type == "FLOAT":
        values += [1e-30, -1e-30, 1e30, -1e30, math.inf, -math.inf, math.nan,
                   rng.uniform(soft_low, min(soft_high, high)),
                   rng.choice([-1, 1]) * 10.0 ** rng.uniform(-40, 38)]  # fmt: skip
    else:
        values += [rng.randint(int(max(low, -(2**31))), int(min(high, 2**31 - 1)))]
    if prop.type == "INT":
        values = [int(max(min(v, 2**31 - 1), -(2**31))) for v in values if not math.isnan(v)]
    return [v for v in values if prop.type == "FLOAT" or low <= v <= high]


def set_value(struct, name: str, value) -> None:
    current = getattr(struct, name)
    try:
        if hasattr(current, "__len__") and not isinstance(current, str):
            setattr(struct, name, [value] * len(current))
        else:
            setattr(struct, name, value)
    except (TypeError, ValueError, OverflowError):  # refused by Blender itself: a clamp
        pass


def outcome(bpy, scene, path) -> str:
    """'picture' (whose values are all finite), or the error's text."""
    scene.render.filepath = str(path)
    try:
        bpy.ops.render.render(write_still=True)
    except RuntimeError as error:
        return str(error)
    channels, _ = read_exr(path)
    for name, values in channels.items():
        assert np.all(np.isfinite(values)), f"channel {name} holds non-finite values"
    return "picture"


def test_random_numeric_settings_give_a_message_or_a_finite_picture(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    made = add_scene(bpy)
    scene = made[0]
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    settings = targets(bpy, *made)
    assert len(settings) > 100
    rng = random.Random(SEED)
    outcomes = {"picture": 0, "message": 0}
    for example in range(EXAMPLES):
        saved = []
        for struct, name in rng.sample(settings, rng.randint(1, 3)):
            prop = struct.bl_rna.properties[name]
            value = rng.choice(edge_values(prop, name, rng))
            current = getattr(struct, name)
            saved.append((struct, name, tuple(current) if hasattr(current, "__len__") else current))
            set_value(struct, name, value)
        tried = ", ".join(f"{s.bl_rna.identifier}.{n}={getattr(s, n)!s:.40}" for s, n, _ in saved)
        said = outcome(bpy, scene, tmp_path / f"example_{example}.exr")
        if said == "picture":
            outcomes["picture"] += 1
        else:
            outcomes["message"] += 1
            # Whitted's message, or Blender's own before the engine starts
            assert "Whitted: " in said or any(m in said for m in BLENDER_REFUSES), (tried, said)
            assert "the render failed" not in said and "Traceback" not in said, (tried, said)
        for struct, name, value in reversed(saved):
            setattr(struct, name, value)
    print(f"numeric settings: {len(settings)}, examples: {EXAMPLES}, outcomes: {outcomes}",
          file=sys.stderr)  # fmt: skip
    assert outcomes["picture"] > 0 and outcomes["message"] > 0
    assert outcome(bpy, scene, tmp_path / "restored.exr") == "picture"  # Blender stays usable


@pytest.mark.parametrize(
    "change, field",
    [
        ("camera.data.type = 'ORTHO'; camera.data.ortho_scale = 0",
         "Camera Properties > Lens > Orthographic Scale: is 0"),
        ("camera.data.shift_x = 1e30", "Camera Properties > Lens > Shift X: is 1e+30"),
        ("camera.data.shift_y = -1e30", "Camera Properties > Lens > Shift Y: is -1e+30"),
        ("world.color = (1e38, 1e38, 1e38); [setattr(s, 'default_value', v) for n in "
         "(world.node_tree.nodes if world.node_tree else ()) if n.type == 'BACKGROUND' "
         "for s, v in zip(n.inputs[:2], ((1e38, 1e38, 1e38, 1.0), 1e38))]",
         "World Properties >"),
        ("lights['point'].data.energy = 1e38; lights['point'].data.color = (1, 1, 1)",
         "Light Properties > Light > Power: with its Color and Exposure gives 1e+38"),
        ("lights['sun'].data.energy = 1e30", "Light Properties > Light > Strength"),
    ],
)  # fmt: skip
def test_settings_that_gave_whitteds_own_failure_are_named(bpy_with_whitted, change, field):
    bpy = bpy_with_whitted
    scene, camera, shapes, material, lights, world = add_scene(bpy)
    exec(change)
    with pytest.raises(RuntimeError) as error:
        bpy.ops.render.render()
    assert field in str(error.value) and "the render failed" not in str(error.value)

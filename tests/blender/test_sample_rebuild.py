"""The committed sample files are what sample_blends/build_samples.py makes from nothing:
Blender 3.4 rebuilds them into a temporary folder, and every scene, object, modifier,
material, light and camera setting matches (read back with the bpy 5.0 module). The
textures are rebuilt byte for byte."""

import filecmp

import pytest

from tests.blender.conftest import ROOT
from tests.support.blender34 import blender_34

pytestmark = [pytest.mark.bpy, pytest.mark.blender34]
SAMPLES = ROOT / "sample_blends"


def _rounded(values, digits=4):
    return tuple(round(float(v), digits) for v in values)


def _whitted(group):
    """An add-on property group's values, by name."""
    out = {}
    for prop in group.bl_rna.properties:
        if prop.identifier == "rna_type":
            continue
        value = getattr(group, prop.identifier)
        if hasattr(value, "name") and not isinstance(value, str):
            value = value.name  # an image
        elif hasattr(value, "__len__") and not isinstance(value, str):
            value = _rounded(value)
        elif isinstance(value, float):
            value = round(value, 5)
        out[prop.identifier] = value
    return out


def fingerprint(bpy, path):
    bpy.ops.wm.open_mainfile(filepath=str(path))
    scenes = {
        scene.name: (
            scene.render.resolution_x, scene.render.resolution_y, _whitted(scene.whitted),
            scene.camera.name if scene.camera else None,
            (_rounded(scene.world.color), _whitted(scene.world.whitted)) if scene.world else None,
            sorted(o.name for o in scene.objects),
        )
        for scene in bpy.data.scenes
    }  # fmt: skip
    objects = {}
    for obj in bpy.data.objects:
        entry = [obj.type, obj.hide_render, _rounded(obj.location), _rounded(obj.rotation_euler),
                 _rounded(obj.scale), obj.parent.name if obj.parent else None,
                 _whitted(obj.whitted)]  # fmt: skip
        entry += [(m.type, m.operation, m.object.name) for m in obj.modifiers]
        if obj.type == "MESH":
            entry += [len(obj.data.vertices), len(obj.data.polygons),
                      [s.material.name for s in obj.material_slots]]  # fmt: skip
        elif obj.type == "LIGHT":
            entry += [obj.data.type, round(obj.data.energy, 4), _whitted(obj.data.whitted)]
            if obj.data.type == "AREA":
                entry.append(round(obj.data.size, 4))
        elif obj.type == "CAMERA":
            dof = obj.data.dof
            entry += [round(obj.data.angle_y, 6), dof.use_dof, round(dof.aperture_fstop, 6),
                      dof.focus_object.name if dof.focus_object else None]  # fmt: skip
        objects[obj.name] = entry
    materials = {
        m.name: (_rounded(m.diffuse_color), _whitted(m.whitted)) for m in bpy.data.materials
    }
    images = {i.name: i.filepath for i in bpy.data.images}
    return scenes, objects, materials, images


def test_build_script_rebuilds_the_committed_samples(bpy_with_whitted, tmp_path):
    bpy = bpy_with_whitted
    run = blender_34(
        "--factory-startup", "--addons", "whitted",
        "--python", str(SAMPLES / "build_samples.py"), "--", str(tmp_path),
    )  # fmt: skip
    assert run.returncode == 0 and "Traceback" not in run.stdout + run.stderr, run.stdout
    committed = sorted(p.name for p in SAMPLES.glob("*.blend"))
    assert sorted(p.name for p in tmp_path.glob("*.blend")) == committed
    assert len(committed) == 11
    for name in committed:
        assert fingerprint(bpy, tmp_path / name) == fingerprint(bpy, SAMPLES / name), name
    textures = sorted(p.name for p in (SAMPLES / "textures").iterdir())
    match, mismatch, errors = filecmp.cmpfiles(
        SAMPLES / "textures", tmp_path / "textures", textures, shallow=False
    )
    assert (mismatch, errors) == ([], [])

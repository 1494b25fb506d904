"""Differences between the Blender versions Whitted supports (3.4, and 4.2 to 5.2), in one
place."""

import bpy

# Blender 4.1 computes split (corner) normals on demand; before it they must be asked for
NEEDS_CALC_NORMALS_SPLIT = bpy.app.version < (4, 1, 0)


def prepare_corner_normals(mesh) -> None:
    """Make `mesh.loop_triangles[*].split_normals` valid."""
    if NEEDS_CALC_NORMALS_SPLIT:
        mesh.calc_normals_split()


# Principled BSDF inputs renamed in Blender 4.0; the newer name first
TRANSMISSION_INPUTS = ("Transmission Weight", "Transmission")
# Cycles' Principled BSDF layers its specular over the diffuse from Blender 4.0 (the
# Principled v2); before, the lobes were added
PRINCIPLED_LAYERED = bpy.app.version >= (4, 0, 0)
# What Cycles dims the layers under a rough Coat by: the exact Fresnel at the coat's normal
# in 4.2 ("NORMAL"), the mean Fresnel over its GGX lobe in 4.5 on ("LOBE"; measured by
# tests/blender/test_cycles_clear_coat.py; 4.3 and 4.4 not tested, taken as 4.2)
COAT_ALBEDO = "LOBE" if bpy.app.version >= (4, 5, 0) else "NORMAL"
# Cycles before 4.5 weighs a diffuse lit through a bent normal by Chiang, Li and Burley's
# shadow terminator term; 4.5 changed its rule to Conty Estevez et al.'s microfacet
# shadowing (core.kernels.bent_normal; measured by tests/blender/test_cycles_tangents.py)
BUMP_TERMINATOR = "chiang" if bpy.app.version < (4, 5, 0) else "conty"
# A Normal Map's Strength mixes the mapped vector as it is in Cycles 4 (measured in 4.2 and
# 4.5), made unit first in Cycles 3 (measured in 3.4): core.model.shader's strength_mix
NORMAL_MAP_MIX = "VECTOR" if bpy.app.version >= (4, 0, 0) else "UNIT"
# A rough diffuse's Oren-Nayar: energy-preserving from 4.3, Fujii's before
# (core.kernels.rough_diffuse; measured against 4.2 and 4.5 by test_cycles_rough_diffuse.py)
ROUGH_DIFFUSE = "EON" if bpy.app.version >= (4, 3, 0) else "FON"


# Blender 5.0 renamed the passes Cycles and EEVEE write (and multilayer EXR files carry, and
# the Render Layers node offers) from the short names of Blender 2.x to words; Whitted names
# its passes as Cycles does in the running Blender, so compositing set-ups made for Cycles
# find them (tests/blender/test_pass_names.py compares with what Cycles writes)
PASS_NAMES_FROM_5 = {
    "IndexOB": "Object Index",
    "IndexMA": "Material Index",
    "DiffCol": "Diffuse Color",
    "Env": "Environment",
    "Emit": "Emission",
}


def pass_name(name: str) -> str:
    """The name Cycles gives the pass Blender before 5.0 called `name`, in this Blender."""
    if bpy.app.version >= (5, 0, 0):
        return PASS_NAMES_FROM_5.get(name, name)
    return name


def node_tree_in_use(datablock):
    """The node tree a material or world renders with, or None. Blender 5.0 always uses nodes
    (and deprecates `use_nodes`); before 5.0 the flag decides."""
    tree = datablock.node_tree
    if tree is None or (bpy.app.version < (5, 0, 0) and not datablock.use_nodes):
        return None
    return tree


def give_nodes(datablock) -> None:
    """Make a new material or world render with nodes (always so from Blender 5.0, where
    setting `use_nodes` is deprecated)."""
    if bpy.app.version < (5, 0, 0) or datablock.node_tree is None:
        datablock.use_nodes = True


def auto_smooth(mesh) -> tuple:
    """Blender before 4.1 keeps Auto Smooth on the mesh, and it changes the split normals
    the export reads; from 4.1 it is a modifier, seen in the evaluated mesh's sharp edges."""
    if not NEEDS_CALC_NORMALS_SPLIT:
        return ()
    return (mesh.use_auto_smooth, mesh.auto_smooth_angle)


# Cycles' Voronoi texture hashes its cells' integer corners with PCG from Blender 5.0, the
# bits of their float corners with lookup3 before (core.kernels.voronoi)
VORONOI_CELL_HASH = "PCG" if bpy.app.version >= (5, 0, 0) else "LOOKUP3"


# Cycles' lights before Blender 4.0 (measured against Cycles in 3.4 and 4.2): a point or spot
# light's radius was always a disk facing the lit point, a spot's cone also fell off with the
# cosine from its axis, a sun's angle spread its light over a disk one unit away, and a disk
# or ellipse area light spread its power as if it filled its bounding rectangle
LIGHTS_BEFORE_4 = bpy.app.version < (4, 0, 0)


def cast_shadow_setting(light) -> tuple:
    """(data, property) of Light > Cast Shadow: Cycles' own before Blender 4.0, Blender's
    from 4.0."""
    cycles = getattr(light, "cycles", None)
    if cycles is not None and hasattr(cycles, "cast_shadow"):
        return cycles, "cast_shadow"
    return light, "use_shadow"


def light_casts_shadow(light) -> bool:
    owner, name = cast_shadow_setting(light)
    return bool(getattr(owner, name))

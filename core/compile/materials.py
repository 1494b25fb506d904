"""Materials and their textures: one row per distinct `Material`, all texture pixels in one
float32 array with an offset and size per texture (each `Texture` loaded once), and the
shader programs of node materials (core.compile.shader_program): a program that reads
nothing of the hit is run here once and its terms stored in the row; the others run per hit.
"""

from __future__ import annotations

import numpy as np

from ..errors import SceneError
from ..kernels.attributes import READS_ATTRIBUTES, READS_FRAME
from ..kernels.layout import Materials
from ..kernels.shader_fold import FOLDED_COLUMNS, fold_surfaces
from ..kernels.shader_program import SHADER_STACK
from ..kernels.shadow_log import SHADOW_VARIES
from ..kernels.surface_terms import CLEAR_COAT_COLUMNS, GLOSS_COLUMNS, NO_CLEAR_COAT
from ..model.shader import passes_light
from ..passes import crypto_id
from ..textures import load_texture
from ..vocabulary import BUMP_RULES
from .arrays import concatenated, rows
from .shader_program import ProgramBuilder


class _Textures:
    """Each distinct Texture's pixels once, with its row."""

    def __init__(self):
        self.loaded: list = []  # (rgb (h, w, 3), alpha (h, w))
        self.row_of: dict = {}

    def row(self, texture, owner: str = "") -> int:
        if id(texture) not in self.row_of:
            self.row_of[id(texture)] = len(self.loaded)
            rgb = load_texture(texture, owner)
            alpha = np.ones(rgb.shape[:2], np.float32)
            if texture.pixels is not None and np.asarray(texture.pixels).shape[2] == 4:
                alpha = np.asarray(texture.pixels, np.float32)[:, :, 3]
            self.loaded.append((rgb, alpha))
        return self.row_of[id(texture)]


def pack_materials(shapes: list, attribute_names=()) -> tuple[Materials, dict[int, int]]:
    """The material table for these shapes, and each material's row by id();
    `attribute_names` the colour attributes the programs may read, in the kernels' order
    (core.model.shader.attribute_names)."""
    materials, row_of = [], {}
    for shape in shapes:
        if id(shape.material) not in row_of:
            row_of[id(shape.material)] = len(materials)
            materials.append((shape.material, shape.owner))
    textures = _Textures()
    texture_rows = []
    for material, user in materials:
        owner = f"material '{material.name}' (on {user})"
        texture = material.texture
        texture_rows.append(-1 if texture is None else textures.row(texture, owner))
    programs = [_program(m, user, textures, attribute_names) for m, user in materials]
    table = Materials(
        diffuse=rows([m.diffuse for m, _ in materials]),
        specular=rows([m.specular for m, _ in materials]),
        shininess=np.array([m.shininess for m, _ in materials], float),
        reflectivity=np.array([m.reflectivity for m, _ in materials], float),
        transparency=np.array([m.transparency for m, _ in materials], float),
        ior=rows([(m.outer_ior, m.inner_ior) for m, _ in materials], 2),
        texture=np.array(texture_rows, np.int32),
        texture_pixels=concatenated(
            [t.reshape(-1, 3) for t, _ in textures.loaded], (0, 3), np.float32
        ),  # fmt: skip
        texture_offset=np.cumsum([0] + [t.shape[0] * t.shape[1] for t, _ in textures.loaded])[
            :-1
        ].astype(np.int64),
        texture_size=np.array(
            [(t.shape[1], t.shape[0]) for t, _ in textures.loaded], np.int64
        ).reshape(-1, 2),  # fmt: skip
        pass_index=np.array([m.pass_index for m, _ in materials], np.int32),
        crypto=np.array([crypto_id(m.name) for m, _ in materials], np.float32),
        mirror=_pairs([(m.mirror_colour, _edge(m)) for m, _ in materials]),
        # the clear layer, its Specular Tint white (a node material's folds in below)
        coat=rows(
            [(m.coat, m.coat_ior, float(m.coat_hides), 1.0, 1.0, 1.0) for m, _ in materials], 6
        ),  # fmt: skip
        glass_tint=_pairs([(m.glass_reflect, m.glass_transmit) for m, _ in materials]),
        refraction_fresnel=np.array([m.refraction_fresnel for m, _ in materials], float),
        mirror_hides_lights=np.array([not m.mirror_sees_lights for m, _ in materials], np.uint8),
        emission=rows([m.emission for m, _ in materials]),
        transparent=rows([m.transparent for m, _ in materials]),
        holdout=np.array([m.holdout for m, _ in materials], float),
        roughness=np.array([m.roughness for m, _ in materials], float),
        gloss=_no_gloss(len(materials)),
        clear_coat=_no_clear_coat(len(materials)),
        mirror_dip=np.zeros((len(materials), 3)),
        absorption=rows([m.absorption for m, _ in materials]),
        translucent=rows([m.translucent for m, _ in materials]),
        diffuse_roughness=np.array([m.diffuse_roughness for m, _ in materials], float),
        bump_rule=np.array([BUMP_RULES[m.bump_rule] for m, _ in materials], np.uint8),
        texture_alpha=concatenated([a.ravel() for _, a in textures.loaded], (0,), np.float32),
        **_program_tables(programs),
    )
    _fold_constant_programs(table, programs)
    return table, row_of


def _program(material, user: str, textures: _Textures, attribute_names=()):
    """The material's shader program, or None; one too large for the kernels' stack is
    refused (the kernels do not check bounds)."""
    if material.surface is None:
        return None
    program = ProgramBuilder(textures.row, attribute_names).build(material.surface)
    needed = len(program.constants) + program.values + 4 * program.attributes
    if needed > SHADER_STACK:
        raise SceneError(
            f"material '{material.name}' (on {user})",
            "surface",
            f"its node graph needs {needed:,} numbers at a hit; at most {SHADER_STACK:,} fit: "
            "simplify it (fewer nodes, or fewer Color Ramp stops)",
        )
    return program


def _program_tables(programs: list) -> dict:
    ops, constants, ranges, constant_ranges = [], [], [], []
    step = constant = 0
    for program in programs:
        if program is None:
            ranges.append((-1, -1))
            constant_ranges.append((0, 0))
            continue
        program_ops, program_constants = program.resolved()
        ranges.append((step, step + len(program_ops)))
        constant_ranges.append((constant, constant + len(program_constants)))
        ops.append(program_ops)
        constants.append(program_constants)
        step += len(program_ops)
        constant += len(program_constants)
    return dict(
        shader_frame=np.array([_reads(p) for p in programs], np.uint8),
        shader_range=np.array(ranges, np.int64).reshape(-1, 2),
        shader_constant_range=np.array(constant_ranges, np.int64).reshape(-1, 2),
        shader_ops=concatenated(ops, (0, 8), np.int32),
        shader_constants=concatenated(constants, (0,), np.float64),
    )


def _reads(program) -> int:
    """Materials.shader_frame's bits for a program (core.kernels.attributes)."""
    if program is None:
        return 0
    return READS_FRAME * program.needs_frame + READS_ATTRIBUTES * (program.attributes > 0)


def _fold_constant_programs(table: Materials, programs: list) -> None:
    """Run each program that reads nothing of the hit once; its terms become the row's."""
    constant = [k for k, p in enumerate(programs) if p is not None and not p.varying]
    if not constant:
        return
    out = np.zeros((len(constant), FOLDED_COLUMNS))
    fold_surfaces(table, np.array(constant, np.int64), out)
    for k, row in zip(constant, out, strict=True):
        table.diffuse[k] = row[0:3]
        table.specular[k] = row[3:6]
        table.shininess[k] = row[6]
        table.reflectivity[k] = row[7]
        table.transparency[k] = row[8]
        table.ior[k] = row[9:11]
        table.mirror[k, 0], table.mirror[k, 1] = row[11:14], row[14:17]
        table.mirror_hides_lights[k] = row[17] != 0.0
        table.coat[k, :3] = row[18:21]
        table.glass_tint[k, 0], table.glass_tint[k, 1] = row[21:24], row[24:27]
        table.refraction_fresnel[k] = row[27]
        table.emission[k] = row[28:31]
        table.transparent[k] = row[31:34]
        table.holdout[k] = row[34]
        table.roughness[k] = row[35]
        table.gloss[k] = row[36 : 36 + GLOSS_COLUMNS]
        table.clear_coat[k] = row[36 + GLOSS_COLUMNS : 36 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS]
        table.coat[k, 3:] = row[36 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS :][:3]
        table.mirror_dip[k] = row[39 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS :][:3]
        table.translucent[k] = row[42 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS :][:3]
        table.diffuse_roughness[k] = row[45 + GLOSS_COLUMNS + CLEAR_COAT_COLUMNS]
        table.shader_range[k] = (-1, -1)


def shadow_shares(table: Materials, surfaces: list, refraction_passes: bool = True) -> np.ndarray:
    """What one crossing of each material's surface lets a shadow ray through: what passes
    it straight (the mean over RGB), plus its transparency when `refraction_passes` (the
    "attenuated" glass-shadow rule; under "blocked" a refracting surface stops shadow rays),
    at most 1. A material whose terms vary over the surface (a program run per hit;
    `surfaces[k]` is row k's graph) is SHADOW_VARIES if its graph can let light through
    anywhere under the rule (its program is run at each crossing, core.kernels.shadow_log),
    else 0: no light passes it."""
    refracted = table.transparency if refraction_passes else 0.0
    share = np.minimum(1.0, refracted + table.transparent.mean(axis=1))
    for k in np.flatnonzero(table.shader_range[:, 0] >= 0):
        lets_through = passes_light(surfaces[k], refraction_passes)
        share[k] = SHADOW_VARIES if lets_through else 0.0
    return share


def shadow_powers(table: Materials, shares: np.ndarray, refraction_passes: bool) -> np.ndarray:
    """float64 (m, 3): the colour of each material's share (`shadow_shares`) as powers of
    it, ln(colour) / ln(share) per channel (Geometry.shape_shadow_power), so that n
    crossings pass share^n in all and colour^n per channel: a red Transparent BSDF casts a
    red shadow, as in Cycles. 1 (grey) where the share is 0, 1 or varies over the surface."""
    refracted = table.transparency if refraction_passes else np.zeros_like(table.transparency)
    colour = np.minimum(1.0, refracted[:, None] + table.transparent)
    power = np.ones((len(shares), 3))
    tinted = (shares > 0.0) & (shares < 1.0) & (np.ptp(colour, axis=1) > 0.0)
    with np.errstate(divide="ignore"):  # a channel of 0: power inf, share^inf = 0
        power[tinted] = np.log(colour[tinted]) / np.log(shares[tinted])[:, None]
    return power


def folded_row(table: Materials, k: int) -> dict:
    """What the kernels read of row k, by core.Material's field names (for tests)."""
    return dict(
        diffuse=table.diffuse[k], specular=table.specular[k], shininess=table.shininess[k],
        reflectivity=table.reflectivity[k], transparency=table.transparency[k],
        inner_ior=table.ior[k, 1], mirror_colour=table.mirror[k, 0],
        mirror_edge=table.mirror[k, 1], mirror_sees_lights=not table.mirror_hides_lights[k],
        coat=table.coat[k, 0], coat_ior=table.coat[k, 1], coat_hides=bool(table.coat[k, 2]),
        glass_reflect=table.glass_tint[k, 0], glass_transmit=table.glass_tint[k, 1],
        refraction_fresnel=table.refraction_fresnel[k], emission=table.emission[k],
        transparent=table.transparent[k], holdout=table.holdout[k],
        roughness=table.roughness[k], programmed=table.shader_range[k, 0] >= 0,
        gloss=table.gloss[k], clear_coat=table.clear_coat[k],
        translucent=table.translucent[k], diffuse_roughness=table.diffuse_roughness[k],
    )  # fmt: skip


def _no_gloss(count: int) -> np.ndarray:
    """Gloss rows of no glint (core.kernels.surface_terms), a coat IOR of 1.5 as its default."""
    gloss = np.zeros((count, GLOSS_COLUMNS))
    gloss[:, 15] = 1.5
    gloss[:, 17:20] = 1.0  # no Specular Tint
    return gloss


def _no_clear_coat(count: int) -> np.ndarray:
    """Clear coat rows of no coat."""
    none = NO_CLEAR_COAT
    row = (*none[:4], *none.tint, *none.normal, float(none.at_normal))
    assert len(row) == CLEAR_COAT_COLUMNS
    return np.tile(np.array(row, float), (count, 1))


def _edge(material):
    """The mirror's tint at grazing incidence: its own tint when it has no Fresnel."""
    return material.mirror_colour if material.mirror_edge is None else material.mirror_edge


def _pairs(values: list) -> np.ndarray:
    """float64 (n, 2, 3) from n pairs of RGB triples."""
    return np.array(values, float).reshape(-1, 2, 3)

"""Materials and their textures."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..checks import Vec3, check_choice, check_count, check_flag, check_number, check_vec3
from ..errors import SceneError
from ..vocabulary import BUMP_RULES
from .shader import ShaderNode


@dataclass(eq=False)
class Texture:
    """An image that replaces a material's diffuse colour, looked up bilinearly and repeated.

    path    -- an image file Pillow can read (PNG, JPEG, ...); or None when `pixels` is given
    pixels  -- alternatively an (h, w, 3) or (h, w, 4) float array in [0, 1], row 0 at the top
    srgb    -- whether the values are sRGB-encoded (true of ordinary image files, and Blender's
               colour textures) and so converted to linear; False uses them as they are (the
               report's renderer did)
    """

    path: str | Path | None = None
    pixels: np.ndarray | None = None
    srgb: bool = True
    name: str = "Texture"

    def validate(self, owner: str) -> None:
        if (self.path is None) == (self.pixels is None):
            raise SceneError(owner, "texture", "give either an image file path or pixels")
        if self.pixels is not None:
            p = np.asarray(self.pixels)
            if p.ndim != 3 or p.shape[2] not in (3, 4) or min(p.shape[:2]) < 1:
                raise SceneError(owner, "texture", f"pixels of shape {p.shape}; use (h, w, 3|4)")
            return
        path = Path(self.path)
        if not path.is_file():
            raise SceneError(owner, "texture", f"image file '{path}' does not exist")


@dataclass(eq=False)
class Material:
    """The report's material: Phong, plus mirror reflection, refraction and a texture; and
    what Blender's shader nodes add to it (core.kernels.integrator has the formulas).

    diffuse       -- linear RGB diffuse reflectance kd, each channel >= 0
    specular      -- linear RGB specular reflectance ks, each channel >= 0
    shininess     -- Phong exponent p >= 0 in ks (R.V)^p
    reflectivity  -- 0..1: weight of the mirror-reflected colour added to the surface colour
    transparency  -- 0..1: fraction of the colour that comes from the dielectric: Fresnel's
                     reflectance F times the reflected colour plus (1 - F) times the refracted
                     colour; the other 1 - transparency is the surface colour plus mirror
    outer_ior     -- index of refraction outside the surface (> 0)
    inner_ior     -- index of refraction inside it (> 0); glass is about 1.5
    texture       -- a `Texture` replacing `diffuse`, or None
    pass_index    -- its value in the material index pass (Material > Settings > Pass Index)

    What Blender's node materials need beyond the report's (the defaults change nothing):
    mirror_colour  -- RGB tint of the mirror at normal incidence (a metal's, a Glossy BSDF's
                      colour)
    mirror_edge    -- RGB the mirror's tint tends to at grazing incidence, Schlick's
                      c + (edge - c)(1 - cos)^5; None: the same as mirror_colour (no Fresnel)
    mirror_sees_lights -- False: lights are not seen in the mirror, as the highlight
                      already holds their light (a rough surface's: its glint,
                      core.kernels.microfacet, for a node material)
    coat           -- 0..1: weight of a clear dielectric layer over the surface, reflecting
                      with the exact Fresnel reflectance of coat_ior (Principled's specular)
    coat_ior       -- its index of refraction (> 0); 1 reflects nothing
    coat_hides     -- True: the diffuse colour below is dimmed by what the layer reflects,
                      (1 - coat F), as Cycles 4's Principled layers; False adds it on top
    glass_reflect  -- RGB tint of the dielectric's Fresnel reflection (Glass BSDF colour)
    glass_transmit -- RGB tint of its refracted ray, at each crossing of the surface
    refraction_fresnel -- 0..1: how much of what Fresnel reflects the refracted ray loses:
                      1 for glass, 0 for Blender's Refraction BSDF (all refracts)
    emission       -- RGB radiance the surface emits, both sides (Emission, Principled)
    transparent    -- RGB share of the light passing straight through, unbent (Transparent
                      BSDF, alpha below 1); shadow rays pass its mean
    holdout        -- 0..1: share of a camera ray's pixel cut out (Holdout shader): alpha
                      lowered by it, nothing seen there
    roughness      -- 0..1: the mirror's, coat's and glass's GGX roughness (Cycles' alpha is
                      its square). Kept sharp unless RenderSettings.glossy_samples asks for
                      their rays to be spread over the lobe
    emission_lights -- whether its emission lights other surfaces (core.compile.glowing) or
                      is only seen
    surface        -- a closure `ShaderNode` (core.model.shader): Blender's node graph, which
                      then makes every term above per hit (name and pass_index still count)
    absorption     -- RGB absorption coefficient (per unit of world length, each >= 0) of the
                      medium the surface encloses: a ray travelling t inside keeps
                      exp(-absorption t) of its light (Beer-Lambert; Blender's Volume
                      Absorption on the Material Output's Volume, (1 - Color) Density;
                      core.kernels.absorption). The mesh should be closed, its normals out
    translucent    -- RGB Lambertian transmission, each >= 0: the light falling on the
                      surface's other side, seen through it diffusely (Blender's Translucent
                      BSDF; core.kernels.translucent)
    diffuse_roughness -- 0..1: the diffuse's Oren-Nayar roughness (Blender's Diffuse BSDF
                      Roughness, Principled Diffuse Roughness; core.kernels.rough_diffuse),
                      0 Lambert's
    bump_rule      -- the shadow terminator term (RenderSettings.bump_terminator) of a normal
                      its graph bends: "corrected" (Blender's Material › Settings › Bump Map
                      Correction on), "uncorrected" (off: no term, but from Cycles 4.5 its
                      test that the light and the bent normal are on one side of the smooth
                      surface), "displaced" (the bend is the Material Output's Displacement,
                      which Cycles makes the surface's own normal: no term)
    """

    diffuse: Vec3 = (0.8, 0.8, 0.8)
    specular: Vec3 = (0.0, 0.0, 0.0)
    shininess: float = 1.0
    name: str = "Material"
    reflectivity: float = 0.0
    transparency: float = 0.0
    outer_ior: float = 1.0
    inner_ior: float = 1.0
    texture: Texture | None = None
    pass_index: int = 0
    mirror_colour: Vec3 = (1.0, 1.0, 1.0)
    mirror_edge: Vec3 | None = None
    mirror_sees_lights: bool = True
    coat: float = 0.0
    coat_ior: float = 1.5
    coat_hides: bool = False
    glass_reflect: Vec3 = (1.0, 1.0, 1.0)
    glass_transmit: Vec3 = (1.0, 1.0, 1.0)
    refraction_fresnel: float = 1.0
    emission: Vec3 = (0.0, 0.0, 0.0)
    transparent: Vec3 = (0.0, 0.0, 0.0)
    holdout: float = 0.0
    roughness: float = 0.0
    emission_lights: bool = True
    surface: ShaderNode | None = None
    absorption: Vec3 = (0.0, 0.0, 0.0)
    translucent: Vec3 = (0.0, 0.0, 0.0)
    diffuse_roughness: float = 0.0
    bump_rule: str = "corrected"

    def validate(self, user: str) -> None:
        owner = f"material '{self.name}' (on {user})"
        check_vec3(owner, "diffuse", self.diffuse, nonnegative=True)
        check_vec3(owner, "specular", self.specular, nonnegative=True)
        check_number(owner, "shininess", self.shininess, low=0.0)
        check_number(owner, "reflectivity", self.reflectivity, low=0.0, high=1.0)
        check_number(owner, "transparency", self.transparency, low=0.0, high=1.0)
        check_number(owner, "outer_ior", self.outer_ior, low=0.0, low_open=True)
        check_number(owner, "inner_ior", self.inner_ior, low=0.0, low_open=True)
        check_count(owner, "pass_index", self.pass_index, high=32767)
        for name in (
            "mirror_colour",
            "glass_reflect",
            "glass_transmit",
            "emission",
            "absorption",
            "translucent",
        ):
            check_vec3(owner, name, getattr(self, name), nonnegative=True)
        if self.mirror_edge is not None:
            check_vec3(owner, "mirror_edge", self.mirror_edge, nonnegative=True)
        check_number(owner, "coat", self.coat, low=0.0, high=1.0)
        check_number(owner, "coat_ior", self.coat_ior, low=0.0, low_open=True)
        check_flag(owner, "coat_hides", self.coat_hides)
        check_flag(owner, "mirror_sees_lights", self.mirror_sees_lights)
        check_flag(owner, "emission_lights", self.emission_lights)
        check_number(owner, "refraction_fresnel", self.refraction_fresnel, low=0.0, high=1.0)
        transparent = check_vec3(owner, "transparent", self.transparent, nonnegative=True)
        if transparent.max() > 1.0:
            raise SceneError(owner, "transparent", f"got {self.transparent!r}; use 0..1 each")
        check_number(owner, "holdout", self.holdout, low=0.0, high=1.0)
        check_number(owner, "roughness", self.roughness, low=0.0, high=1.0)
        check_number(owner, "diffuse_roughness", self.diffuse_roughness, low=0.0, high=1.0)
        check_choice(owner, "bump_rule", self.bump_rule, tuple(BUMP_RULES))
        if self.surface is not None:
            if not isinstance(self.surface, ShaderNode) or not self.surface.is_closure:
                raise SceneError(owner, "surface", f"got {self.surface!r}; need a closure "
                                 "ShaderNode (a BSDF, Emission, Mix Shader...)")  # fmt: skip
            self.surface.validate(owner, {})
        if self.texture is not None:
            if not isinstance(self.texture, Texture):
                raise SceneError(owner, "texture", f"got {self.texture!r}; need a Texture")
            self.texture.validate(owner)

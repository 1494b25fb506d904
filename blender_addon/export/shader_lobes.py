"""What a Blender shader contributes, in Whitted's terms: `Lobes`, each weighted by its share
of the material (Mix Shader factors multiply down the tree, Add Shader sums).

Every lobe is linear in its weight, so a mix of shaders is the weighted sum of their lobes:

    diffuse            Lambert albedo (RGB)
    mirror_normal/edge a sharp mirror's tint at normal and grazing incidence (Schlick), RGB
    coat               a clear dielectric layer's weight, reflecting with the exact Fresnel
                       reflectance of coat_ior; coat_hides: it dims the diffuse below by what
                       it reflects (Cycles 4's Principled layering)
    glass              a dielectric's weight, with its IOR, the tint of its reflection and of
                       its refracted ray (at each crossing), and refraction_fresnel 1 (Glass:
                       the refracted ray loses what Fresnel reflects) or 0 (Refraction BSDF)
    highlight          Phong highlights of the lights from rough lobes: ks and shininess
    emission           emitted radiance (RGB)
    transparent        what passes straight through (RGB)
    holdout            the share cut out of the picture

Roughness r (alpha = r^2, as Cycles) keeps mirrors and glass sharp, carrying the lobe's whole
reflectance, so a rough surface reflects as much light as in Cycles, unblurred. Past
SHARP_ROUGHNESS a mirror or coat lobe (not glass) also makes a Phong highlight of the
lights: exponent p = (2 / alpha^2 - 2) / 4 (Walter et al. 2007's Blinn-Phong equivalent of
a microfacet lobe, on R.V) and ks = F0 (2p + 1) / 4, which is the GGX lobe's peak
F0 / (4 alpha^2) seen and lit head-on; its mirror then does not show the lights again
(`mirror_sees_lights` False).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

# Roughness up to which a lobe is a perfect mirror (lights seen in it, no highlight)
SHARP_ROUGHNESS = 0.1
# The largest Phong exponent a highlight gets (roughness just past SHARP_ROUGHNESS)
MAX_SHININESS = 10000.0


def _rgb(value=0.0) -> np.ndarray:
    return np.full(3, float(value))


@dataclass
class Lobes:
    diffuse: np.ndarray = field(default_factory=_rgb)
    mirror_normal: np.ndarray = field(default_factory=_rgb)
    mirror_edge: np.ndarray = field(default_factory=_rgb)
    coat: float = 0.0
    coat_ior_sum: float = 0.0  # coat_ior times coat, summed (a mean over coats)
    coat_hides: bool = False
    glass: float = 0.0
    glass_ior_sum: float = 0.0  # ior times glass weight, summed
    glass_reflect: np.ndarray = field(default_factory=_rgb)  # tint times glass weight
    glass_transmit: np.ndarray = field(default_factory=_rgb)
    refraction_fresnel_sum: float = 0.0
    highlight: np.ndarray = field(default_factory=_rgb)  # ks
    shininess_sum: float = 0.0  # shininess times the highlight's mean ks
    emission: np.ndarray = field(default_factory=_rgb)
    transparent: np.ndarray = field(default_factory=_rgb)
    holdout: float = 0.0
    rough_mirror: bool = False  # a rough lobe's highlight stands for the lights in its mirror
    # the diffuse colour's image (an Image Texture feeding it) and the weight it comes with
    texture: object = None
    texture_weight: float = 0.0
    glass_iors: set = field(default_factory=set)  # the distinct IORs mixed, to warn about

    def add(self, other: Lobes) -> None:
        for name, value in vars(other).items():
            if name in ("coat_hides", "rough_mirror"):
                setattr(self, name, getattr(self, name) or value)
            elif name == "texture":
                if value is not None and self.texture is None:
                    self.texture, self.texture_weight = value, other.texture_weight
            elif name == "glass_iors":
                self.glass_iors |= value
            elif name != "texture_weight":
                setattr(self, name, getattr(self, name) + value)

    def add_diffuse(self, weight: float, colour, texture=None) -> None:
        self.diffuse += weight * np.asarray(colour, float)
        if texture is not None and self.texture is None:
            self.texture, self.texture_weight = texture, weight

    def add_mirror(self, weight: float, normal, edge, roughness: float) -> None:
        normal, edge = np.asarray(normal, float), np.asarray(edge, float)
        self.mirror_normal += weight * normal
        self.mirror_edge += weight * edge
        self._highlight(weight * normal, roughness)

    def add_coat(self, weight: float, ior: float, roughness: float, hides: bool) -> None:
        self.coat += weight
        self.coat_ior_sum += weight * ior
        self.coat_hides = self.coat_hides or hides
        self._highlight(_rgb(weight * f0_of_ior(ior)), roughness)

    def add_glass(self, weight, ior, reflect, transmit, fresnel=1.0) -> None:
        """Glass stays sharp at any roughness, its reflection showing the lights (the
        integrator lights no surface under a glass share of 1, so it has no highlight)."""
        self.glass += weight
        self.glass_ior_sum += weight * ior
        self.glass_iors.add(round(float(ior), 4))
        self.glass_reflect += weight * np.asarray(reflect, float)
        self.glass_transmit += weight * np.asarray(transmit, float)
        self.refraction_fresnel_sum += weight * fresnel

    def _highlight(self, f0: np.ndarray, roughness: float) -> None:
        if roughness <= SHARP_ROUGHNESS or not np.any(f0 > 0.0):
            return
        shininess = phong_exponent(roughness)
        ks = f0 * (2.0 * shininess + 1.0) / 4.0  # the GGX lobe's peak, head-on
        self.highlight += ks
        self.shininess_sum += shininess * float(ks.mean())
        self.rough_mirror = True

    def kinds(self) -> list[str]:
        """The names of the lobes present, as the material panel lists them."""
        present = (
            ("diffuse", np.any(self.diffuse > 0.0) or self.texture is not None),
            ("mirror", np.any(self.mirror_normal > 0.0) or np.any(self.mirror_edge > 0.0)),
            ("specular coat", self.coat > 0.0),
            ("highlights", np.any(self.highlight > 0.0)),
            ("glass", self.glass > 0.0),
            ("emission", np.any(self.emission > 0.0)),
            ("transparent", np.any(self.transparent > 0.0)),
            ("holdout", self.holdout > 0.0),
        )
        return [name for name, there in present if there]


def phong_exponent(roughness: float) -> float:
    """The Phong exponent (on R.V) of a microfacet lobe of Blender's roughness."""
    alpha = max(float(roughness), 1e-4) ** 2
    return float(min(max((2.0 / alpha**2 - 2.0) / 4.0, 0.0), MAX_SHININESS))


def f0_of_ior(ior: float) -> float:
    """A dielectric's reflectance at normal incidence."""
    return ((ior - 1.0) / (ior + 1.0)) ** 2


def ior_of_f0(f0: float) -> float:
    root = np.sqrt(min(max(f0, 0.0), 0.9999))
    return float((1.0 + root) / (1.0 - root))

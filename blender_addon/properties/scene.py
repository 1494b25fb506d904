"""Render Properties › Sampling, Light Paths, Performance: Whitted's render settings, drawn by
ui.render. Tooltips speak of what a user sees (noise, time, blur), not of the CS488 report
the project grew from."""

import bpy
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    IntProperty,
)

from ..core.model.settings import (
    DEFAULT_ENVIRONMENT_SAMPLES,
    DEFAULT_GLOSSY_SAMPLES,
    DEFAULT_PIXEL_SAMPLES,
    DEFAULT_SHADOW_SAMPLES,
)


class WhittedSceneSettings(bpy.types.PropertyGroup):
    max_depth: IntProperty(
        name="Max Bounces",
        description=(
            "Reflection and refraction bounces after the camera ray; each level can double "
            "the rays of a pixel between facing mirrors or through glass"
        ),
        min=0,
        soft_max=16,
        max=64,
        default=5,
    )
    glass_shadows: EnumProperty(
        name="Glass Shadows",
        description="What light does at glass and other refracting surfaces on its way to a "
        "lit point",
        items=[
            (
                "BLOCKED",
                "Blocked",
                "Refracting surfaces (Glass and Refraction BSDFs, Principled Transmission) "
                "block direct light, as in Cycles: a glass ball casts a full shadow. "
                "Transparent BSDF and Alpha still let light through",
            ),
            (
                "ATTENUATED",
                "Attenuated",
                "Shadow rays pass refracting surfaces unbent, dimmed by their transmission: "
                "the classic ray tracer's approximation, lighter than physics (a glass ball's "
                "shadow is pale, with no focused light in it)",
            ),
        ],
        default="BLOCKED",
    )
    use_caustics_reflective: BoolProperty(
        name="Reflective Caustics",
        description="Light that mirrors throw onto diffuse surfaces (a mirror's sun patch, a "
        "chrome bowl's focus), traced as photons from the lights",
        default=True,
    )
    use_caustics_refractive: BoolProperty(
        name="Refractive Caustics",
        description="Light that glass focuses onto diffuse surfaces (a glass ball's bright "
        "spot in its shadow), traced as photons from the lights. Needs Light Paths > Glass: "
        "Blocked",
        default=True,
    )
    use_auto_photons: BoolProperty(
        name="Automatic Photons",
        description="Trace as many caustic photons as the caustics in the camera's frame need "
        "(a pilot pass measures them: a caustic filling the frame gets more than a glint), "
        "at most one per camera ray, so the pass costs no more than the rest of the render",
        default=True,
    )
    caustic_photons: IntProperty(
        name="Caustic Photons",
        description="Photons traced for caustics (Automatic off), shared among the lights, "
        "mirrors and glass by the power each sends: more give a smoother, sharper caustic "
        "(both errors fall as the fourth root). No photon is traced in a scene without "
        "mirrors or glass",
        min=0,
        soft_max=2_000_000,
        max=10_000_000,
        default=200_000,
    )
    pixel_samples: IntProperty(
        name="Anti-Aliasing",
        description=(
            "n: each pixel averages n x n camera rays, smoothing jagged edges (3 is smooth for "
            "most scenes); render time grows as n squared"
        ),
        min=1,
        soft_max=8,
        max=32,
        default=DEFAULT_PIXEL_SAMPLES,
    )
    use_adaptive_pixels: BoolProperty(
        name="Adaptive Anti-Aliasing",
        description=(
            "Trace one ray at each pixel corner and one at its centre first, and a pixel's "
            "own rays only where these differ by more than the threshold: flat areas cost "
            "two rays a pixel, edges all of them. May miss detail smaller than a pixel "
            "that none of the five meets"
        ),
        default=False,
    )
    adaptive_threshold: FloatProperty(
        name="Adaptive Threshold",
        description=(
            "How far a pixel's corners and centre may differ (in each colour, compressed as "
            "x / (1 + x), and in alpha) before it gets its own rays: lower is finer and slower"
        ),
        min=0.0001,
        max=1.0,
        default=0.02,
        precision=4,
    )
    pixel_sampling: EnumProperty(
        name="Pattern",
        description="Where in the pixel the camera rays go",
        items=[
            ("GRID", "Grid", "At the centres of an n x n grid: no noise, fine patterns may alias"),
            ("JITTERED", "Jittered", "At a random point in each grid cell: noise, not aliasing"),
            ("RANDOM", "Random", "At independent random points in the pixel (for comparison)"),
        ],
        default="GRID",
    )
    shadow_sampling: EnumProperty(
        name="Shadow Pattern",
        description="Where on an area light the shadow rays go",
        items=[
            (
                "STRATIFIED",
                "Stratified",
                "One ray in each of equal cells of the light (at 1 shadow sample, one cell for "
                "each of the pixel's camera rays): less noise",
            ),
            ("UNIFORM", "Uniform", "Independent random points: the most noise, for comparison"),
            ("HALTON", "Halton", "Low-discrepancy points, randomly shifted per shading point"),
        ],
        default="STRATIFIED",
    )
    seed: IntProperty(
        name="Seed",
        description="Selects the random numbers; the same seed gives the same picture",
        min=0,
        default=0,
    )
    shadow_samples: IntProperty(
        name="Soft Shadow Samples",
        description=(
            "Shadow rays per area light per shading point, stratified over the light (at 1, "
            "over the pixel's camera rays together); render time grows in proportion, noise "
            "falls as its square root"
        ),
        min=1,
        soft_max=256,
        default=DEFAULT_SHADOW_SAMPLES,
    )
    adaptive_shadows: BoolProperty(
        name="Adaptive Soft Shadows",
        description=(
            "Probe each light at nine points of its outline and centre first, and cast its "
            "shadow rays only where they disagree: lit and shadowed areas cost nine rays, "
            "penumbrae all of them. May miss an occluder narrower than the light"
        ),
        default=False,
    )
    environment_samples: IntProperty(
        name="World Samples",
        description=(
            "Shadow rays towards the World per shading point, for its light (its colour or "
            "Environment Texture); 0 lights nothing by it. Noise falls as its square root"
        ),
        min=0,
        soft_max=256,
        max=65536,
        default=DEFAULT_ENVIRONMENT_SAMPLES,
    )
    glossy_samples: IntProperty(
        name="Glossy Samples",
        description=(
            "Rays spread over a rough mirror's or glass's lobe where a camera ray meets it "
            "(fewer where the lobe reflects little, as a plastic's; one at later bounces), "
            "blurring reflections and refractions as Cycles does. 0 keeps rough surfaces "
            "sharp: as bright as their lobe on average, at no cost"
        ),
        min=0,
        soft_max=256,
        max=4096,
        default=DEFAULT_GLOSSY_SAMPLES,
    )
    tile_size: IntProperty(
        name="Tile Size",
        description="Edge of the square tiles rendered in parallel and streamed to the image",
        min=8,
        max=1024,
        default=32,
    )

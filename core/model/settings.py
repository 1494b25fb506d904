"""How to render: image size, tiling, threads, recursion and sampling."""

from __future__ import annotations

from dataclasses import dataclass

from ..checks import check_choice, check_count, check_flag, check_number, machine_memory
from ..errors import SceneError
from ..passes import DEFAULT_CRYPTO_LEVELS, MAX_CRYPTO_LEVELS, MIST_FALLOFFS, channels, check_passes
from ..vocabulary import (
    BUMP_TERMINATORS,
    GLASS_SHADOWS,
    PIXEL_PATTERNS,
    ROUGH_DIFFUSE_MODELS,
    SHADOW_PATTERNS,
)

PIXEL_SAMPLINGS = tuple(PIXEL_PATTERNS)
SHADOW_SAMPLINGS = tuple(SHADOW_PATTERNS)
GLASS_SHADOW_RULES = tuple(GLASS_SHADOWS)
CAUSTIC_KINDS = ("reflective", "refractive")
# Photons traced for caustics by default, when asked for: as many as the caustics in the frame
# need (core.compile.photon_budget); and at most (88 bytes a stored photon, up to two stored
# a photon traced: 1.8 GB)
AUTO_PHOTONS = "auto"
DEFAULT_CAUSTIC_PHOTONS = AUTO_PHOTONS
MAX_CAUSTIC_PHOTONS = 10_000_000
# The defaults a new render starts with, from the speed-against-accuracy charts
# (tests/benchmarks: bench_sampling, bench_whole_scene): 3 x 3 grid camera rays cut the edge
# scene's anti-aliasing error 7x for 9 rays, and past 4 shadow rays per shading point no
# anti-aliasing setting of the final scene up to 4 x 4 gained 3% in accuracy
DEFAULT_PIXEL_SAMPLES = 3
DEFAULT_SHADOW_SAMPLES = 4
# Shadow rays towards the environment (the World) per shading point. bench_environment (an
# HDRI with a small sun): each doubling cuts the error by a third at every count, and from 8
# to 16 the render time starts to double with the rays (1.75x): 16 sits at that knee, with
# 144 rays a pixel under the default 3 x 3 camera rays
DEFAULT_ENVIRONMENT_SAMPLES = 16
# Rays a rough surface's lobe spreads where a camera ray meets it, in Blender (Render ›
# Sampling › Glossy Blur › Samples; the core's own default, 0, keeps the sharp rule of the
# CS488 scenes). bench_glossy: the error against time bends at 64 rays a pixel (the point
# farthest from the chord of its curve, 1 to 1,024 rays); under Blender's default 3 x 3
# camera rays a pixel, 8 each make 72
DEFAULT_GLOSSY_SAMPLES = 8
# Far beyond any that changes a picture (a million camera rays per pixel; 65536 shadow rays
# per light), and below where the sample numbers overflow
MAX_PIXEL_SAMPLES = 1024
MAX_SHADOW_SAMPLES = 65536
MAX_GLOSSY_SAMPLES = 4096
MAX_BOUNCES = 10_000


@dataclass
class RenderSettings:
    """How to render: image size, tiling, threads, recursion and sampling.

    width, height    -- image size in pixels, each >= 1
    tile_size        -- edge of the square tiles handed to threads and streamed back, >= 1
    threads          -- worker threads; 0 means one per available core
    region           -- optional (x, y, width, height) in pixels, y counted from the top row:
                        render only this part (a render border); pixels are the same as in a
                        full render
    max_depth        -- reflection/refraction bounces after the camera ray, >= 0
    pixel_samples    -- n: each pixel averages n x n camera rays (the report used 3), <= 1024
    pixel_sampling   -- "grid": at the centres of the n x n cells (the report's supersampling);
                        "jittered": one random point in each cell; "random": n x n
                        independent random points in the pixel
    shadow_samples   -- shadow rays per area light per shading point, 1 to 65536
    shadow_sampling  -- "stratified": one sample in each of as many equal-area cells of the
                        light (at 1 shadow sample, a pixel's n x n camera rays share out
                        n x n cells, each its own, in a random order per pixel); "uniform":
                        independent random points (the report's way);
                        "halton": the Halton sequence, shifted at random per shading point
    adaptive_threshold -- adaptive anti-aliasing, from 2 x 2 pixel_samples up: 0 gives every
                        pixel its n x n camera rays (the exact, report's way); t > 0 traces
                        one ray at each pixel corner (shared by the four pixels that meet
                        there) and one at each pixel's centre, and gives a pixel its n x n
                        rays only where these differ by more than t (in R, G, B after
                        x / (1 + x), or alpha), otherwise half the centre and an eighth
                        each corner (core.kernels.adaptive_tile); 0 to 1
    adaptive_shadows -- adaptive soft shadows: nine probe rays to each area light first (eight
                        around its outline and its centre), its samples' rays only where
                        the probes disagree; fully lit and fully shadowed points then cost
                        9 rays, not shadow_samples (core.kernels.shadow_rays), from 18
                        shadow samples up. False casts every sample's ray, the exact
                        estimate
    environment_samples -- shadow rays towards the environment (the World's light) per
                        shading point, 0 to 65536; 0 lights nothing by it (it is still seen
                        behind the scene and in mirrors and glass)
    glossy_samples   -- 0: rough mirrors and glass stay sharp, reflecting and refracting
                        as much light as their rough lobe does on average (the documented
                        rule of core.kernels.glossy); n > 0: each camera ray's hit on one
                        spreads up to n rays over its GGX lobe (n times the share of the
                        light its lobes send on; later hits one each), blurring them as
                        Cycles does; 0 to 4096 (Blender's default: DEFAULT_GLOSSY_SAMPLES)
    bump_terminator  -- the shadow terminator term a diffuse lit through a bent normal (Bump,
                        Normal Map) is weighed by (core.kernels.bent_normal): "chiang"
                        (Chiang, Li and Burley's, Cycles before 4.5: the light kept where
                        the bent normal faces a light the smooth surface faces away from),
                        "conty" (Conty Estevez, Lecocq and Stein's microfacet shadowing,
                        Cycles from 4.5), or "none"
    rough_diffuse    -- the Oren-Nayar model of a diffuse's roughness: "EON", energy
                        preserving (Cycles from 4.3), or "FON", Fujii's (Cycles before);
                        core.kernels.rough_diffuse
    seed             -- selects the random numbers; the same seed gives the same picture
    transparent      -- camera rays that meet nothing are transparent: alpha 0 there and
                        fractional at edges, colour premultiplied (Blender's Film ›
                        Transparent); what mirrors and glass show still includes the
                        background, and a glass surface itself is opaque, as in Cycles
    passes           -- names of the render passes to make beside Combined (see core.passes:
                        depth, mist, normal, position, uv, object_index, material_index,
                        diffuse_color, shadow, the terms of Combined, crypto_object, ...)
    crypto_levels    -- Cryptomatte ranks kept per pixel (objects or materials), 1 to 16
    mist_start, mist_depth, mist_falloff -- the mist pass: 0 at mist_start from the camera,
                        1 at mist_start + mist_depth, the ramp raised to 2 ("QUADRATIC"), 1
                        ("LINEAR") or 1/2 ("INVERSE_QUADRATIC"), as Blender's World > Mist Pass
    glass_shadows    -- what a shadow ray does at a refracting surface (a material's
                        transparency: glass, Principled Transmission, Refraction BSDF):
                        "attenuated" passes it unbent, the light dimmed by the transparency
                        (the report's rule: a classic ray tracer's cheap approximation,
                        lighter than physics: a glass ball's shadow is 1 - tau dark with no
                        caustic); "blocked" stops it, as physics has it and Cycles draws it:
                        light reaches what lies behind glass only along refracted paths.
                        What passes a surface straight (Transparent BSDF, Alpha) lights what
                        is behind under either rule. Blender scenes render "blocked"
    caustics         -- light carried by mirrors ("reflective") and glass ("refractive") onto
                        diffuse surfaces, traced as photons from the lights in Blender's
                        units (core.compile.caustics); refractive caustics need
                        glass_shadows "blocked". () traces none (the report's pictures)
    caustic_photons  -- photons traced for caustics, shared among the lights and the
                        mirrors and glass by the power each sends; 0 to 10 million, or
                        "auto": as many as the caustics the camera sees need, from a pilot
                        pass, within the full frame's camera rays (core.compile.photon_budget)
    caustic_photons_max -- the most "auto" traces (the viewport's cap), 1 to 10 million
    shadow_culling   -- an area light's shadow rays test only the shapes in the pyramid from
                        the shading point to the light, from 8 shadow rays per light up
                        (below, it costs more than it saves): exact, the same pixels either
                        way; False only to measure what it saves
    """

    width: int = 640
    height: int = 480
    tile_size: int = 32
    threads: int = 0
    region: tuple[int, int, int, int] | None = None
    max_depth: int = 5
    pixel_samples: int = DEFAULT_PIXEL_SAMPLES
    pixel_sampling: str = "grid"
    shadow_samples: int = DEFAULT_SHADOW_SAMPLES
    shadow_sampling: str = "stratified"
    adaptive_shadows: bool = False
    adaptive_threshold: float = 0.0
    environment_samples: int = DEFAULT_ENVIRONMENT_SAMPLES
    glossy_samples: int = 0
    bump_terminator: str = "chiang"
    rough_diffuse: str = "EON"
    seed: int = 0
    shadow_culling: bool = True
    glass_shadows: str = "attenuated"
    caustics: tuple[str, ...] = ()
    caustic_photons: int | str = DEFAULT_CAUSTIC_PHOTONS
    caustic_photons_max: int = MAX_CAUSTIC_PHOTONS
    transparent: bool = False
    passes: tuple[str, ...] = ()
    crypto_levels: int = DEFAULT_CRYPTO_LEVELS
    mist_start: float = 5.0
    mist_depth: float = 25.0
    mist_falloff: str = "QUADRATIC"

    def validate(self) -> None:
        owner = "render settings"
        for name in ("width", "height", "tile_size"):
            check_count(owner, name, getattr(self, name), low=1)
        # Counts the kernels multiply into 64-bit sample numbers: beyond these they overflowed
        # into black pixels, long after any picture would change
        check_count(owner, "pixel_samples", self.pixel_samples, low=1, high=MAX_PIXEL_SAMPLES)
        check_count(owner, "shadow_samples", self.shadow_samples, low=1, high=MAX_SHADOW_SAMPLES)
        check_count(owner, "environment_samples", self.environment_samples, high=MAX_SHADOW_SAMPLES)
        # each waits on the ray stack (core.kernels.workspace): 4096 is a 64 x 64 lobe
        check_count(owner, "glossy_samples", self.glossy_samples, high=MAX_GLOSSY_SAMPLES)
        check_choice(owner, "bump_terminator", self.bump_terminator, tuple(BUMP_TERMINATORS))
        check_choice(owner, "rough_diffuse", self.rough_diffuse, tuple(ROUGH_DIFFUSE_MODELS))
        # Each bounce's ray waits on a stack of max_depth + 2 (core.kernels.workspace): past
        # this many, any light left is below what a pixel shows, and 1e12 asked for 21.8 TiB
        check_count(owner, "max_depth", self.max_depth, low=0, high=MAX_BOUNCES)
        check_count(owner, "seed", self.seed, low=0, high=2**63 - 1)
        check_count(owner, "threads", self.threads, low=0)
        check_choice(owner, "pixel_sampling", self.pixel_sampling, PIXEL_SAMPLINGS)
        check_choice(owner, "shadow_sampling", self.shadow_sampling, SHADOW_SAMPLINGS)
        check_flag(owner, "shadow_culling", self.shadow_culling)
        check_choice(owner, "glass_shadows", self.glass_shadows, GLASS_SHADOW_RULES)
        if isinstance(self.caustics, str) or not isinstance(self.caustics, (tuple, list)):
            raise SceneError(owner, "caustics", f"got {self.caustics!r}; use a tuple of "
                             f"{', '.join(CAUSTIC_KINDS)} (or () for none)")  # fmt: skip
        self.caustics = tuple(self.caustics)
        for kind in self.caustics:
            check_choice(owner, "caustics", kind, CAUSTIC_KINDS)
        if self.caustic_photons != AUTO_PHOTONS:
            if isinstance(self.caustic_photons, str):
                valid = f'a count from 0 to {MAX_CAUSTIC_PHOTONS:,} or "{AUTO_PHOTONS}"'
                got = f"got {self.caustic_photons!r}; use {valid}"
                raise SceneError(owner, "caustic_photons", got)
            check_count(owner, "caustic_photons", self.caustic_photons, high=MAX_CAUSTIC_PHOTONS)
        check_count(owner, "caustic_photons_max", self.caustic_photons_max, low=1,
                    high=MAX_CAUSTIC_PHOTONS)  # fmt: skip
        check_flag(owner, "adaptive_shadows", self.adaptive_shadows)
        check_number(owner, "adaptive_threshold", self.adaptive_threshold, low=0.0, high=1.0)
        check_flag(owner, "transparent", self.transparent)
        self.passes = check_passes(owner, self.passes)
        check_count(owner, "crypto_levels", self.crypto_levels, low=1, high=MAX_CRYPTO_LEVELS)
        check_number(owner, "mist_start", self.mist_start)
        check_number(owner, "mist_depth", self.mist_depth, low=0.0)
        check_choice(owner, "mist_falloff", self.mist_falloff, tuple(MIST_FALLOFFS))
        self._check_image_fits()
        if self.region is not None:
            x, y, w, h = self.region
            if w < 1 or h < 1 or x < 0 or y < 0 or x + w > self.width or y + h > self.height:
                raise SceneError(
                    owner,
                    "region",
                    f"got {self.region}; it must lie inside the {self.width}x{self.height} image",
                )

    def _check_image_fits(self) -> None:
        """Refuse, before allocating it, an image of more than half this machine's memory
        (float32 RGBA, 16 bytes a pixel, and 4 a channel of each pass; Blender keeps a copy
        of its own): a 65536 x 65536 frame started and would have needed 64 GiB."""
        memory = machine_memory()
        pass_channels = sum(channels(name, self.crypto_levels) for name in self.passes)
        needed = self.width * self.height * (16 + 4 * pass_channels)
        if memory is not None and needed > memory // 2:
            raise SceneError(
                "render settings",
                "width, height",
                f"a {self.width} x {self.height} image needs {needed / 2**30:.1f} GiB, more "
                f"than half of this machine's {memory / 2**30:.1f} GiB; render it smaller, or "
                "in parts, a render border each (README: on a render farm)",
            )

    def pixel_region(self) -> tuple[int, int, int, int]:
        return self.region if self.region is not None else (0, 0, self.width, self.height)

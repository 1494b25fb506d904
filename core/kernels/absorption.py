"""Beer-Lambert absorption in the medium a closed surface encloses (Blender's Volume
Absorption on a glass's Material Output Volume; glTF's KHR_materials_volume attenuation).

Light travelling a length t inside a medium of absorption coefficient sigma keeps
exp(-sigma t) of itself, channel by channel: exact for a homogeneous medium, as Cycles
computes it (no scattering, so nothing to sample). Each ray carries the material row of the
medium it travels in (`RayStack.medium`, a photon its own): a ray crossing a surface into
an object that absorbs (refracted or passing straight) enters that material's medium, and
crossing out of it is back in air; reflected rays stay where they are. Media are not
stacked: a ray leaving an absorbing object nested in another (ice in coloured water) is
taken to be in air, not in the outer medium. Shadow rays are not absorbed: under Cycles'
rule ("blocked" glass shadows) no shadow ray crosses glass, and the light the glass lets
through comes as caustic photons, which are absorbed (core.kernels.photons).
"""

import math

from ..jit.decorators import kernel
from .features import WITH_ABSORPTION

NO_MEDIUM = -1  # air: nothing absorbed


@kernel
def absorbed(mats, medium, w, t):
    """w (RGB) after a length t (inf: a ray that meets nothing) through the medium of
    material row `medium` (NO_MEDIUM: air)."""
    if not WITH_ABSORPTION or medium < 0:
        return w
    sigma = mats.absorption
    return (
        _kept(w[0], sigma[medium, 0], t),
        _kept(w[1], sigma[medium, 1], t),
        _kept(w[2], sigma[medium, 2], t),
    )


@kernel
def _kept(w, sigma, t):
    """One channel: no absorption keeps it all, even over an infinite length."""
    return w if sigma <= 0.0 else w * math.exp(-sigma * t)


@kernel
def medium_beyond(mats, material, entering, medium):
    """The medium a ray in `medium` travels in after crossing a surface of material row
    `material`: entering an object that absorbs, its material's; leaving the medium's own
    object, air; else (a surface of no medium of its own) the same."""
    if not WITH_ABSORPTION:
        return medium
    if entering:
        sigma = mats.absorption
        if sigma[material, 0] > 0.0 or sigma[material, 1] > 0.0 or sigma[material, 2] > 0.0:
            return material
        return medium
    return NO_MEDIUM if material == medium else medium

"""Sun lights: parallel light, or light from a small disk of sky `angle` degrees across.

Irradiance S on a surface facing the sun. Every sample has the same weight, and the
emitter table's radiance carries the rest (`core.kernels.emitters`):

- cone (Blender 4.0 on): directions uniform in the cone of half-angle h, radiance
  S / (pi sin^2 h), so that a facing surface receives S exactly; the table holds
  (S / pi) 2 / (1 + cos h).
- disk (Blender 3.x): directions through points uniform on a disk of radius tan h one unit
  away, each carrying S; the table holds S / pi. A facing surface receives
  S 2 (sqrt(1 + tan^2 h) - 1) / tan^2 h, less than S for a wide sun, as Blender 3.x shows.
"""

from ..jit.decorators import kernel
from .light_samples import concentric_disk, cone_direction, in_frame
from .vec import add, normalize


@kernel
def sun_sample(toward, one_minus_cos_half, tan_half, disk, a, b):
    """A unit direction towards the sun for sample (a, b) (its weight is 1)."""
    if disk:
        x, y = concentric_disk(a, b)
        return normalize(add(toward, in_frame(toward, tan_half * x, tan_half * y, 0.0)))
    return cone_direction(toward, one_minus_cos_half, a, b)

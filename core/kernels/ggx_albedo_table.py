"""The albedo E(r, mu) of a GGX lobe with F = 1 (core.kernels.microfacet), r its roughness
(alpha = r^2) and mu = n.v, on a square grid of both from 0 to 1, and E_avg(r) = 2 int E mu
dmu: computed, not copied. `python -m core.kernels.ggx_albedo_table` writes
core/kernels/ggx_albedo_values.py; the integration is too slow to run at import.

E is the mean over the normals visible from the view (Heitz 2018's sampler, driven by a
midpoint grid of its unit square instead of random numbers) of G2(v, l) / G1(v), l the view
mirrored about the normal, and 0 where l falls below the surface: the lobe's f cos(l)
integrated over l, importance-sampled exactly.
"""

import math
import sys
from pathlib import Path

import numpy as np

TABLE_SIZE = 33
DIELECTRIC_SIZE = 17
VALUES = Path(__file__).with_name("ggx_albedo_values.py")


def _visible_normals(mu, alpha, u1, u2):
    """numpy: microfacet normals (x, y, z arrays) of GGX's distribution of normals visible
    from the view (sqrt(1 - mu^2), 0, mu), drawn by the uniform numbers u1, u2 (Heitz 2018:
    the view stretched to unit roughness, a point on a half-squeezed disc, stretched back)."""
    sin = math.sqrt(max(0.0, 1.0 - mu * mu))
    vh = np.array([alpha * sin, 0.0, mu])
    vh /= np.linalg.norm(vh)
    t1 = np.array([0.0, 1.0, 0.0]) if vh[0] > 1e-9 else np.array([1.0, 0.0, 0.0])
    t2 = np.cross(vh, t1)
    r, phi = np.sqrt(u1), 2.0 * np.pi * u2
    p1, p2 = r * np.cos(phi), r * np.sin(phi)
    squeeze = 0.5 * (1.0 + vh[2])
    p2 = (1.0 - squeeze) * np.sqrt(np.maximum(0.0, 1.0 - p1 * p1)) + squeeze * p2
    up = np.sqrt(np.maximum(0.0, 1.0 - p1 * p1 - p2 * p2))
    m = p1[:, None] * t1 + p2[:, None] * t2 + up[:, None] * vh
    m = np.stack([alpha * m[:, 0], alpha * m[:, 1], np.maximum(m[:, 2], 0.0)], axis=1)
    return m / np.linalg.norm(m, axis=1)[:, None]


def _ggx_lambda(alpha2, cos):
    tan2 = np.maximum(1.0 / np.maximum(cos * cos, 1e-300) - 1.0, 0.0)
    return 0.5 * (np.sqrt(1.0 + alpha2 * tan2) - 1.0)


def _lobe(roughness, mu, u1, u2):
    """numpy: (G2(v, l) / G1(v), 0 where l is below the surface; v.m) of the visible normals
    m drawn by u1, u2, seen from mu: the lobe's weights and their Fresnel's cosines."""
    alpha = max(roughness * roughness, 1e-4)
    alpha2 = alpha * alpha
    mu = max(mu, 1e-4)
    v = np.array([math.sqrt(1.0 - mu * mu), 0.0, mu])
    m = _visible_normals(mu, alpha, u1, u2)
    vm = m @ v
    up = (2.0 * vm[:, None] * m - v)[:, 2]
    lambda_v = _ggx_lambda(alpha2, np.array(mu))
    g2 = 1.0 / (1.0 + lambda_v + _ggx_lambda(alpha2, up))
    return np.where(up > 0.0, g2 * (1.0 + lambda_v), 0.0), vm


def _unit_square(steps):
    grid = (np.arange(steps) + 0.5) / steps
    return [a.ravel() for a in np.meshgrid(grid, grid, indexing="ij")]


def ggx_albedo_table(size: int = TABLE_SIZE, steps: int = 384):
    """numpy: (E (size, size) over roughness x mu, E_avg (size,)) of a GGX lobe with F = 1:
    E = the mean over visible normals m of G2(v, l) / G1(v), l = v mirrored about m (0 where
    l falls below the surface), by the midpoint rule on a steps x steps grid of the sampler's
    unit square (the integrand is smooth there but for the horizon)."""
    u1, u2 = _unit_square(steps)
    rough = np.linspace(0.0, 1.0, size)
    mus = np.linspace(0.0, 1.0, size)
    table = np.ones((size, size))
    for i, r in enumerate(rough):
        for j, mu in enumerate(mus):
            table[i, j] = np.mean(_lobe(r, mu, u1, u2)[0])
    # E_avg = 2 * integral of E(mu) mu dmu, by the trapezoid rule over the grid
    weights = np.full(size, 1.0 / (size - 1))
    weights[0] = weights[-1] = 0.5 / (size - 1)
    average = 2.0 * (table * mus * weights).sum(axis=1)
    return table, average


def fresnel_dielectric(cos, ior):
    """numpy: the exact unpolarised reflectance from air into `ior` at incidence cos."""
    sin2_t = (1.0 - cos * cos) / (ior * ior)
    cos_t = np.sqrt(np.maximum(1.0 - sin2_t, 0.0))
    rs = (cos - ior * cos_t) / (cos + ior * cos_t)
    rp = (cos_t - ior * cos) / (cos_t + ior * cos)
    return 0.5 * (rs * rs + rp * rp)


def ior_of_z(z):
    """The IOR whose sqrt((ior - 1) / (ior + 1)) is z (the dielectric table's third axis)."""
    return (1.0 + z * z) / max(1.0 - z * z, 1e-9)


def dielectric_fresnel_table(size: int = DIELECTRIC_SIZE, steps: int = 128):
    """numpy: F_mean (size, size, size) over roughness x mu x z: a rough dielectric's Fresnel
    averaged over its GGX lobe seen from mu (the lobe's weights G2 / G1 as in
    ggx_albedo_table), z = sqrt((ior - 1) / (ior + 1)). Its directional albedo is F_mean E."""
    u1, u2 = _unit_square(steps)
    axis = np.linspace(0.0, 1.0, size)
    iors = [ior_of_z(z) for z in axis]
    table = np.ones((size, size, size))
    for i, r in enumerate(axis):
        for j, mu in enumerate(axis):
            weights, vm = _lobe(r, mu, u1, u2)
            total = weights.sum()
            for k, ior in enumerate(iors):
                if total > 0.0:
                    f = fresnel_dielectric(np.clip(vm, 1e-6, 1.0), ior)
                    table[i, j, k] = (weights * f).sum() / total
    return table


def _lines(values, per_line=11):
    numbers = [f"{x:.6f}" for x in np.ravel(values)]
    return "\n".join(" ".join(numbers[k : k + per_line]) for k in range(0, len(numbers), per_line))


def write_values(path: Path = VALUES, steps: int = 384) -> None:
    table, average = ggx_albedo_table(steps=steps)
    dielectric = dielectric_fresnel_table(steps=steps // 3)
    path.write_text(
        '"""E(r, mu) and E_avg(r) of a GGX lobe, and a rough dielectric\'s mean Fresnel: written\n'
        f"by `python -m core.kernels.ggx_albedo_table` (midpoint grids of {steps} x {steps} and\n"
        f'{steps // 3} x {steps // 3}); do not edit."""\n\n'
        f"TABLE_SIZE = {TABLE_SIZE}\n"
        f"DIELECTRIC_SIZE = {DIELECTRIC_SIZE}\n"
        "# E: rows roughness 0..1, columns mu 0..1\n"
        f'ALBEDO = """\n{_lines(table)}\n"""\n'
        f'ALBEDO_AVERAGE = """\n{_lines(average)}\n"""\n'
        "# F_mean: roughness 0..1, mu 0..1, z = sqrt((ior - 1) / (ior + 1)) 0..1, z fastest\n"
        f'DIELECTRIC_FRESNEL = """\n{_lines(dielectric)}\n"""\n'
    )


if __name__ == "__main__":
    write_values(steps=int(sys.argv[1]) if len(sys.argv) > 1 else 384)

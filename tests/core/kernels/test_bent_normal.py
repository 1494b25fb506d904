"""A bent shading normal kept from reflecting below the surface (core.kernels.bent_normal),
checked by the property that defines it: where the mirror direction about the bent normal
rises at least t = min(0.9 I.Ng, 0.01) above the surface, the normal is kept; elsewhere the
new normal lies between the old one and the geometric normal, in their plane, and the
mirror direction about it rises exactly t."""

import numpy as np

from core.kernels.bent_normal import kept_above


def _unit(v):
    return v / np.linalg.norm(v)


def _height(n, wi, ng):
    r = 2.0 * np.dot(n, wi) * n - wi
    return np.dot(r, ng)


def test_a_bent_normal_is_kept_or_lifted_just_enough():
    rng = np.random.default_rng(61)
    lifted = kept = 0
    for _ in range(4000):
        ng = _unit(rng.normal(size=3))
        n = _unit(ng + rng.normal(scale=0.8, size=3))
        if np.dot(n, ng) <= 0.05:
            continue  # a bent normal stays on its surface's side
        wi = _unit(rng.normal(size=3))
        side = -1.0 if np.dot(wi, ng) < 0.0 else 1.0  # seen from the back: both turn
        if abs(np.dot(wi, ng)) < 1e-3:
            continue
        got = np.array(kept_above(tuple(ng), tuple(-wi), tuple(n)))
        viewer_ng, viewer_n, viewer_got = side * ng, side * n, side * got
        t = min(0.9 * np.dot(wi, viewer_ng), 0.01)
        if _height(viewer_n, wi, viewer_ng) >= t:
            np.testing.assert_array_equal(got, n)
            kept += 1
            continue
        lifted += 1
        assert abs(np.linalg.norm(got) - 1.0) < 1e-12
        assert abs(_height(viewer_got, wi, viewer_ng) - t) < 1e-9
        # in the plane of the geometric normal and the old one, tilted towards the first
        assert abs(np.dot(np.cross(ng, n), got)) < 1e-9
        assert np.dot(viewer_got, viewer_ng) > np.dot(viewer_n, viewer_ng)
    assert lifted > 200 and kept > 200  # the premise: both cases met often

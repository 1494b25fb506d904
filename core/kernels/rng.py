"""Counter-based random numbers: a hash of (seed, pixel, sample, purpose, index).

No generator state is carried from one pixel to the next, so every random number depends
only on where it is used. The same image comes out whatever the tile size, thread count or
render border, and a farm can render a frame in pieces and stitch them.
The hash is splitmix64's finalizer (Steele, Lea and Flood 2014), applied along the key.
"""

import numpy as np

from ..jit.decorators import kernel

PURPOSE_PIXEL = 1  # where in the pixel a camera ray passes
PURPOSE_LENS = 2  # where on the lens it starts
PURPOSE_LIGHT = 3  # where on an area light a shadow ray ends
PURPOSE_LIGHT_SHIFT = 4  # the random shift of a shading point's Halton points
PURPOSE_GLOSSY = 5  # the microfacet normal a rough surface's ray leaves by
PURPOSE_PHOTON = 6  # a caustic photon: where it starts, its light sample, its branches
PURPOSE_CLEAR_COAT = 7  # the microfacet normal a rough clear coat's ray leaves by

_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_S30 = np.uint64(30)
_S27 = np.uint64(27)
_S31 = np.uint64(31)
_S11 = np.uint64(11)
_UNIT = 1.0 / 9007199254740992.0  # 2^-53


@kernel
def mix(z):
    z = (z ^ (z >> _S30)) * _M1
    z = (z ^ (z >> _S27)) * _M2
    return z ^ (z >> _S31)


@kernel
def chain(key, value):
    """A new key from `key` and an integer."""
    return mix(key + _GOLDEN + np.uint64(value))


@kernel
def sample_key(seed, px, py, sample):
    """The key of one camera sample of one pixel."""
    return chain(chain(chain(chain(np.uint64(0), seed), px), py), sample)


@kernel
def uniform2(key, purpose, a, b):
    """Two independent uniform numbers in [0, 1) for (purpose, a, b) under `key`."""
    h = chain(chain(chain(key, purpose), a), b)
    return float(h >> _S11) * _UNIT, float(mix(h + _GOLDEN) >> _S11) * _UNIT


_ODD = np.uint64(0x2545F4914F6CDD1D)


@kernel
def permuted(index, count, key):
    """Where `index` goes in a random permutation of 0..count-1 chosen by `key`: a bijection
    of the next power of two (xor, odd multiply and xor-shift, each invertible modulo
    2^k), walked until it lands below count (Black's cycle walking)."""
    mask = np.uint64(1)
    while mask < np.uint64(count):
        mask = mask << np.uint64(1)
    mask = mask - np.uint64(1)
    i = np.uint64(index)
    salt = mix(np.uint64(key))
    while True:
        for round_ in range(3):
            i = (i ^ (salt >> np.uint64(7 * round_))) & mask
            i = (i * _ODD) & mask
            i = i ^ ((i & mask) >> np.uint64(3))
        if i < np.uint64(count):
            return int(i)

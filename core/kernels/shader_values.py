"""The value nodes of a shader program, each as Blender's Cycles computes it: Math, Mix
Color, Invert, Gamma, Bright/Contrast, Hue/Saturation/Value, RGB to BW, Color Ramp,
Mapping, and the Checker and Gradient textures. Colours and vectors are triples."""

import math

import numpy as np

from ..jit.decorators import kernel
from .vec import add, scale, sub

# Math node operations (core.model.shader.MATH_OPERATIONS, in that order)
(M_ADD, M_SUBTRACT, M_MULTIPLY, M_DIVIDE, M_MULTIPLY_ADD, M_POWER, M_MINIMUM, M_MAXIMUM,
 M_LESS_THAN, M_GREATER_THAN, M_ABSOLUTE, M_SQRT, M_FLOOR, M_CEIL, M_FRACT, M_MODULO, M_SINE,
 M_COSINE, M_SNAP, M_ROUND, M_SIGN, M_EXPONENT, M_LOGARITHM, M_PINGPONG, M_WRAP,
 M_SMOOTH_MIN, M_SMOOTH_MAX, M_COMPARE, M_TRUNC, M_INVERSE_SQRT, M_FLOORED_MODULO,
 M_TANGENT, M_ARCSINE, M_ARCCOSINE, M_ARCTANGENT, M_ARCTAN2, M_SINH, M_COSH, M_TANH,
 M_RADIANS, M_DEGREES) = range(41)  # fmt: skip
# Mix Color blend types (core.model.shader.MIX_BLENDS)
(B_MIX, B_ADD, B_MULTIPLY, B_SUBTRACT, B_SCREEN, B_DIVIDE, B_DIFFERENCE, B_DARKEN, B_LIGHTEN,
 B_OVERLAY, B_EXCLUSION, B_BURN, B_DODGE, B_HUE, B_SATURATION, B_VALUE, B_COLOR, B_SOFT_LIGHT,
 B_LINEAR_LIGHT) = range(19)  # fmt: skip
# Gradient texture types (core.model.shader.GRADIENT_TYPES)
(G_LINEAR, G_QUADRATIC, G_EASING, G_DIAGONAL, G_RADIAL, G_QUADRATIC_SPHERE,
 G_SPHERICAL) = range(7)  # fmt: skip
# Mapping types (core.model.shader.MAPPING_TYPES)
MAP_POINT, MAP_TEXTURE, MAP_VECTOR, MAP_NORMAL = range(4)
# Color Ramp interpolations (core.model.shader.RAMP_INTERPOLATIONS)
RAMP_LINEAR, RAMP_CONSTANT, RAMP_EASE = 0, 1, 2

# Blender's scene-linear luminance weights (Rec. 709), for RGB to BW and colour -> value
LUMA = (0.2126, 0.7152, 0.0722)


@kernel
def luminance(c):
    return LUMA[0] * c[0] + LUMA[1] * c[1] + LUMA[2] * c[2]


@kernel
def _wrap(value, high, low):
    span = high - low
    return value - span * np.floor((value - low) / span) if span != 0.0 else low


@kernel
def _smooth_min(a, b, k):
    if k == 0.0:
        return min(a, b)
    h = max(k - abs(a - b), 0.0) / k
    return min(a, b) - h * h * h * k / 6.0


@kernel
def math_node(op, a, b, c):
    """The Math node's operation on a, b (and c), with Cycles' safe variants."""
    if op == M_ADD:
        return a + b
    if op == M_SUBTRACT:
        return a - b
    if op == M_MULTIPLY:
        return a * b
    if op == M_DIVIDE:
        return a / b if b != 0.0 else 0.0
    if op == M_MULTIPLY_ADD:
        return a * b + c
    if op == M_POWER:
        if a >= 0.0:
            return a**b if (a != 0.0 or b > 0.0) else (1.0 if b == 0.0 else 0.0)
        return a**b if b == np.floor(b) else 0.0
    if op == M_MINIMUM:
        return min(a, b)
    if op == M_MAXIMUM:
        return max(a, b)
    if op == M_LESS_THAN:
        return 1.0 if a < b else 0.0
    if op == M_GREATER_THAN:
        return 1.0 if a > b else 0.0
    if op == M_ABSOLUTE:
        return abs(a)
    if op == M_SQRT:
        return math.sqrt(a) if a > 0.0 else 0.0
    if op == M_FLOOR:
        return np.floor(a)
    if op == M_CEIL:
        return np.ceil(a)
    if op == M_FRACT:
        return a - np.floor(a)
    if op == M_MODULO:
        return a - b * np.trunc(a / b) if b != 0.0 else 0.0  # C's fmod
    if op == M_SINE:
        return math.sin(a)
    if op == M_COSINE:
        return math.cos(a)
    if op == M_SNAP:
        return np.floor(a / b) * b if b != 0.0 else 0.0
    if op == M_ROUND:
        return np.floor(a + 0.5)
    if op == M_SIGN:
        return 1.0 if a > 0.0 else (-1.0 if a < 0.0 else 0.0)
    if op == M_EXPONENT:
        return math.exp(min(a, 700.0))
    if op == M_LOGARITHM:
        return math.log(a) / math.log(b) if a > 0.0 and b > 0.0 and b != 1.0 else 0.0
    if op == M_PINGPONG:
        if b == 0.0:
            return 0.0
        return abs((a - b) - 2.0 * b * np.floor((a - b) / (2.0 * b)) - b)
    if op == M_WRAP:
        return _wrap(a, b, c)
    if op == M_SMOOTH_MIN:
        return _smooth_min(a, b, c)
    if op == M_SMOOTH_MAX:
        return -_smooth_min(-a, -b, c)
    if op == M_COMPARE:
        return 1.0 if abs(a - b) <= max(c, 1e-5) else 0.0
    if op == M_TRUNC:
        return np.trunc(a)
    return _more_math(op, a, b)


@kernel
def _more_math(op, a, b):
    """The Math node's less common operations, as Cycles' safe variants."""
    if op == M_INVERSE_SQRT:
        return 1.0 / math.sqrt(a) if a > 0.0 else 0.0
    if op == M_FLOORED_MODULO:
        return a - np.floor(a / b) * b if b != 0.0 else 0.0
    if op == M_TANGENT:
        return math.tan(a)
    if op == M_ARCSINE:
        return math.asin(min(max(a, -1.0), 1.0))
    if op == M_ARCCOSINE:
        return math.acos(min(max(a, -1.0), 1.0))
    if op == M_ARCTANGENT:
        return math.atan(a)
    if op == M_ARCTAN2:
        return math.atan2(a, b)
    if op == M_SINH:
        return math.sinh(min(max(a, -700.0), 700.0))
    if op == M_COSH:
        return math.cosh(min(max(a, -700.0), 700.0))
    if op == M_TANH:
        return math.tanh(a)
    if op == M_RADIANS:
        return a * (math.pi / 180.0)
    if op == M_DEGREES:
        return a * (180.0 / math.pi)
    return 0.0


@kernel
def _lerp(a, b, t):
    return add(scale(a, 1.0 - t), scale(b, t))


@kernel
def mix_colour(blend, t, c1, c2):
    """Mix Color (MixRGB) of blend type `blend`, factor t, as Cycles' svm_mix."""
    if blend == B_ADD:
        return _lerp(c1, add(c1, c2), t)
    if blend == B_MULTIPLY:
        return _lerp(c1, (c1[0] * c2[0], c1[1] * c2[1], c1[2] * c2[2]), t)
    if blend == B_SUBTRACT:
        return _lerp(c1, sub(c1, c2), t)
    if blend == B_SCREEN:
        tm = 1.0 - t
        return (
            1.0 - (tm + t * (1.0 - c2[0])) * (1.0 - c1[0]),
            1.0 - (tm + t * (1.0 - c2[1])) * (1.0 - c1[1]),
            1.0 - (tm + t * (1.0 - c2[2])) * (1.0 - c1[2]),
        )
    if blend == B_DIVIDE:
        tm = 1.0 - t
        return (
            tm * c1[0] + t * c1[0] / c2[0] if c2[0] != 0.0 else c1[0],
            tm * c1[1] + t * c1[1] / c2[1] if c2[1] != 0.0 else c1[1],
            tm * c1[2] + t * c1[2] / c2[2] if c2[2] != 0.0 else c1[2],
        )
    if blend == B_DIFFERENCE:
        return _lerp(c1, (abs(c1[0] - c2[0]), abs(c1[1] - c2[1]), abs(c1[2] - c2[2])), t)
    if blend == B_DARKEN:
        return _lerp(c1, (min(c1[0], c2[0]), min(c1[1], c2[1]), min(c1[2], c2[2])), t)
    if blend == B_LIGHTEN:
        return _lerp(c1, (max(c1[0], c2[0]), max(c1[1], c2[1]), max(c1[2], c2[2])), t)
    if blend == B_OVERLAY:
        return (_overlay(t, c1[0], c2[0]), _overlay(t, c1[1], c2[1]), _overlay(t, c1[2], c2[2]))
    if blend == B_EXCLUSION:
        e = _lerp(c1, (c1[0] + c2[0] - 2.0 * c1[0] * c2[0], c1[1] + c2[1] - 2.0 * c1[1] * c2[1],
                       c1[2] + c2[2] - 2.0 * c1[2] * c2[2]), t)  # fmt: skip
        return (max(e[0], 0.0), max(e[1], 0.0), max(e[2], 0.0))
    if blend >= B_BURN:
        return _mix_more(blend, t, c1, c2)
    return _lerp(c1, c2, t)


@kernel
def _burn(t, a, b):
    """Color Burn of one channel: 1 - (1 - a) / (1 - t + t b), within 0..1."""
    below = 1.0 - t + t * b
    if below <= 0.0:
        return 0.0
    return min(max(1.0 - (1.0 - a) / below, 0.0), 1.0)


@kernel
def _dodge(t, a, b):
    """Color Dodge of one channel: a / (1 - t b), at most 1 (0 stays 0)."""
    if a == 0.0:
        return a
    below = 1.0 - t * b
    if below <= 0.0:
        return 1.0
    return min(a / below, 1.0)


@kernel
def _soft(t, a, b):
    """Soft Light of one channel: towards (1 - a) b a + a screen(a, b)."""
    screen = 1.0 - (1.0 - b) * (1.0 - a)
    return (1.0 - t) * a + t * ((1.0 - a) * b * a + a * screen)


@kernel
def _mix_more(blend, t, c1, c2):
    """Mix Color's Burn, Dodge, the HSV blends (Hue, Saturation, Value, Color), Soft Light
    and Linear Light, as Blender defines them (Cycles' svm_mix)."""
    if blend == B_BURN:
        return _burn(t, c1[0], c2[0]), _burn(t, c1[1], c2[1]), _burn(t, c1[2], c2[2])
    if blend == B_DODGE:
        return _dodge(t, c1[0], c2[0]), _dodge(t, c1[1], c2[1]), _dodge(t, c1[2], c2[2])
    if blend == B_SOFT_LIGHT:
        return _soft(t, c1[0], c2[0]), _soft(t, c1[1], c2[1]), _soft(t, c1[2], c2[2])
    if blend == B_LINEAR_LIGHT:
        return add(c1, scale((2.0 * c2[0] - 1.0, 2.0 * c2[1] - 1.0, 2.0 * c2[2] - 1.0), t))
    # the HSV blends: take B's hue (Hue), hue and saturation (Color), or blend saturation
    # (Saturation) or value (Value) towards B's
    h1, s1, v1 = _rgb_to_hsv(c1)
    h2, s2, v2 = _rgb_to_hsv(c2)
    if blend == B_VALUE:
        return _hsv_to_rgb(h1, s1, (1.0 - t) * v1 + t * v2)
    if blend == B_SATURATION:
        if s1 == 0.0:
            return c1
        return _hsv_to_rgb(h1, (1.0 - t) * s1 + t * s2, v1)
    if s2 == 0.0:  # Hue and Color of a grey B change nothing
        return c1
    if blend == B_HUE:
        return _lerp(c1, _hsv_to_rgb(h2, s1, v1), t)
    return _lerp(c1, _hsv_to_rgb(h2, s2, v1), t)  # B_COLOR


@kernel
def _overlay(t, a, b):
    tm = 1.0 - t
    if a < 0.5:
        return a * (tm + 2.0 * t * b)
    return 1.0 - (tm + 2.0 * t * (1.0 - b)) * (1.0 - a)


@kernel
def clamp01(c):
    return (min(max(c[0], 0.0), 1.0), min(max(c[1], 0.0), 1.0), min(max(c[2], 0.0), 1.0))


@kernel
def invert(fac, c):
    return _lerp(c, (1.0 - c[0], 1.0 - c[1], 1.0 - c[2]), fac)


@kernel
def gamma(c, g):
    return (
        c[0] ** g if c[0] > 0.0 else c[0],
        c[1] ** g if c[1] > 0.0 else c[1],
        c[2] ** g if c[2] > 0.0 else c[2],
    )


@kernel
def bright_contrast(c, bright, contrast):
    a = 1.0 + contrast
    b = bright - contrast * 0.5
    return (max(a * c[0] + b, 0.0), max(a * c[1] + b, 0.0), max(a * c[2] + b, 0.0))


@kernel
def _rgb_to_hsv(c):
    r, g, b = c
    top = max(r, g, b)
    bottom = min(r, g, b)
    delta = top - bottom
    v = top
    if top == 0.0 or delta == 0.0:
        return 0.0, 0.0, v
    s = delta / top
    if r == top:
        h = (g - b) / delta
    elif g == top:
        h = 2.0 + (b - r) / delta
    else:
        h = 4.0 + (r - g) / delta
    h /= 6.0
    if h < 0.0:
        h += 1.0
    return h, s, v


@kernel
def _hsv_to_rgb(h, s, v):
    if s == 0.0:
        return v, v, v
    if h == 1.0:
        h = 0.0
    h *= 6.0
    i = np.floor(h)
    f = h - i
    p = v * (1.0 - s)
    q = v * (1.0 - s * f)
    t = v * (1.0 - s * (1.0 - f))
    if i == 0.0:
        return v, t, p
    if i == 1.0:
        return q, v, p
    if i == 2.0:
        return p, v, t
    if i == 3.0:
        return p, q, v
    if i == 4.0:
        return t, p, v
    return v, p, q


@kernel
def hue_saturation_value(hue, saturation, value, fac, c):
    h, s, v = _rgb_to_hsv(c)
    h = h + hue + 0.5
    h -= math.floor(h)
    s = min(max(s * saturation, 0.0), 1.0)
    v *= value
    out = _hsv_to_rgb(h, s, v)
    mixed = _lerp(c, out, fac)
    return (max(mixed[0], 0.0), max(mixed[1], 0.0), max(mixed[2], 0.0))


@kernel
def colour_ramp(stack, first, count, interpolation, t):
    """(RGB, alpha) of a Color Ramp whose `count` stops sit in the stack from `first`, five
    numbers each (position, R, G, B, A), in increasing position."""
    if t <= stack[first] or count == 1:
        k = first
        return (stack[k + 1], stack[k + 2], stack[k + 3]), stack[k + 4]
    last = first + 5 * (count - 1)
    if t >= stack[last]:
        return (stack[last + 1], stack[last + 2], stack[last + 3]), stack[last + 4]
    k = first
    while stack[k + 5] < t:
        k += 5
    if interpolation == RAMP_CONSTANT:
        return (stack[k + 1], stack[k + 2], stack[k + 3]), stack[k + 4]
    span = stack[k + 5] - stack[k]
    f = (t - stack[k]) / span if span > 0.0 else 0.0
    if interpolation == RAMP_EASE:
        f = f * f * (3.0 - 2.0 * f)
    rgba = (
        stack[k + 1] * (1.0 - f) + stack[k + 6] * f,
        stack[k + 2] * (1.0 - f) + stack[k + 7] * f,
        stack[k + 3] * (1.0 - f) + stack[k + 8] * f,
    )
    return rgba, stack[k + 4] * (1.0 - f) + stack[k + 9] * f


@kernel
def _curve(stack, first, rows, channel, x):
    """One channel of an RGB Curves table (see rgb_curves) at x, as Cycles' ramp lookup:
    linear between rows; beyond them along the end rows' slope (Extend: Extrapolated), or
    the end row (Extend: Horizontal)."""
    low, high, extrapolate = stack[first], stack[first + 1], stack[first + 2] != 0.0
    table = first + 3
    f = (x - low) / (high - low)
    last = rows - 1
    if not extrapolate:
        f = min(max(f, 0.0), 1.0)
    if f < 0.0:
        start = stack[table + channel]
        return start + (start - stack[table + 3 + channel]) * (-f) * last
    if f > 1.0:
        end = stack[table + 3 * last + channel]
        return end + (end - stack[table + 3 * (last - 1) + channel]) * (f - 1.0) * last
    position = f * last
    i = min(int(position), last - 1)
    t = position - i
    a = stack[table + 3 * i + channel]
    return a + (stack[table + 3 * (i + 1) + channel] - a) * t


@kernel
def rgb_curves(stack, first, rows, c):
    """RGB Curves' colour for c: each channel through its baked curve, whose table of `rows`
    RGB rows follows x's range (two numbers) and 1 to extrapolate in the stack from
    `first`."""
    return (_curve(stack, first, rows, 0, c[0]), _curve(stack, first, rows, 1, c[1]),
            _curve(stack, first, rows, 2, c[2]))  # fmt: skip


@kernel
def magic(p, depth, distortion):
    """The Magic texture's colour at p (already scaled): three waves of p's coordinates'
    sums, each then bent by the others `depth` times (0..10), Blender's formula."""
    x = math.sin((p[0] + p[1] + p[2]) * 5.0)
    y = math.cos((-p[0] + p[1] - p[2]) * 5.0)
    z = -math.cos((-p[0] - p[1] + p[2]) * 5.0)
    if depth > 0:
        x, y, z = x * distortion, y * distortion, z * distortion
        y = -math.cos(x - y + z) * distortion
    if depth > 1:
        x = math.cos(x - y - z) * distortion
    if depth > 2:
        z = math.sin(-x - y - z) * distortion
    if depth > 3:
        x = -math.cos(-x + y - z) * distortion
    if depth > 4:
        y = -math.sin(-x + y + z) * distortion
    if depth > 5:
        y = -math.cos(-x + y + z) * distortion
    if depth > 6:
        x = math.cos(x + y + z) * distortion
    if depth > 7:
        z = math.sin(x + y - z) * distortion
    if depth > 8:
        x = -math.cos(-x - y + z) * distortion
    if depth > 9:
        y = -math.sin(x - y + z) * distortion
    if distortion != 0.0:
        x, y, z = x / (2.0 * distortion), y / (2.0 * distortion), z / (2.0 * distortion)
    return 0.5 - x, 0.5 - y, 0.5 - z


@kernel
def _euler_rows(r):
    """Rows of Blender's XYZ Euler rotation matrix (X first, then Y, then Z)."""
    cx, cy, cz = math.cos(r[0]), math.cos(r[1]), math.cos(r[2])
    sx, sy, sz = math.sin(r[0]), math.sin(r[1]), math.sin(r[2])
    return (
        (cy * cz, sx * sy * cz - cx * sz, cx * sy * cz + sx * sz),
        (cy * sz, sx * sy * sz + cx * cz, cx * sy * sz - sx * cz),
        (-sy, sx * cy, cx * cy),
    )


@kernel
def _rows_times(m, v):
    return (
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    )


@kernel
def _columns_times(m, v):
    return (
        m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2],
        m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
        m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2],
    )


@kernel
def _safe_divide(a, b):
    return (
        a[0] / b[0] if b[0] != 0.0 else 0.0,
        a[1] / b[1] if b[1] != 0.0 else 0.0,
        a[2] / b[2] if b[2] != 0.0 else 0.0,
    )


@kernel
def mapping(kind, v, location, rotation, size):
    """The Mapping node of type `kind` (MAP_*), as Cycles' svm_mapping."""
    rows = _euler_rows(rotation)
    if kind == MAP_POINT:
        return add(_rows_times(rows, (v[0] * size[0], v[1] * size[1], v[2] * size[2])), location)
    if kind == MAP_TEXTURE:
        return _safe_divide(_columns_times(rows, sub(v, location)), size)
    if kind == MAP_VECTOR:
        return _rows_times(rows, (v[0] * size[0], v[1] * size[1], v[2] * size[2]))
    n = _rows_times(rows, _safe_divide(v, size))
    length = math.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
    return scale(n, 1.0 / length) if length > 0.0 else (0.0, 0.0, 0.0)


@kernel
def checker(p, scale_):
    """The Checker texture's factor at p (1: Color1's squares), as Cycles' svm_checker."""
    x = (p[0] * scale_ + 0.000001) * 0.999999
    y = (p[1] * scale_ + 0.000001) * 0.999999
    z = (p[2] * scale_ + 0.000001) * 0.999999
    xi = abs(int(math.floor(x)))
    yi = abs(int(math.floor(y)))
    zi = abs(int(math.floor(z)))
    return 1.0 if ((xi % 2 == yi % 2) == (zi % 2 == 1)) else 0.0


@kernel
def _brick_noise(n):
    """Cycles' brick_noise: integer hashing in 32-bit unsigned arithmetic (each product
    reduced mod 2^32, which int64 holds: the factors stay below 2^32 and 2^31), the result
    a float32 in [0, 1)."""
    low32, low31 = 0xFFFFFFFF, 0x7FFFFFFF
    n = (n + 1013) & low31
    n = (n >> 13) ^ n
    inner = (((n * n) & low32) * 60493 + 19990303) & low32
    nn = ((n * inner) & low32) + 1376312589
    nn &= low31
    return 0.5 * float(np.float32(nn)) / 1073741824.0


@kernel
def brick(p, mortar_size, mortar_smooth, bias, brick_width, row_height, offset_amount,
          offset_frequency, squash_amount, squash_frequency):  # fmt: skip
    """The Brick texture at p (already scaled): (tint, mortar) as Cycles' svm_brick. The
    row and brick numbers hash (row << 16) + (brick & 0xFFFF) as 32 bits, as Cycles' int
    arithmetic wraps."""
    rownum = int(math.floor(p[1] / row_height))
    offset = 0.0
    if offset_frequency != 0 and squash_frequency != 0:
        if rownum % squash_frequency == 0:
            brick_width *= squash_amount
        if rownum % offset_frequency == 0:
            offset = brick_width * offset_amount
    bricknum = int(math.floor((p[0] + offset) / brick_width))
    x = (p[0] + offset) - brick_width * bricknum
    y = p[1] - row_height * rownum
    hashed = ((rownum << 16) + (bricknum & 0xFFFF)) & 0xFFFFFFFF
    tint = min(max(_brick_noise(hashed) + bias, 0.0), 1.0)
    min_dist = min(min(x, y), min(brick_width - x, row_height - y))
    if min_dist >= mortar_size:
        mortar = 0.0
    elif mortar_smooth == 0.0:
        mortar = 1.0
    else:
        f = (1.0 - min_dist / mortar_size) / mortar_smooth
        if f <= 0.0:
            mortar = 0.0
        elif f >= 1.0:
            mortar = 1.0
        else:
            mortar = 3.0 * f * f - 2.0 * f * f * f
    return tint, mortar


@kernel
def gradient(kind, p):
    """The Gradient texture's factor at p, clamped to [0, 1], as Cycles' svm_gradient."""
    x, y, z = p
    if kind == G_LINEAR:
        f = x
    elif kind == G_QUADRATIC:
        r = max(x, 0.0)
        f = r * r
    elif kind == G_EASING:
        r = min(max(x, 0.0), 1.0)
        f = 3.0 * r * r - 2.0 * r * r * r
    elif kind == G_DIAGONAL:
        f = (x + y) * 0.5
    elif kind == G_RADIAL:
        f = math.atan2(y, x) / (2.0 * math.pi) + 0.5
    else:
        r = max(0.999999 - math.sqrt(x * x + y * y + z * z), 0.0)
        f = r * r if kind == G_QUADRATIC_SPHERE else r
    return min(max(f, 0.0), 1.0)

"""A plain-Python oracle for the report's lighting model, written apart from the kernels.

Spheres are intersected in world space as quadrics (x^T Q x = 0 with Q = T^-T diag(1,1,1,-1)
T^-1), not in object space as the kernels do, and nothing here is shared with `core`'s
kernels. Slow (one ray at a time), so tests use it for a handful of pixels.
"""

import math

import numpy as np


def sphere_quadric(world_from_object):
    inverse = np.linalg.inv(np.asarray(world_from_object, float))
    return inverse.T @ np.diag([1.0, 1.0, 1.0, -1.0]) @ inverse


def intersect_quadric(Q, origin, direction):
    """Both roots t (sorted) of (o + t d, 1)^T Q (o + t d, 1) = 0, or None."""
    o = np.append(origin, 1.0)
    d = np.append(direction, 0.0)
    a, b, c = d @ Q @ d, 2.0 * (o @ Q @ d), o @ Q @ o
    discriminant = b * b - 4 * a * c
    if discriminant < 0:
        return None
    root = math.sqrt(discriminant)
    return sorted(((-b - root) / (2 * a), (-b + root) / (2 * a)))


def quadric_normal(Q, point):
    gradient = (Q @ np.append(point, 1.0))[:3]
    return gradient / np.linalg.norm(gradient)


def nearest(spheres, origin, direction, t_max=math.inf, t_min=1e-7):
    """(index, t) of the nearest sphere hit with t_min < t < t_max, or (None, inf)."""
    best, best_t = None, t_max
    for i, sphere in enumerate(spheres):
        roots = intersect_quadric(sphere["Q"], origin, direction)
        for t in roots or ():
            if t_min < t < best_t:
                best, best_t = i, t
    return best, best_t


def camera_ray(eye, view, up, fovy_degrees, width, height, px, py):
    forward = np.asarray(view, float) / np.linalg.norm(view)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, forward)
    half_h = math.tan(math.radians(fovy_degrees) / 2)
    half_w = half_h * width / height
    sx = (2 * (px + 0.5) / width - 1) * half_w
    sy = (1 - 2 * (py + 0.5) / height) * half_h
    d = forward + sx * right + sy * true_up
    return np.asarray(eye, float), d / np.linalg.norm(d)


def orthographic_camera_ray(eye, view, up, view_height, width, height, px, py, shift=(0, 0)):
    """The ray of pixel (px, py)'s centre for an orthographic camera whose image is
    view_height scene units tall: parallel to the view, from the plane through the eye.
    `shift` moves the image by half-widths and half-heights."""
    forward = np.asarray(view, float) / np.linalg.norm(view)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, forward)
    half_h = view_height / 2
    half_w = half_h * width / height
    sx = (2 * (px + 0.5) / width - 1 + shift[0]) * half_w
    sy = (1 - 2 * (py + 0.5) / height + shift[1]) * half_h
    return np.asarray(eye, float) + sx * right + sy * true_up, forward


def shade_ray(spheres, lights, ambient, background, origin, direction):
    """Colour along a ray: ambient + per unshadowed light kd(N.L) + ks(R.V)^p, attenuated."""
    index, t = nearest(spheres, origin, direction)
    if index is None:
        return np.asarray(background, float)
    sphere = spheres[index]
    point = origin + t * direction
    normal = quadric_normal(sphere["Q"], point)
    if normal @ direction > 0:
        normal = -normal
    kd, ks, p = (np.asarray(sphere[k], float) for k in ("kd", "ks", "p"))
    colour = kd * np.asarray(ambient, float)
    for light in lights:
        to_light = np.asarray(light["position"], float) - point
        distance = np.linalg.norm(to_light)
        light_dir = to_light / distance
        n_dot_l = normal @ light_dir
        if n_dot_l <= 0:
            continue
        start = point + normal * 1e-7 * max(1.0, np.abs(point).max())
        if nearest(spheres, start, light_dir, t_max=distance)[0] is not None:
            continue
        c0, c1, c2 = light["attenuation"]
        reflected = 2 * n_dot_l * normal - light_dir
        specular = max(0.0, reflected @ -direction) ** p
        colour = colour + (kd * n_dot_l + ks * specular) * np.asarray(light["intensity"]) / (
            c0 + c1 * distance + c2 * distance**2
        )
    return colour

"""Add-on export benchmark (Blender 5.0 bpy module): a million-triangle mesh into core.

Prints export_1m_tris_s (foreach_get of vertices, triangles, smooth flags, corner normals and
UVs into a TriangleMesh) and export_unchanged_1m_tris_s (the next frame's check that finds it
unchanged and reuses it). Best of 3.
"""

import time

import bpy

from blender_addon.export.mesh import MeshCache, triangle_mesh


def best_of(runs, f):
    best = float("inf")
    for _ in range(runs):
        start = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - start)
    return best


def main():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    # 708 x 708 vertices: 707^2 quads, 999,698 triangles
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=707, y_subdivisions=707)
    bpy.ops.object.shade_smooth()
    mesh = bpy.context.active_object.data
    converted = triangle_mesh(mesh, "grid")
    print(f"triangles: {len(converted.triangles)}")
    print(f"export_1m_tris_s: {best_of(3, lambda: triangle_mesh(mesh, 'grid')):.3f}")
    cache = MeshCache()
    cache.get("grid", mesh, "grid")
    print(f"export_unchanged_1m_tris_s: {best_of(3, lambda: cache.get('grid', mesh, 'grid')):.3f}")


if __name__ == "__main__":
    main()

"""What the tests share, in one place: reference implementations (`reference_tracer`,
`reference_shapes`), scenes and meshes (`scenes`, `meshes`, `csg_examples`, `fuzz_scenes`),
ray sets (`rays`), single-ray probes of the kernels (`probe`, `cache_probe`), running
Debian's Blender 3.4 (`blender34`), a .blend's expected pixels computed without the add-on
(`blender_reference`) and what a render of a .blend exports (`render_view`). Test modules
import from here, never from each other."""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]  # the checkout

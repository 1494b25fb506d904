"""File › Import › CS488 Lua scene: the report's scene scripts as Blender data.

`importer` runs a script (in a child process, with limits) and places what its gr.render
calls describe; `build` turns each call's node graph into objects through the shared
`blender_data` builder.
"""

from . import importer


def register():
    importer.register()


def unregister():
    importer.unregister()

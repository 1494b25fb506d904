"""The one error type that bad scene input raises."""


class SceneError(ValueError):
    """A scene, object or setting that Whitted cannot render as given.

    The message names the object (by kind and name) and the field, says what was found and
    what would be valid, so that a Blender user or a Lua script author can fix it without
    reading our code.
    """

    def __init__(self, owner: str, field: str, problem: str):
        self.owner = owner
        self.field = field
        self.problem = problem
        super().__init__(f"{owner}: {field}: {problem}")

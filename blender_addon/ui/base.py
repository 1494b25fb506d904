"""What every Whitted panel shares: shown only while Whitted is the render engine, and only
when the data it edits is there."""

from ..engine import WhittedRenderEngine

ENGINE = WhittedRenderEngine.bl_idname


class WhittedPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    COMPAT_ENGINES = {ENGINE}
    # The context member (e.g. "material") the panel edits; it shows only when there is one
    context_member = None

    @classmethod
    def poll(cls, context):
        if context.engine not in cls.COMPAT_ENGINES:
            return False
        return cls.context_member is None or getattr(context, cls.context_member, None) is not None

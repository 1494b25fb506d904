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


def draw_warnings(layout, context, warnings: list[str]) -> None:
    """Each warning under an ERROR icon, wrapped to the panel's width (a label is cut, not
    wrapped), without its leading 'light 'X': ' (the panel is the light's own)."""
    width = getattr(context.region, "width", 300)
    # (A scale of 0 is what Blender without a window reports)
    scale = context.preferences.system.ui_scale or 1.0
    per_line = max(24, int(width / (7.0 * scale)) - 6)
    for warning in warnings:
        words = warning.split(": ", 1)[-1].split()
        lines, line = [], ""
        for word in words:
            if line and len(line) + 1 + len(word) > per_line:
                lines.append(line)
                line = word
            else:
                line = f"{line} {word}".strip()
        lines.append(line)
        column = layout.column(align=True)
        for number, text in enumerate(lines):
            column.label(text=text, icon="ERROR" if number == 0 else "BLANK1")

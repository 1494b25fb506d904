"""A material's preview thumbnail as RGB rows, for the window scripts that run in Blender
(tests/blender/scripts/window_preview*.py)."""


def rgb_rows(preview) -> list:
    """The preview's pixels as displayed, RGB rows with row 0 at the top (Blender's rows run
    bottom-up)."""
    width, height = preview.image_size
    values = preview.image_pixels_float[:]
    rows = [[values[4 * (y * width + x) : 4 * (y * width + x) + 3] for x in range(width)]
            for y in range(height)]  # fmt: skip
    return rows[::-1]

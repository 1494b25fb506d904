"""Whitted's extension of gr.render: an options table after the report's arguments, and the
command line's options of the same names. Without either, a script renders the report's
picture bit for bit.

    gr.render(node, 'out.png', 500, 500, eye, view, up, 50, ambient, lights,
              {caustics = 'both', photons = 400000, glass_shadows = 'blocked'})

caustics       -- 'none' (the report's), 'reflective' (light off mirrors), 'refractive'
                  (light through glass) or 'both'; true means 'both', false 'none'
photons        -- caustic photons traced, or 'auto' (the default): as many as the
                  caustics in the frame need (core.model.settings' limit)
glass_shadows  -- 'attenuated' (the report's pale shadow through glass) or 'blocked' (a
                  full shadow, the light behind glass coming as caustics); by default
                  'blocked' where refractive caustics are asked for, else 'attenuated'
"""

from __future__ import annotations

from dataclasses import dataclass

from ..model.settings import AUTO_PHOTONS, DEFAULT_CAUSTIC_PHOTONS, MAX_CAUSTIC_PHOTONS
from ..vocabulary import GLASS_SHADOWS
from .sandbox import ArgumentError

CAUSTICS = {
    "none": (),
    "reflective": ("reflective",),
    "refractive": ("refractive",),
    "both": ("reflective", "refractive"),
}
OPTION_NAMES = ("caustics", "photons", "glass_shadows")
USAGE = (
    "{caustics = 'none'|'reflective'|'refractive'|'both', photons = N|'auto', "
    "glass_shadows = 'attenuated'|'blocked'}"
)


@dataclass(frozen=True)
class RenderOptions:
    """The extension's settings; None where neither the script nor the command line set it."""

    caustics: tuple[str, ...] | None = None
    photons: int | str | None = None
    glass_shadows: str | None = None

    def over(self, script: RenderOptions) -> RenderOptions:
        """These options (the command line's) where set, else the script's."""
        return RenderOptions(
            self.caustics if self.caustics is not None else script.caustics,
            self.photons if self.photons is not None else script.photons,
            self.glass_shadows or script.glass_shadows,
        )

    def settings(self) -> dict:
        """RenderSettings fields: the report's where nothing is set."""
        caustics = self.caustics or ()
        rule = self.glass_shadows or ("blocked" if "refractive" in caustics else "attenuated")
        photons = self.photons if self.photons is not None else DEFAULT_CAUSTIC_PHOTONS
        return {"caustics": caustics, "caustic_photons": photons, "glass_shadows": rule}

    def summary(self) -> list[str]:
        """Lines for gr.render's print-out, none when nothing is set (the report's)."""
        if self == NO_OPTIONS:
            return []
        fields = self.settings()
        kinds = " and ".join(fields["caustics"]) or "off"
        lines = [f"Caustics: {kinds}"]
        if fields["caustics"]:
            photons = fields["caustic_photons"]
            counted = "automatic" if photons == AUTO_PHOTONS else f"{photons:,}"
            lines[0] += f" ({counted} photons)"
        lines.append(f"Glass shadows: {fields['glass_shadows']}")
        return lines


NO_OPTIONS = RenderOptions()


def caustics_named(value, what: str) -> tuple[str, ...]:
    """One of CAUSTICS' names (or true / false) as the settings' tuple."""
    if isinstance(value, bool):
        return CAUSTICS["both" if value else "none"]
    if isinstance(value, str) and value.strip().lower() in CAUSTICS:
        return CAUSTICS[value.strip().lower()]
    names = ", ".join(f"'{name}'" for name in CAUSTICS)
    raise ArgumentError(f"{what} must be one of {names}, true or false; got {value!r}")


def glass_rule_named(value, what: str) -> str:
    if isinstance(value, str) and value.strip().lower() in GLASS_SHADOWS:
        return value.strip().lower()
    names = " or ".join(f"'{name}'" for name in GLASS_SHADOWS)
    raise ArgumentError(f"{what} must be {names}; got {value!r}")


def photons_named(value, what: str) -> int | str:
    if isinstance(value, str) and value.strip().lower() == AUTO_PHOTONS:
        return AUTO_PHOTONS
    number = value if isinstance(value, (int, float)) and not isinstance(value, bool) else None
    if number is None or not 0 <= number <= MAX_CAUSTIC_PHOTONS or number != int(number):
        raise ArgumentError(
            f"{what} must be a whole number from 0 to {MAX_CAUSTIC_PHOTONS:,} or "
            f"'{AUTO_PHOTONS}'; got {value!r}"
        )
    return int(number)


def script_options(table) -> RenderOptions:
    """gr.render's options table (a Lua table of names: a dict here; {} comes as a list)."""
    if isinstance(table, list) and not table:
        return NO_OPTIONS
    if not isinstance(table, dict):
        raise ArgumentError(f"the options after the lights must be a table {USAGE}")
    unknown = sorted(str(key) for key in table if key not in OPTION_NAMES)
    if unknown:
        raise ArgumentError(
            f"options {{{', '.join(unknown)}}}: not an option of gr.render; it takes {USAGE}"
        )
    caustics = table.get("caustics")
    photons = table.get("photons")
    rule = table.get("glass_shadows")
    return RenderOptions(
        caustics_named(caustics, "options.caustics") if caustics is not None else None,
        photons_named(photons, "options.photons") if photons is not None else None,
        glass_rule_named(rule, "options.glass_shadows") if rule is not None else None,
    )

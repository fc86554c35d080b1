"""A scene file's ``[requirement]``: how close to the reference, and how fast.

The error (``max_error_levels`` display levels, ``against`` true Phong or the method's own
float form) is what the compiler's width search meets.  The speed is a pixel rate: given
as ``mpixels_per_second``, or as the display the core drives, ``width`` × ``height`` ×
``fps`` (active pixels only: a display whose blanking the core must also cover gives its
pixel clock as ``mpixels_per_second``).  Without either, the compiler keeps the cheapest
architecture whatever its speed and reports the rate it reaches.
"""

import math
from dataclasses import dataclass

__all__ = ["Requirement", "bound_limit", "KEYS", "MPX_MAX", "SIDE_MAX", "FPS_MAX", "parse_requirement", "max_error",
           "throughput"]

#: Keys of the ``[requirement]`` table.
KEYS = ("max_error_levels", "against", "mpixels_per_second", "width", "height", "fps")
#: Largest pixel rate (Mpixel/s), display side (pixels) and frame rate (Hz) accepted: far
#: beyond any one shading core, small enough to catch a rate typed in pixels per second.
MPX_MAX = 100_000
SIDE_MAX = 16384
FPS_MAX = 1000
_DISPLAY = ("width", "height", "fps")


@dataclass(frozen=True)
class Requirement:
    max_error_levels: float = 1.0
    against: str = "phong"
    #: the pixel rate the core must sustain (Mpixel/s); None: no speed requirement
    mpixels_per_second: float = None
    #: ``(width, height, fps)`` of the display driven, when the rate was given that way
    display: tuple = None

    @property
    def bound_limit(self):
        """:func:`bound_limit` of :attr:`max_error_levels`."""
        return bound_limit(self.max_error_levels)

    def as_dict(self):
        """The manifest's ``"requirement"``."""
        out = {"max_error_levels": self.max_error_levels, "against": self.against,
               "mpixels_per_second": self.mpixels_per_second}
        if self.display:
            out["display"] = dict(zip(_DISPLAY, self.display))
        return out


def bound_limit(max_error_levels):
    """The continuous error bound ``B`` a certificate must stay under: the displayed error it
    guarantees, ``floor(B + 1/2)``, is at most ``max_error_levels`` exactly when
    ``B < floor(max_error_levels) + 1/2``."""
    return math.floor(max_error_levels) + 0.5


def max_error(reader, value, field):
    """``max_error_levels`` checked by ``reader`` (the scene file's, or the command line's)."""
    return reader.number(value, field, 0, 65535, open_lo=True)


def throughput(reader, value, field):
    """A pixel rate in Mpixel/s checked by ``reader``: a number in (0, :data:`MPX_MAX`]."""
    return reader.number(value, field, 0, MPX_MAX, open_lo=True)


def parse_requirement(reader, data):
    """The :class:`Requirement` of a ``[requirement]`` table ``data``, checked by the scene
    file's ``reader`` (its ``fail``, ``table``, ``number``, ``integer``: one-line
    :class:`~phongfx.scene.file.SceneError` naming the field, the value and the range)."""
    data = reader.table(data, "requirement", KEYS)
    against = data.get("against", "phong")
    if against not in ("phong", "self"):
        reader.fail(f"requirement.against must be \"phong\" or \"self\", not {against!r}")
    error = max_error(reader, data.get("max_error_levels", 1.0), "requirement.max_error_levels")
    given = [key for key in _DISPLAY if key in data]
    if "mpixels_per_second" in data and given:
        reader.fail(f"requirement must give the pixel rate either as mpixels_per_second or as the "
                    f"display's width, height and fps, not both: {['mpixels_per_second', *given]}")
    if "mpixels_per_second" in data:
        rate = throughput(reader, data["mpixels_per_second"], "requirement.mpixels_per_second")
        return Requirement(error, against, rate)
    if not given:
        return Requirement(error, against)
    for key in _DISPLAY:
        if key not in data:
            reader.fail(f"requirement.{key} is missing: width, height and fps together give the pixel "
                        f"rate of the display driven (given: {', '.join(given)})")
    width = reader.integer(data["width"], "requirement.width", 1, SIDE_MAX)
    height = reader.integer(data["height"], "requirement.height", 1, SIDE_MAX)
    fps = reader.number(data["fps"], "requirement.fps", 0, FPS_MAX, open_lo=True)
    return Requirement(error, against, width * height * fps / 1e6, (width, height, fps))

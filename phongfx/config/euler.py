"""Configuration of the corrected Euler unit of Hast, Barrera & Bengtsson."""

from dataclasses import dataclass

from phongfx.core.format import Format

from .base import BlockConfig, check_format, check_step_formats

__all__ = ["EulerConfig"]


@dataclass(frozen=True)
class EulerConfig(BlockConfig):
    """Hast, Barrera & Bengtsson corrected Euler unit: per pixel output ``p``, then
    ``p += t``, ``t += ds`` (equations 16–17); ``init`` loads ``p0``, ``t0``, ``ds``.

    ``p``, ``t``, ``ds`` are the register formats (signed); fraction bits must not fall
    from ``ds`` to ``t`` to ``p`` so both adders are exact and only the register widths
    wrap.  ``out`` is the intensity taken from ``p`` by truncation, saturated (``0.8``:
    ``floor(256·p)`` clamped to 0..255).  See :mod:`phongfx.golden.euler`.
    """

    p: str = "S1.30"
    t: str = "S3.30"
    ds: str = "S3.30"
    out: str = "0.8"

    INPUTS = {"init": (Format(1, 0), 1), "p0": ("p", 1), "t0": ("t", 1), "ds": ("ds", 1)}
    OUTPUTS = {"p": ("p", 1), "level": ("out", 1)}
    # one interpolated cosine: N·L when fed L, the base of the specular power when fed H
    SHADES = {"diff": "p", "spec": "p"}

    def validate(self):
        check_step_formats(self, ("ds", "t", "p"))
        check_format("out", self.out)

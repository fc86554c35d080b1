"""Configuration of the Gouraud unit, the baseline of Hast, Barrera & Bengtsson."""

from dataclasses import dataclass

from phongfx.core.format import Format

from .base import BlockConfig, check_format, check_step_formats

__all__ = ["GouraudConfig"]


@dataclass(frozen=True)
class GouraudConfig(BlockConfig):
    """Gouraud unit: per pixel output ``p``, then ``p += dp``; ``init`` loads ``p0``, ``dp``.

    Formats as :class:`~phongfx.config.euler.EulerConfig`: ``dp`` may not have more
    fraction bits than ``p``.
    """

    p: str = "S1.30"
    dp: str = "S3.30"
    out: str = "0.8"

    INPUTS = {"init": (Format(1, 0), 1), "p0": ("p", 1), "dp": ("dp", 1)}
    OUTPUTS = {"p": ("p", 1), "level": ("out", 1)}
    # one interpolated cosine: N·L when fed L, the base of the specular power when fed H
    SHADES = {"diff": "p", "spec": "p"}

    def validate(self):
        check_step_formats(self, ("dp", "p"))
        check_format("out", self.out)

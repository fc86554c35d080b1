"""A certificate: a sound upper bound on a design's error over a scene's input domain.

The error is the compiler's (:mod:`phongfx.compiler.compile`): per pixel and
channel, ``|out - (2^bits - 1)·I_ref|`` in display levels before the reference's own
rounding.  A continuous bound ``B`` on it bounds the displayed error
``|out - level(I_ref)|`` by ``floor(B + 0.5)`` (the reference's rounding adds at most half
a level, and the displayed error is an integer), which is what the scene's
``requirement.max_error_levels`` is compared with.
"""

import math
from dataclasses import dataclass, field

from phongfx.scene.requirement import bound_limit

__all__ = ["Certificate", "integer_bound", "meets"]


def integer_bound(bound_levels):
    """The displayed error ``floor(B + 0.5)`` that a continuous bound ``B`` guarantees."""
    return math.floor(bound_levels + 0.5)


def meets(bound_levels, max_error_levels):
    """Whether a bound ``B`` (None: no bound) guarantees ``max_error_levels``."""
    return bound_levels is not None and bound_levels < bound_limit(max_error_levels)


@dataclass(frozen=True)
class Certificate:
    """How far a design's outputs can be from the reference over a whole domain.

    ``certified``: the bound meets the requirement (:func:`meets`); ``bound_levels``: a
    sound upper bound on ``|out - (2^bits - 1)·I_ref|`` over the domain (None when none was
    obtained); ``method``: how (``"interval"``, ``"exhaustive"``, ``"gappa+interval"``...);
    ``parts``: named contributions (``{"rounding": .., "approximation": .., "output": 0.5}``,
    or what the method measured); ``why``: one sentence when not certified or without a
    bound; ``seconds``: how long it took.
    """

    certified: bool
    bound_levels: float
    method: str
    parts: dict = field(default_factory=dict)
    why: str = ""
    seconds: float = 0.0

    @classmethod
    def from_dict(cls, data):
        """The certificate :meth:`as_dict` gave (other keys ignored)."""
        return cls(data["certified"], data["bound_levels"], data["method"], dict(data.get("parts") or {}),
                   data.get("why", ""), data.get("seconds", 0.0))

    def as_dict(self):
        """JSON-able: what the manifest and ``phongfx certify --json`` write."""
        return {"certified": self.certified, "bound_levels": self.bound_levels, "method": self.method,
                "parts": dict(self.parts), "why": self.why, "seconds": round(self.seconds, 3)}

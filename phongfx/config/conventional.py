"""Configuration of the conventional Phong unit: normalization, reflection, true power."""

from dataclasses import dataclass

from .base import check_format
from .blinn import BlinnConfig

__all__ = ["ConventionalConfig"]


@dataclass(frozen=True)
class ConventionalConfig(BlinnConfig):
    """Phong's own shader as Lyon (1993, "Background") describes the direct design: the
    interpolated ``N`` normalized per pixel, the specular cosine ``R·V`` of the reflected
    light ``R = 2(N̂·L)N̂ - L`` (Phong 1975), raised to the shininess ``n`` at 16-bit precision.

    Per pixel: ``diffuse = clamp(N̂·L, 0, 1)`` and ``specular = clamp(R·V, 0, 1)^n``, 0
    wherever ``N̂·L <= 0`` (the light behind the surface), for an un-normalized ``N``,
    ``L`` and ``V`` unit unless :attr:`local_light` / :attr:`local_viewer`, all ``vec``,
    shininess ``n`` an integer ``1..n_max``.  Every :class:`BlinnConfig` field means what it
    means there (the normalizer, the cosine scaling, the log/exp tables and ``out``; the
    defaults are Blinn's, for the same reasons), and:

    * ``cos`` [``S1.17``]: the signed cosines ``N̂·L`` and ``N̂·V`` that form
      ``R·V = 2(N̂·L)(N̂·V) - L·V``; signed because ``N̂·V`` may be negative where the
      reflection still reaches the viewer, two guard bits over ``t`` since ``R·V`` takes
      each twice.  The diffuse output is ``N̂·L`` rounded from it;
    * ``local_light`` / ``local_viewer`` [False]: ``L`` / ``V`` is an un-normalized vector
      (a point light, a viewer near the surface), which the unit normalizes per pixel by its
      own copy of the normalizer (:attr:`q` of ``vec``, then ``m``, ``y``, ``nr``, ``dot``),
      the unit vector rounded back to ``vec``.  False: the input is taken as unit length
      and no normalizer is built.

    Zero-length ``N`` gives 0 for both outputs; a zero-length local ``L`` or ``V``
    normalizes to the zero vector (its seed word is 0), which gives defined outputs too.
    """

    cos: str = "S1.17"
    local_light: bool = False
    local_viewer: bool = False

    INPUTS = {"normal": ("vec", 3), "light": ("vec", 3), "view": ("vec", 3), "n": ("n", 1)}
    OUTPUTS = {"diffuse": ("out", 1), "specular": ("out", 1)}
    #: ``(diffuse port, lane, specular port)`` of the light it computes, as a shader's blend
    #: takes it (:func:`phongfx.config.shader.unit_terms`)
    TERMS = ("diffuse", None, "specular")
    #: The inputs that depend on the light (:attr:`BlinnConfig.PER_LIGHT`); N, V and ``n``
    #: enter a shader once, V only when every copy takes it alike (the same ``local_viewer``)
    PER_LIGHT = ("light",)
    #: A shared input -> the fields every copy must agree on for it to be shared
    SHARED_ALIKE = {"view": ("local_viewer",)}

    def validate(self):
        super().validate()
        check_format("cos", self.cos, signed=True, holds_one=True)
        for name in ("local_light", "local_viewer"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{name} must be True or False, not {getattr(self, name)!r}")

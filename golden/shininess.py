"""The shininess operand of Lyon (1993) Figure 7c (``n``) and Figure 8 (``m = √n``): the
per-pixel port's codes, or the constant the configuration builds into the hardware
(:class:`~phongfx.config.base.ConstantShininess`) in the port's format, so that a fixed
shininess gives the codes of feeding that value on the port.
"""

import numpy as np

from .fixed import Fixed, check_range

__all__ = ["shininess_input"]


def shininess_input(config, value, count):
    """The shininess operand of a block ``config`` (a ``ConstantShininess``): the port's
    ``value`` (checked to lie in ``1..<port>_max``) when the shininess is a port, else the
    constant in the port's format for each of ``count`` cases, which must then come without
    a port value."""
    name, constant = config.SHININESS, config.shininess_const
    if constant:
        if value is not None:
            raise ValueError(f"{name} must not be given: {name}_const = {constant} fixes it")
        return Fixed(np.full(count, constant), config.fmt(name))
    if value is None:
        raise ValueError(f"{name} must be given: {name}_const = 0 makes it an input")
    check_range(name, value, 1, config.shininess_max)
    return value

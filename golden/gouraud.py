"""Golden model of the Gouraud unit: one adder, ``p += dp`` (Gouraud 1971; Hast et al. §1).

Per pixel the unit outputs ``p`` and then steps ``p += dp``; ``init`` loads ``p = p0``
and ``dp`` first (output ``p0``).  ``k`` pixels after ``init``: ``p_k = p0 + k·dp``.
Hast, Barrera & Bengtsson's corrected Euler recurrence (equations 16–17) without its
second difference: the model is :func:`phongfx.golden.euler.forward_difference_unit`
with one step register instead of two.

Formats (:class:`~phongfx.config.GouraudConfig`): registers ``p`` [``S1.30``] and ``dp``
[``S3.30``], ``dp`` with no more fraction bits than ``p``; the sum has no bit growth and
wraps in ``p``'s width like the hardware adder.  ``level`` is ``p`` truncated and
saturated to ``out`` [``0.8``], as in :mod:`phongfx.golden.euler`.  Before any ``init``
the registers hold 0.
"""

from .euler import forward_difference_unit

__all__ = ["gouraud"]


def gouraud(config, init, p0, dp):
    """Linearly interpolated intensities of a sequence of pixels.

    Parameters
    ----------
    config : GouraudConfig
    init : Fixed, shape (count,), ``1.0``
        1 on the first pixel of a scanline: load ``p0``, ``dp``.
    p0, dp : Fixed, shape (count,), ``config.p``, ``config.dp``

    The arrays are the ordered sequence of valid pixels: the unit is stateful.

    Returns
    -------
    dict
        ``{"p": Fixed (count,) in config.p, "level": Fixed (count,) in config.out}``
    """
    return forward_difference_unit(config, init, (p0, dp), "gouraud level")

"""Golden model of the Reflect operation, Lyon (1993) Figure 7b: ``R = 2(N·V)N - V``.

The formats are our reconstruction (the figure's bit annotations are lost from our
copy).  ``N`` and ``V`` are ``S1.10``: 10 fraction bits as in the Figure 7a text, and
one integer bit so that the edge value 1.0 is exact.  ``N·V`` is three exact
12×12 products, ``S3.20`` (the corner ``(-2)·(-2) = 4`` needs the third integer
bit), summed exactly in ``S5.20``, then rounded once to ``dot`` = ``S1.12``: two
guard bits, so that after doubling and scaling by ``|N_i| <= 1`` its rounding costs
at most 1/4 LSB of ``R``; the integer bit holds ``N·V = ±1`` exactly.  Doubling is
a shift (``S2.11``, same raw bits); each 14×12 product ``S2.11 × S1.10`` is exact in
``S4.21``; subtracting ``V`` gives ``S5.21``, rounded once to ``out`` = ``S1.10``,
the format in which Figure 7c takes ``R``.  Error against exact arithmetic on the
same inputs, unit inputs, round half up: at most 1/4 + 1/2 = 3/4 LSB of ``R``.

For unit inputs ``|N·V| <= 1`` and ``|R| = |V|``, so neither quantize overflows;
junk codes (``|N_i|`` up to 2) reach ``|N·V| = 12``, so both saturate rather than
wrap a large reflection into a wrong direction.
"""

__all__ = ["reflect"]


def reflect(config, n, v):
    """Reflect the viewpoint ``v`` about the normal ``n``.

    Parameters
    ----------
    config : ReflectConfig
    n, v : Fixed, shape (count, 3), format ``config.vec``

    Returns
    -------
    dict
        ``{"r": Fixed (count, 3) in config.out}``
    """
    dot = n.dot(v).quantize(config.dot, config.rounding, "saturate", op="reflect N·V")
    p = n * (dot << 1)[:, None]
    return {"r": (p - v).quantize(config.out, config.rounding, "saturate", op="reflect R")}

"""Certificates: sound upper bounds on a design's error over a scene's whole input domain.

* :mod:`.certificate`: the :class:`~.certificate.Certificate` record;
* :mod:`.exhaustive`: every input code the host can send, where the domain is small enough
  (exact per-pixel normals, one ``n``, lights and viewer at infinity);
* :mod:`.gappa`: Gappa's proof of the rounding error of Lyon's Figure 7c–d chain.

May import every layer but ``phongfx.cli``.
"""

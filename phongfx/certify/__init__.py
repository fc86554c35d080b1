"""Certificates: sound upper bounds on a design's error over a scene's whole input domain.

* :mod:`.certificate`: the :class:`~.certificate.Certificate` record;
* :mod:`.bound`: :func:`~.bound.certify`, through the unit's bounding method (:mod:`.bounding`);
  :mod:`.figures`, the ``"interval"`` method of Lyon's datapaths: rounding error by interval
  arithmetic through the golden blocks (:mod:`.interval`, :mod:`.datapath`), the ideal
  datapath's distance from the reference (:mod:`.approximation`), both on boxes of the domain's
  normals (:mod:`.sphere`) refined by branch and bound (:mod:`.branch`), summed at the outputs (:mod:`.outputs`);
  :mod:`.spherical`, the spherical unit's, fed per span (:mod:`.span`), its one-angle tables
  (:mod:`.lobe`) on the same boxes and sum;
  :mod:`.table_units`, the ``"interval+tables"`` method of the conventional and Blinn units: the
  normalizer's cosines on intervals (:mod:`.normalizer`), its seed table and the power's log and
  exp tables run on every code (:mod:`.tables`);
* :mod:`.exhaustive`: every input code the host can send, where the domain is small enough
  (exact per-pixel normals, one ``n``, lights and viewer at infinity);
* :mod:`.gappa`: Gappa's proof of the rounding error of Lyon's Figure 7c–d chain.

May import every layer below it: everything but ``phongfx.compiler`` and ``phongfx.cli``
(it bounds a design through the compile room's fitting of a method to a scene,
:mod:`phongfx.explore.compile.run`, and the compiler calls it).
"""

from .bound import certify
from .certificate import Certificate

__all__ = ["Certificate", "certify"]

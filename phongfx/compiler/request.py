"""What a compile is asked: :class:`CompileRequest`, the scene and every option, checked.

:func:`phongfx.compiler.compile.compile_scene` takes one request; ``phongfx compile`` builds it
from its flags.  A request is checked when it is made, before the minutes of search: a bad
field raises ``ValueError`` naming the field, the value given and what it may be.
"""

import math
from dataclasses import dataclass, field

from phongfx.explore.compile.architecture import CLOCK_MAX, COST_UNITS, Speed
from phongfx.explore.compile.workers import count
from phongfx.core.methods import METHODS

__all__ = ["CERTIFY", "CompileRequest", "check_methods", "check_samples"]

#: What a compile certifies: nothing (the measured error alone chooses), the chosen design once
#: (kept in :attr:`~phongfx.compiler.compile.Compiled.certificate`, changing nothing), or every
#: width point searched (the certified search, ``phongfx compile``'s default).
CERTIFY = ("none", "chosen", "search")


def check_methods(methods):
    """``methods`` as a list (all of :data:`~phongfx.core.methods.METHODS` for None), each checked."""
    names = list(METHODS) if methods is None else list(methods)
    for name in names:
        if name not in METHODS:
            raise ValueError(f"method must be one of {', '.join(METHODS)}, not {name!r}")
    return names


def check_samples(name, value):
    """Raise unless ``value`` (the field ``name``) is None or a positive integer."""
    if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
        raise ValueError(f"{name} must be a positive integer, not {value!r}")


def _check_positive(name, value, hi, unit):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or not 0 < value <= hi:
        raise ValueError(f"{name} must be a number of {unit} in (0, {hi}], not {value!r}")


@dataclass(frozen=True)
class CompileRequest:
    """A scene to compile (``spec``, a :class:`~phongfx.scene.file.SceneSpec`) and how.

    :ivar methods: keys of :data:`~phongfx.core.methods.METHODS` to consider (None: all).
    :ivar synth: cost by synthesis instead of the proxy.
    :ivar target: what the cost is measured on: ``"ecp5"`` (LUT-eq), ``"ice40"`` or
        ``"asic"`` (µm²); with ``device`` (the part, or the library on ``"asic"``, default
        ``osu018``), ``freq`` (the clock given to the tools, MHz) and ``seed`` (nextpnr's
        placement seed).
    :ivar clock: the clock (MHz) the core will run at: the chosen architecture must reach it,
        its pixel rate is ``clock / interval``, and synthesis is given it instead of ``freq``;
        None: each design at its own Fmax.  The pixel rate asked is the scene's
        ``requirement.mpixels_per_second`` (:func:`phongfx.scene.file.with_throughput`).
    :ivar scheduler: where ``synth`` runs its candidates in parallel (a Dask scheduler
        address; None: a local cluster of ``workers`` processes).  ``workers`` also bounds
        the processes that search the methods' widths and the witness side by side
        (:mod:`~phongfx.explore.compile.workers`; None: every core, 1: this process alone).
    :ivar samples: domain points per measured width point, instead of the scene's
        (``[domain] samples``); ``final_samples``: those of the witness search.
    :ivar journal: a folder where every measured width point is kept, so that a rerun of
        the same scene (and code) skips them (:mod:`phongfx.explore.compile.journal`).
    :ivar prove: prove the chosen design's ``overflow="error"`` claims
        (:mod:`phongfx.sim.prove`, ``prove_timeout`` seconds per claim); a design with a
        counterexample is not chosen and the next cheapest is proven instead.
    :ivar certify: one of :data:`~phongfx.compiler.request.CERTIFY`.  ``"search"``: each method certifiable on the scene
        is searched once with its certificate (:func:`phongfx.certify.certify`) as a second
        test, the others are rejected with the certificate's why
        (:mod:`~phongfx.explore.compile.certified`); when no method has a certified design,
        nothing is chosen and the result's ``refused`` says why per method.  ``"chosen"``: the
        chosen design's certificate is computed once and kept, changing nothing.
    :ivar certificates: a folder where certificates are kept and read back
        (:func:`phongfx.certify.remembered.remembering`; None: each bounded afresh).
    :ivar geometries: the scene's frames when the caller has them (None: computed).
    :ivar progress: called with a short description of each step; each synthesis as
        "candidate i of N (label): stage, T s".
    :ivar prepare: ``prepare(result, analysis)``, work the caller will need for the chosen
        design (``result`` a search result), begun for the likeliest choice in a forked process
        beside its witness search and, when that design is chosen, left running for the caller,
        who takes its return when it needs it (:meth:`~phongfx.compiler.compile.Compiled.take_prepared`,
        or :meth:`~phongfx.compiler.compile.Compiled.close` to end it): the command builds its RTL
        check's simulator and makes its shipped module
        (:func:`~phongfx.explore.compile.emit.prepare_outputs`), and emit takes them after drawing
        its pictures.
    """

    spec: object
    methods: tuple = None
    synth: bool = False
    target: str = "ecp5"
    device: str = None
    freq: float = 150
    seed: int = 1
    clock: float = None
    scheduler: str = None
    workers: int = None
    samples: int = None
    final_samples: int = None
    journal: object = None
    prove: bool = False
    prove_timeout: float = 600
    certify: str = "none"
    certificates: object = None
    geometries: object = field(default=None, compare=False, repr=False)
    progress: object = field(default=None, compare=False, repr=False)
    prepare: object = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        if self.methods is not None:
            object.__setattr__(self, "methods", tuple(check_methods(self.methods)))
        if self.target not in COST_UNITS:
            raise ValueError(f"target must be one of {', '.join(COST_UNITS)}, not {self.target!r}")
        if self.certify not in CERTIFY:
            raise ValueError(f"certify must be one of {', '.join(CERTIFY)}, not {self.certify!r}")
        check_samples("samples", self.samples)
        check_samples("final_samples", self.final_samples)
        count(self.workers)
        _check_positive("freq", self.freq, CLOCK_MAX, "MHz")
        _check_positive("prove_timeout", self.prove_timeout, math.inf, "seconds")
        if isinstance(self.seed, bool) or not isinstance(self.seed, int):
            raise ValueError(f"seed must be an integer, not {self.seed!r}")
        Speed(self.spec.requirement.mpixels_per_second, self.clock)  # checked before the minutes of search

    @property
    def speed(self):
        """The :class:`~phongfx.explore.compile.architecture.Speed` asked: the scene's pixel
        rate and :attr:`clock`."""
        return Speed(self.spec.requirement.mpixels_per_second, self.clock)

    @property
    def names(self):
        """The methods considered, in order (every one of METHODS when ``methods`` is None)."""
        return check_methods(self.methods)

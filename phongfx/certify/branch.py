"""Branch and bound over boxes of a domain's normals: the search every box-based bounding
method shares.

A bounding method gives ``errors(boxes, floor)``: per box and channel the ``rounding`` and
``approximation`` parts of its bound (B, 3) in display levels, the quantizes that may overflow
(``faults``) and per box the backside ``gate`` (0 where the hardware's and the reference's
backside tests agree).  Each box's total ``max_c(rounding + approximation) + 1/2`` holds for
every point in it and the boxes cover the domain, so the largest total over the boxes at any
round is sound; :func:`bound_boxes` halves the boxes whose total is within ``tolerance`` of the
largest, round after round, until the largest stops falling (or the time or box budget is spent):
splitting only makes the bound tighter.  ``floor`` (levels, before the output's half level) is
where the new boxes' bounds stop mattering this round: a box under it is not split while the
largest stays above ``floor + tolerance``, so a method may spend its costlier, tighter bound
only on the boxes above it (:mod:`.table_units` lists codes there) and give any sound bound below.

A method whose bound of a box depends on that box alone (``separable``) has each round's boxes
bounded in two halves, one by a :class:`~phongfx.explore.compile.workers.Twin` of this process,
while a core is idle (:func:`~phongfx.explore.compile.workers.spare_core`: the last width search
running alone): the same bounds, sooner.

A :class:`Resume` keeps where a branch and bound stopped, so that the same search given a larger
budget goes on from there instead of halving the same boxes again: its rounds do not depend on
the budget (only its stops do), so it ends where a fresh one with that budget would.
"""

import time

import numpy as np

from phongfx.explore.compile.workers import Twin, spare_core

from .sphere import Boxes, cover

__all__ = ["TWIN_BOXES", "SECONDS", "Resume", "bound_boxes", "cases", "first_boxes"]

#: Boxes from which a round is worth halving between this process and its twin.
TWIN_BOXES = 4096
#: Wall-clock seconds after which a branch and bound stops: a guard against a hang, not a budget.
#: The budget is ``max_boxes``, the same on every machine; at 60 s a loaded machine's compile of
#: the local mesh shipped a bound of 1.422 levels (166,688 boxes) where an idle one's is 1.398
#: (317,610 boxes), so the time stop sits far above what any certificate takes (2.5–6 s on the
#: example scenes), and a certificate it cut says so (``parts["timed_out"]``).
SECONDS = 900.0


def cases(domain):
    """``(n, material)`` per admissible shininess of every used material of ``domain``."""
    return [(n, m) for m, (_, values) in enumerate(domain.materials) for n in values]


def first_boxes(domain):
    """The first cover of the domain's normals (:func:`~phongfx.certify.sphere.cover`), one set
    per admissible ``n``."""
    return cover(domain.view_cos_min, domain.min_normal_length, cases(domain),
                 view_cos_max=getattr(domain, "view_cos_max", 1.0))


class Resume:
    """Where a branch and bound over one domain stopped (module docstring): ``bound_boxes(...,
    resume=r)`` goes on from ``r`` when it holds a stop, and leaves its own stop in it."""

    def __init__(self):
        self.stop = None


def bound_boxes(errors, domain, *, tolerance=0.02, max_boxes=300_000, seconds=None, batch=2048,
                max_batch=65536, enough=None, boxes=None, patience=4, resume=None, separable=False):
    """Branch and bound (module docstring): ``(bound, parts)``, ``bound`` inf when some box
    cannot be bounded (``parts["faults"]`` then names the quantizes that may overflow).

    ``boxes``: the first cover (default :func:`first_boxes`).  Each round halves the boxes within
    ``tolerance`` of the largest bound (at least the ``batch`` largest, at most ``max_batch``); it
    stops when the largest has fallen by under 0.2 % over ``patience`` rounds that split every box
    near it (a box with more sides needs more halvings before its children's bounds fall), or once
    ``max_boxes`` boxes have been bounded (the budget that makes the result the same on every
    machine), or at ``seconds`` (a hang guard, :data:`SECONDS`; ``parts["timed_out"]`` then), or as
    soon as the largest is below ``enough`` (a width search
    needs no tighter bound).  With ``enough``, it also stops once the largest, falling at its
    pace per box of the last ``patience - 1`` rounds that split every box near it, would still not be
    below ``enough`` when the budget is spent (``parts["abandoned"]``): the bounds of a branch and
    bound fall ever more slowly, so the pace so far is the most the rest could give, and a width
    search's failing designs, the most of its certificates, cost a fraction of the budget.
    ``separable``: each box's bound depends on that box alone, so that a round's boxes may be
    bounded in halves (module docstring)."""
    seconds = SECONDS if seconds is None else seconds
    with _Halves(errors, separable) as errors:
        start, faults, history, spent, abandoned = time.perf_counter(), set(), [], [], False

        def evaluate(boxes, floor=-np.inf):
            rounding, approximation, found, gate = errors(boxes, floor)
            faults.update(found)
            total = np.max(rounding + approximation, axis=-1) + 0.5
            return boxes, np.nan_to_num(total, nan=np.inf), rounding, approximation, gate

        if resume is not None and resume.stop is not None:
            pool, evaluated, history, spent, found = resume.stop
            history, spent = list(history), list(spent)
            faults.update(found)
        else:
            pool = evaluate(first_boxes(domain) if boxes is None else boxes)
            evaluated = len(pool[0])
        while True:
            boxes, total = pool[0], pool[1]
            top = float(total.max())
            near = total >= top - tolerance
            whole = np.count_nonzero(near) <= max_batch
            history.append((top, whole))
            settled = (len(history) > patience and all(w for _, w in history[-patience:])
                       and history[-patience - 1][0] - top <= 0.002 * max(top, 1.0))
            met = enough is not None and top < enough
            spent.append(evaluated)
            if (enough is not None and not met and len(history) > patience - 1
                    and all(w for _, w in history[-patience:])):
                pace = (history[-patience][0] - top) / max(evaluated - spent[-patience], 1)
                abandoned = top - pace * (max_boxes - evaluated) >= enough
            timed_out = time.perf_counter() - start > seconds
            if met or settled or abandoned or timed_out or evaluated > max_boxes:
                break
            count = min(max(np.count_nonzero(near), batch), max_batch, len(total))
            pick = np.zeros(len(total), dtype=bool)
            pick[np.argpartition(-total, count - 1)[:count]] = True
            # a child under the top's near band is not split next round, nor is its bound reported
            children = _inherit(evaluate(boxes.take(pick).split(), top - tolerance - 0.5),
                                [part[pick] for part in pool[1:]])
            evaluated += len(children[0])
            rest = [boxes.take(~pick)] + [part[~pick] for part in pool[1:]]
            pool = (Boxes.concat(rest[0], children[0]),) + tuple(np.concatenate([a, b])
                                                                 for a, b in zip(rest[1:], children[1:]))
        if resume is not None:  # before the last round's record: going on, the stops are asked again
            resume.stop = (pool, evaluated, history[:-1], spent[:-1], set(faults))
        bound, parts = _worst(*pool, domain)
        parts.update(boxes=int(evaluated), rounds=len(history))
        if abandoned:
            parts["abandoned"] = True
        if timed_out and not (met or settled or abandoned or evaluated > max_boxes):
            parts["timed_out"] = True
        if faults:
            parts["faults"] = sorted(faults)
        return bound, parts


class _Halves:
    """``errors`` with a round of :data:`TWIN_BOXES` boxes or more bounded in halves, the second
    by a :class:`~phongfx.explore.compile.workers.Twin` (begun when first needed, ended on leaving
    the ``with``) while a core is idle; ``errors`` itself unless ``separable``."""

    def __init__(self, errors, separable):
        self.errors, self.separable, self.twin = errors, separable, None

    def __enter__(self):
        return self if self.separable else self.errors

    def __exit__(self, *_):
        if self.twin is not None:
            self.twin.close()

    def __call__(self, boxes, floor):
        if len(boxes) < TWIN_BOXES or not spare_core():
            return self.errors(boxes, floor)
        if self.twin is None:
            self.twin = Twin(lambda item: self.errors(*item))
        first = np.arange(len(boxes)) < len(boxes) // 2
        self.twin.send((boxes.take(~first), floor))
        mine, theirs = self.errors(boxes.take(first), floor), self.twin.result()
        return (np.concatenate([mine[0], theirs[0]]), np.concatenate([mine[1], theirs[1]]), mine[2] | theirs[2],
                np.concatenate([mine[3], theirs[3]]))


def _inherit(children, parents):
    """A child keeps its parent's bound where its own is larger: the parent's holds on it too
    (interval bounds need not shrink with the box, only hold on it)."""
    boxes, total, *rest = children
    # Boxes.split puts the low halves first, then the high ones: parents twice over
    worse = total > np.concatenate([parents[0], parents[0]])
    for mine, theirs in zip([total, *rest], parents):
        both = np.concatenate([theirs, theirs])
        mine[worse] = both[worse]
    return (boxes, total, *rest)


def _box(boxes, i, domain, channel=None):
    """Where box ``i`` is: its ``n``, material, channel and ranges of θ, φ (degrees) and z."""
    out = {"n": int(boxes.n[i]), "material": domain.materials[int(boxes.material[i])][0]}
    if channel is not None:
        out["channel"] = "rgb"[channel]
    out.update(theta_deg=[round(float(np.degrees(x)), 4) for x in boxes.theta[i]],
               phi_deg=[round(float(np.degrees(x)), 4) for x in boxes.phi[i]],
               z=[round(float(x), 6) for x in boxes.z[i]])
    if boxes.cells is not None:
        out["cell"] = [[round(float(x), 6) for x in corner] for corner in boxes.cells[i]]
    return out


def _worst(boxes, total, rounding, approximation, gate, domain):
    """``(bound, parts)``: the box with the largest total, its parts (they sum to the bound), and
    the largest of each part alone with its box."""
    i = int(np.argmax(total))
    c = int(np.argmax(rounding[i] + approximation[i]))
    parts = {"rounding": float(rounding[i, c]), "approximation": float(approximation[i, c]), "output": 0.5,
             "where": _box(boxes, i, domain, c)}
    if gate[i] > 0:
        parts["backside"] = float(gate[i])
    for name, part in (("rounding", rounding), ("approximation", approximation)):
        j = int(np.argmax(part.max(axis=-1)))
        parts[f"largest_{name}"] = {"levels": float(part[j].max()), "where": _box(boxes, j, domain)}
    return float(total[i]), parts

"""How a long synthesis loop says where it is: "synthesizing candidate i of N (what) 12 s".

``compile --synth``, ``tables cost`` and ``report`` each synthesize a list of designs, each
taking from seconds to minutes.  A bar that only counts steps looks hung for minutes, so
every one of them names the candidate, its place in the list and the time spent so far,
and passes the synthesis flow's own stage (yosys, nextpnr, sta) through.
"""

import time

__all__ = ["describe", "Candidates"]


def describe(block, params=None):
    """``fig7, vec=10 t=8`` of a block name and its changed widths (``params``: a dict)."""
    if not params:
        return str(block)
    return f"{block}, " + " ".join(f"{k}={v}" for k, v in params.items())


class Candidates:
    """Counts the candidates of one loop and words each step for a ``progress(text)`` callable.

    >>> lines = []
    >>> steps = Candidates(2, lines.append, clock=lambda: 0.0)
    >>> stage = steps.next("fig7", {"vec": 10})
    >>> stage("yosys")
    >>> lines
    ['synthesizing candidate 1 of 2 (fig7, vec=10) 0 s', 'synthesizing candidate 1 of 2 (fig7, vec=10): yosys 0 s']
    >>> steps.failed("nextpnr failed (exit code 1); log x/nextpnr.log:\nERROR: ...")
    >>> lines[-1]
    'synthesizing candidate 1 of 2 (fig7, vec=10) FAILED: nextpnr failed (exit code 1); log x/nextpnr.log 0 s'
    """

    def __init__(self, total, progress, clock=time.monotonic):
        if not isinstance(total, int) or total < 0:
            raise ValueError(f"total must be a non-negative integer, not {total!r}")
        self.total, self.progress, self.clock = total, progress, clock
        self.index, self.started = 0, clock()
        self.what = None

    def next(self, block, params=None):
        """Announce the next candidate; returns the callable that words its flow's stages."""
        self.index += 1
        what = self.what = f"synthesizing candidate {self.index} of {self.total} ({describe(block, params)})"
        self.progress(f"{what} {self.clock() - self.started:.0f} s")
        return lambda stage: self.progress(f"{what}: {stage} {self.clock() - self.started:.0f} s")

    def failed(self, error):
        """Say that the current candidate failed, with the first line of ``error`` (the
        loop goes on to the next one, and a failure must not pass unseen)."""
        first = (str(error).strip().splitlines() or [type(error).__name__])[0]
        self.progress(f"{self.what} FAILED: {first} {self.clock() - self.started:.0f} s")

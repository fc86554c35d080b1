"""A golden model run a chunk of pixels at a time, for speed; the outputs are the same.

Every operation of a numpy golden model is a pass over int64 arrays, and its temporaries
are as long as the batch: on 10^6 pixels each is 8 MB (24 MB for a vector), so every pass
goes to main memory.  Cut into chunks of :data:`CHUNK` pixels, one chunk's temporaries
stay in the CPU's cache (a 2 MiB L2 per core on the machine measured), which made the Figure 7
golden model 2–6× faster on 1–16 Mpixels (``make bench``); much smaller chunks lose it
again to the Python overhead of each call.

Only a model that keeps no state from pixel to pixel may be cut anywhere: a stateful
unit (Hast et al.'s Euler and Gouraud units, the spherical unit) reloads its state at an
``init`` port, and :func:`stateless` refuses any port of that name.

A chunk that raises (an ``overflow="error"`` quantize met a value outside its format, an
input out of range) makes the whole batch run again at once, so that the error, which
counts the offending values and names the first, is the one the whole batch gives.
"""

import numpy as np

__all__ = ["CHUNK", "stateless", "chunked"]

#: Pixels per chunk: the best of 8K–128K for the Figure 7 datapath (measured with ``make bench``
#: on a loaded 2-core machine; 16K–128K were within the noise of each other).
CHUNK = 1 << 16


def stateless(ports):
    """Whether a model with input ports ``ports`` (names) keeps no state between pixels:
    none is ``init`` (or a copy's ``c<j>_init``), where a stateful unit reloads."""
    return not any(name == "init" or name.endswith("_init") for name in ports)


def chunked(function, raw, chunk=CHUNK):
    """``function(raw)`` (a dict of arrays, the pixels along the first axis, in and out)
    computed ``chunk`` pixels at a time and joined; at once when ``chunk`` is None, when
    the batch is not longer than a chunk, or when the arrays do not all have its length."""
    lengths = {len(value) if np.ndim(value) else -1 for value in raw.values()}
    count = lengths.pop() if len(lengths) == 1 else -1
    if chunk is None or count <= chunk:
        return function(raw)
    out = None
    try:
        for start in range(0, count, chunk):
            part = function({name: value[start:start + chunk] for name, value in raw.items()})
            if out is None:  # filled in place: no second copy of every output to join at the end
                out = {name: np.empty((count, *np.shape(value)[1:]), np.asarray(value).dtype)
                       for name, value in part.items()}
            for name, value in part.items():
                out[name][start:start + len(value)] = value
    except (ValueError, OverflowError):
        return function(raw)
    return out

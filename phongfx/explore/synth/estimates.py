"""The tool-free estimates of a design, kept: on disk in the per-user cache and in memory.

An estimate (the area proxy's LUT-eq or µm², the clock proxy's Fmax) is a pure function of the
design and of the estimator's code, read from the design's RTLIL; elaborating a Figure 7
datapath to RTLIL takes 1.5 s, which was 62 % of a ``phongfx compile`` of the torus (12
candidates priced).  :func:`cached_estimate` keys each estimate by the design's identity
(:func:`phongfx.hdl.identity.design_identity`: its classes, config, the elaboration settings and
the digest of the sources that make hardware) and the digest of this folder's sources (the
estimators), so pricing a known candidate elaborates nothing; any edit of either is a new key.
Entries live in the per-user cache's ``proxy/`` folder (:func:`phongfx.core.cache.folder`), one
``estimate.json`` each, made whole or not at all (:func:`phongfx.core.cache.make_entry`).
"""

import copy
import functools
import hashlib
import json
from pathlib import Path

from phongfx.core.cache import folder, make_entry

__all__ = ["ESTIMATE", "estimate_key", "cached_estimate"]

#: The file of an entry: the estimate as JSON.
ESTIMATE = "estimate.json"
#: Estimates found in this process, by key.
_KNOWN = {}


@functools.cache
def _estimators_digest():
    from phongfx.hdl.identity import folder_digest

    return folder_digest(Path(__file__).parent)


def estimate_key(kind, block, target, device):
    """The key of estimate ``kind`` of ``block`` (a :class:`~phongfx.core.registry.Block`) on
    ``target`` and ``device``, or None when the design has no identity (it is then computed
    every time)."""
    from phongfx.hdl.identity import design_identity

    identity = design_identity(block.component_class, block.config, block.name)
    if identity is None:
        return None
    parts = [kind, str(target), str(device), identity, _estimators_digest()]
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()[:32]


def cached_estimate(kind, block, target, device, compute):
    """Estimate ``kind`` (``"area"``, ``"clock"``) of ``block`` on ``target``/``device``:
    ``compute()`` (a JSON-able dict) the first time, then read back from memory or from the
    per-user cache's ``proxy/`` folder.  Each call returns its own copy."""
    key = estimate_key(kind, block, target, device)
    if key is None:
        return compute()
    if key not in _KNOWN:
        def make(work):
            value = compute()
            (work / ESTIMATE).write_text(json.dumps(value, sort_keys=True) + "\n")
            return value

        entry, value = make_entry(folder("proxy"), key, ESTIMATE, make)
        if entry is not None:  # the stored form, as every later run reads it
            value = json.loads((entry / ESTIMATE).read_text())
        _KNOWN[key] = value
    return copy.deepcopy(_KNOWN[key])

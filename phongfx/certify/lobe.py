"""The spherical unit's functions of one angle, as tables a box of normals looks up
(Szirmay-Kalos et al. 2000, equations 17–19, §4; :mod:`.spherical` sums them).

The unit reads ``g(θ)``, ``cos²`` (specular) or ``cos`` (diffuse) at the angle register's
``θ`` through a ROM of ``2^A`` cells; the register drifts at most ``δ`` from the exact angle
(:mod:`.spherical`).  A pixel's exact specular angle is ``θ = a·x`` with ``A·cos x = N_s·H =
cos ψ`` (``A <= 1``, so ``|x| <= ψ`` and ``A = cos ψ/cos x``), its diffuse one ``x_d`` with
``A_d·cos x_d = N_s·L``.  Tables per cell of ``ψ`` (:data:`PSI_CELLS` on ``[0, π/2]``):

* :func:`lobe_table`: the range of the float form ``A^n'·g(a·x)`` (equation 19's ``cos²(a·x)``
  for ``cos^n'``, times equation 18's ``A^n'``);
* :func:`rom_table`: the most ``A^n'·|W - g_per(θ)|`` (the ROM word against the exact angle's
  value) can be, each cell's error weighted by the largest ``A^n'`` its ``x`` allows;
* :func:`read_table`: the range of ``A^n'·W`` itself, the float form and the word's error at
  the same ``x`` (tighter against Phong than the two apart: the ROM errs most on the lobe's
  flanks, the fit at its ends);
* :func:`diffuse_rom`: the cos ROM's error over the cells an ``|x_d|`` up to a bound reaches;
* :func:`wrap_error`: what a register that wraps past ``±π`` can add.
"""

import functools
import math

import numpy as np

from phongfx.core.format import Format
from phongfx.golden.spherical import rom_angles, rom_contents
from phongfx.golden.spherical_setup import solve_a

__all__ = ["PSI_CELLS", "X_CELLS", "cell_errors", "lobe_table", "lobe_range", "rom_table", "read_table",
           "read_range", "psi_max",
           "diffuse_rom", "wrap_error"]


def _window(y, function):
    """``g_per(y)``: the 2π-periodic ``cos₊²`` (``"cos2"``) or ``cos₊`` (``"cos"``)."""
    c = np.maximum(np.cos(y), 0.0)
    return c * c if function == "cos2" else c


def _range(lo, hi, function):
    """Exact ``(min, max)`` of ``g_per`` over ``[lo, hi]`` (shorter than 2π): unimodal on each
    window ``|y - 2πk| <= π/2`` and 0 between, so an extremum is at an end, or 1 at a peak
    ``2πk`` inside, or 0 where the interval meets ``[π/2, 3π/2] + 2πk``."""
    ends = np.stack([_window(lo, function), _window(hi, function)])
    two_pi = 2 * np.pi
    peak = np.floor(hi / two_pi) >= np.ceil(lo / two_pi)
    dark = np.floor((hi - np.pi / 2) / two_pi) >= np.ceil((lo - 3 * np.pi / 2) / two_pi)
    return np.where(dark, 0.0, ends.min(0)), np.where(peak, 1.0, ends.max(0))


#: Cells of the angle ``ψ`` between ``N_s`` and ``H`` on ``[0, π/2]`` in :func:`lobe_table`,
#: and of the in-plane angle ``x`` on ``[0, π/(2a)]`` it is maximized over.
PSI_CELLS, X_CELLS = 1 << 12, 1 << 11


@functools.lru_cache(maxsize=64)
def lobe_table(n_fed):
    """Per cell ``[ψ_j, ψ_j+1]`` of ``ψ ∈ [0, π/2]``, bounds ``(lo, hi)`` on the float form
    ``u = A^n'·g(a·x)`` of every pixel whose ``N_s·H = cos ψ`` (``n' = n_fed``, ``a = a(n')``).
    ``A·cos x = cos ψ`` with ``A <= 1`` leaves ``x ∈ [0, ψ]`` and ``A = cos ψ/cos x``: at
    ``x = 0`` the form is Phong's ``cos^n' ψ``, at ``x = ψ`` (a span through ``H``)
    Szirmay-Kalos's ``g(aψ)``.  ``u`` falls with ``ψ`` at fixed ``x``, ``g`` with ``x`` and
    ``cos ψ/cos x`` rises with it, so on a cell ``[x_a, x_b]`` of ``x``
    ``u <= min(1, cos ψ_j/cos x_b)^n'·g(a·x_a)`` and ``u >= (cos ψ_j+1/cos x_a)^n'·g(a·x_b)``
    (``x`` up to ``ψ_j+1``; ``u = 0`` past ``π/(2a)``, which ``x`` reaches once ``ψ`` does);
    past ``π/2`` every ``u`` is 0."""
    a = solve_a(n_fed)
    psi = np.linspace(0.0, np.pi / 2, PSI_CELLS + 1)
    x = np.linspace(0.0, np.pi / (2 * a), X_CELLS + 1)
    g = np.cos(np.minimum(a * x, np.pi / 2)) ** 2
    cos_x = np.cos(x)
    lo, hi = np.empty(PSI_CELLS), np.empty(PSI_CELLS)
    for start in range(0, PSI_CELLS, 256):
        j = np.arange(start, min(start + 256, PSI_CELLS))
        reach = x[None, :-1] <= psi[j + 1, None]  # cells with x_a <= ψ_j+1
        up = np.minimum(1.0, np.cos(psi[j, None]) / cos_x[None, 1:]) ** n_fed * g[None, :-1]
        down = np.minimum(1.0, np.cos(psi[j + 1, None]) / cos_x[None, :-1]) ** n_fed * g[None, 1:]
        hi[j] = np.max(np.where(reach, up, 0.0), axis=1)
        lo[j] = np.min(np.where(reach, down, np.inf), axis=1)
        # x = 0 is always there (the form cos^n' ψ), x past π/(2a) too once ψ reaches it (0)
        lo[j] = np.where(psi[j + 1] > x[-1], 0.0, np.minimum(lo[j], np.cos(psi[j + 1]) ** n_fed))
        hi[j] = np.maximum(hi[j], np.cos(psi[j]) ** n_fed)
    return _sparse(np.maximum(lo * (1 - 1e-12) - 1e-15, 0.0), np.minimum, 1.0), \
        _sparse(hi * (1 + 1e-12) + 1e-15, np.maximum, 0.0)


def _sparse(values, pick, pad):
    """Range-extremum table of ``values``: level ``l`` holds ``pick`` over ``2^l`` cells from each."""
    levels = [values]
    while (1 << len(levels)) <= len(values):
        last, step = levels[-1], 1 << (len(levels) - 1)
        levels.append(pick(last, np.concatenate([last[step:], np.full(step, pad)])))
    return np.stack(levels)


def _query(table, first, last):
    """``pick`` of cells ``first..last`` (arrays) of a :func:`_sparse` table."""
    level = np.floor(np.log2(np.maximum(last - first + 1, 1))).astype(np.int64)
    level = np.where((1 << (level + 1)) <= last - first + 1, level + 1, level)  # float log2 one low
    level = np.where((1 << level) > last - first + 1, level - 1, level)
    return table[level, first], table[level, last - (1 << level) + 1]


def _cells(h):
    """The first and last cells of ``ψ`` (clipped to ``[0, π/2]``) that ``cos ψ ∈ h`` meets."""
    cells = PSI_CELLS / (np.pi / 2)
    first = np.clip(np.floor(np.arccos(np.clip(h[1], -1, 1)) * cells), 0, PSI_CELLS - 1).astype(np.int64)
    last = np.clip(np.floor(np.arccos(np.clip(h[0], -1, 1)) * cells), 0, PSI_CELLS - 1).astype(np.int64)
    return first, last


def lobe_range(n_fed, h):
    """Per box ``(lo, hi)`` of the float form ``A^n'·g(a·x)`` where ``N_s·H`` lies in
    ``h = (lo, hi)`` (:func:`lobe_table`)."""
    low, high = lobe_table(n_fed)
    first, last = _cells(h)
    lo = np.minimum(*_query(low, first, last))
    hi = np.maximum(*_query(high, first, last))
    # past π/2 (N_s·H <= 0) the form is 0
    return np.where(h[0] <= 0, 0.0, lo), np.where(h[1] <= 0, 0.0, hi)


def wrap_error(n_fed, span_deg, delta):
    """``(bound, cut)``: the most a wrapped read adds, ``max g_per(y)`` over
    ``3π/2 - δ <= |y| <= π/2 + a·Γ + δ`` (0 when ``a·Γ`` is too short to wrap), and ``cut``,
    the ``N_s·H`` above which no pixel reaches ``|a·x| >= 3π/2 - δ`` (-inf when every one may)."""
    a = solve_a(n_fed)
    gamma = math.radians(span_deg)
    lo, hi = 1.5 * math.pi - delta, 0.5 * math.pi + a * gamma + delta
    if hi <= lo:
        return 0.0, -math.inf
    bound = float(_range(np.array([lo]), np.array([hi]), "cos2")[1][0]) if hi - lo < 2 * np.pi else 1.0
    x = lo / a
    # |x| <= π + Γ (φ ∈ (-π, π]); below 2π - x every |x| >= x has cos x <= cos x
    cut = math.cos(x) if x < math.pi / 2 and math.pi + gamma <= 2 * math.pi - x else -math.inf
    return bound, cut


@functools.lru_cache(maxsize=256)
def cell_errors(addr_bits, rom, function, delta):
    """Per ROM cell of ``θ >= 0`` (the ROM is even: cell ``c`` and ``-c-1`` hold one word)
    ``(lo, hi, err)``: its angles (radians) and ``max |W_c - g_per(y)|`` for ``y`` within
    ``delta`` of it (:func:`_range`), in order of angle."""
    word = rom_contents(addr_bits, rom, function) * Format.parse(rom).lsb
    half = math.pi / (1 << addr_bits)
    centre = rom_angles(addr_bits)
    keep = np.argsort(centre)[1 << (addr_bits - 1):]
    centre, word = centre[keep], word[keep]
    lo, hi = _range(centre - half - delta, centre + half + delta, function)
    err = np.maximum(word - lo, hi - word) * (1 + 1e-12) + 1e-15
    return centre - half, centre + half, err


@functools.lru_cache(maxsize=64)
def _binned(addr_bits, rom, n_fed, delta):
    """``(x, err)``: :data:`X_CELLS` bins of ``x ∈ [0, (π/2 + δ)/a]`` and per bin the largest
    error of the specular ROM's cells whose ``δ``-widened angles meet ``a·x`` there."""
    lo, hi, err = cell_errors(addr_bits, rom, "cos2", delta)
    a = solve_a(n_fed)
    x = np.linspace(0.0, (np.pi / 2 + delta) / a, X_CELLS + 1)
    first = np.clip(np.searchsorted(hi + delta, a * x[:-1], side="left"), 0, len(err) - 1)
    last = np.clip(np.searchsorted(lo - delta, a * x[1:], side="right") - 1, 0, len(err) - 1)
    return x, np.maximum(*_query(_sparse(err, np.maximum, 0.0), first, np.maximum(first, last)))


def _per_psi(x, bound, reduce):
    """Per cell ``j`` of ``ψ``, ``reduce`` over the bins with ``x_b <= ψ_j+1`` of
    ``bound(cos ψ_j, cos ψ_j+1)`` (each (J, X_CELLS)), in blocks of 256 cells."""
    psi = np.linspace(0.0, np.pi / 2, PSI_CELLS + 1)
    out = np.empty(PSI_CELLS)
    for start in range(0, PSI_CELLS, 256):
        j = np.arange(start, min(start + 256, PSI_CELLS))
        values = bound(np.cos(psi[j, None]), np.cos(psi[j + 1, None]))
        reach = x[None, :-1] <= psi[j + 1, None]
        out[j] = reduce(np.where(reach, values, np.inf if reduce is np.min else 0.0), axis=1)
    return out, psi


@functools.lru_cache(maxsize=64)
def rom_table(addr_bits, rom, n_fed, delta):
    """Per cell ``j`` of ``ψ``, a bound on ``A^n'·|W - g_per(a·x)|`` (the specular ROM), as a
    :func:`_sparse` max table.  A pixel's exact angle ``a·x`` with ``a·x > π/2 + δ`` reads a
    zero cell where ``g_per`` is 0 too (up to ``3π/2``: :func:`wrap_error`), so only
    ``x <= X = (π/2 + δ)/a`` counts, cut into :data:`X_CELLS` bins (:func:`_binned`); a bin
    takes its error times ``min(1, cos ψ_j/cos x_b+1)^n'`` (``A = cos ψ/cos x``), over the
    bins with ``x_b <= ψ_j+1``."""
    x, err = _binned(addr_bits, rom, n_fed, delta)
    out, _ = _per_psi(x, lambda c0, c1: np.minimum(1.0, c0 / np.cos(x[None, 1:])) ** n_fed * err[None, :],
                      np.max)
    return _sparse(out * (1 + 1e-12) + 1e-15, np.maximum, 0.0), float(err.max())


@functools.lru_cache(maxsize=64)
def read_table(addr_bits, rom, n_fed, delta):
    """Per cell ``j`` of ``ψ``, ``(lo, hi)`` :func:`_sparse` tables bounding ``A^n'·W``, the exact
    constant times the word the hardware reads: the float form and the ROM's error at one
    ``x`` together (:func:`lobe_table`'s bounds with ``g ± err`` of each bin of
    :func:`_binned`; ``W >= 0``; ``W = 0`` past ``X``, which ``x`` reaches once ``ψ`` does)."""
    x, err = _binned(addr_bits, rom, n_fed, delta)
    a = solve_a(n_fed)
    g = np.cos(np.minimum(a * x, np.pi / 2)) ** 2
    hi, psi = _per_psi(x, lambda c0, c1: np.minimum(1.0, c0 / np.cos(x[None, 1:])) ** n_fed
                       * (g[None, :-1] + err[None, :]), np.max)
    lo, _ = _per_psi(x, lambda c0, c1: np.minimum(1.0, c1 / np.cos(x[None, :-1])) ** n_fed
                     * np.maximum(0.0, g[None, 1:] - err[None, :]), np.min)
    lo = np.where(psi[1:] > x[-1], 0.0, lo)
    return (_sparse(np.maximum(lo * (1 - 1e-12) - 1e-15, 0.0), np.minimum, 1.0),
            _sparse(hi * (1 + 1e-12) + 1e-15, np.maximum, 0.0))


def read_range(tables, h):
    """Per box ``(lo, hi)`` of ``A^n'·W`` where ``N_s·H ∈ h`` (:func:`read_table`'s ``tables``);
    where ``N_s·H <= 0`` the angle is past ``π/2 + δ`` (the caller checks ``a``) and ``W = 0``."""
    first, last = _cells(h)
    lo = np.minimum(*_query(tables[0], first, last))
    hi = np.maximum(*_query(tables[1], first, last))
    return np.where(h[0] <= 0, 0.0, lo), np.where(h[1] <= 0, 0.0, hi)


def psi_max(table, h):
    """Per box the largest entry of a :func:`_sparse` max table over the ``ψ`` cells that
    ``N_s·H ∈ h = (lo, hi)`` meets."""
    first, last = _cells(h)
    return np.maximum(*_query(table, first, last))


@functools.lru_cache(maxsize=64)
def _diffuse_prefix(addr_bits, rom, delta):
    lo, _, err = cell_errors(addr_bits, rom, "cos", delta)
    return lo - delta, np.maximum.accumulate(err)


def diffuse_rom(addr_bits, rom, delta, cosine):
    """Per box a bound on ``A_d·|W - g_per(x_d)|`` (the diffuse ROM) where ``N_s·L >= cosine``
    (B,): ``|x_d| <= acos(cosine)`` when it is positive (``A_d <= 1``), so only the cells whose
    ``δ``-widened angles start below that count; all of them otherwise."""
    start, prefix = _diffuse_prefix(addr_bits, rom, delta)
    reach = np.where(cosine > 0, np.arccos(np.clip(cosine, 0.0, 1.0)), np.inf)
    index = np.clip(np.searchsorted(start, reach, side="right") - 1, 0, len(prefix) - 1)
    return prefix[index]

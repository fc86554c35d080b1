"""The bounding method of the spherical interpolation unit (Szirmay-Kalos et al. 2000, Figure 12).

Per light the unit computes ``spec = Q(C_q·W(θ_hw))`` and ``diff = Q(C_dq·W_cos(θ_d,hw))``:
``C = A^n'`` (``n' = 4n``, equation 18) and ``C_d = A_d`` rounded to ``c``, ``θ_hw = Q(b) +
k·Q(s)`` the angle register (units of π, wrapping) at pixel ``k`` of a span, ``W`` the ROM word
of its cell.  The exact setup gives ``θ(k) = a·x`` with ``A·cos x = N_s·H`` (``N_s`` the slerp
of the span's end normals at ``t = k/(L - 1)``, :mod:`.span`; ``a = a(n')``, §4), so
``|θ_hw - θ| <= δ = π·2^-(f+1)·L_max`` (``f`` the register's fraction bits, ``L_max``
:func:`~phongfx.certify.span.max_pixels`).  The unit's own float form is
``A^n'·g(a·x)``, ``g(y) = cos²y`` for ``|y| <= π/2``, else 0 (0 on a dark span, whose ``C``
the host loads as 0), and ``(N_s·L)₊`` for the diffuse channel.  Per term:

* **rounding** (hardware against ``A^n'·W``, the exact constant times the word read): the
  product's rounding and ``|C_q - C|·W``; the diffuse channel's also holds ``A_d·|W - g_per|``
  (:func:`~phongfx.certify.lobe.diffuse_rom`, ``g_per`` the 2π-periodic ``cos₊`` a wrapping
  register reads, each cell's angle widened by ``δ``);
* **approximation** (``A^n'·W`` against Phong at ``N̂``): ``N_s`` is within ``ε``
  (:func:`~phongfx.certify.span.slerp_gap`) of ``N̂``, so ``N_s·H`` lies in the box's ``N̂·H``
  range widened by ``ε`` (:func:`~phongfx.certify.span.widen`), over which
  :func:`~phongfx.certify.lobe.read_table` bounds ``A^n'·W``: equation 19's ``cos²(a·x)`` for
  ``cos^n' x`` and the word's error at the same ``x`` together; against ``max(R̂·L, 0)^n``
  (Lyon's appendix: ``(N·H)^4n`` stands for ``(R·L)^n``) both rise with their cosine.  Where
  the register can wrap (``a·Γ > π``: a span that meets the lobe ``|a·x| <= π/2`` runs to
  ``|a·x| <= π/2 + aΓ``, and past ``3π/2`` reads the lit cells again) :func:`~phongfx.certify.lobe.wrap_error`
  is added on the boxes whose ``N_s·H`` is low enough.  The diffuse term is ``ε``-Lipschitz:
  ``|N_s·L - N̂·L| <= ε``.  Against the unit's own float form (``"self"``) the ROM's error
  (:func:`~phongfx.certify.lobe.rom_table`) and a wrap are the rounding part instead, and the
  specular approximation is 0.

The per-light terms sum at the outputs as :func:`~phongfx.certify.outputs.light_rounding`
says (its backside gate: the hardware's ``diff > 0``), over boxes of ``N̂``
(:mod:`.sphere`) refined by :func:`~phongfx.certify.branch.bound_boxes`.  Lights and viewer
at infinity, the viewer along +z (the unit's setup takes ``V = (0, 0, 1)``).
"""

import math

import numpy as np

from phongfx.golden.spherical import rom_contents
from phongfx.golden.spherical_setup import solve_a
from phongfx.scene.span_inputs import VIEWER, halfway

from .branch import bound_boxes, cases
from .figures import directional_why_not
from .interval import rounding_error
from .lobe import cell_errors, diffuse_rom, lobe_range, psi_max, read_range, read_table, rom_table, wrap_error
from .outputs import coefficient_tables, light_rounding
from .regions import limits
from .span import max_pixels, slerp_gap, widen
from .sphere import cover, frame, projection

__all__ = ["Spherical", "SPHERICAL"]


def _coded(fmt):
    """Largest distance from a value in ``[0, 1]`` to its code (rounded, saturated)."""
    top = fmt.max_raw * fmt.lsb
    return max(fmt.lsb / 2, 1.0 - top)


class _Copy:
    """One copy of the unit (one light): its constant error parts and its tables per ``n``."""

    def __init__(self, unit, pixels, span_deg, fed):
        theta, rom, c, out = (unit.fmt(name) for name in ("theta", "rom", "c", "out"))
        self.unit, self.rom, self.fed = unit, str(rom), fed
        #: the register's drift: Q(b) and k·Q(s), k <= L_max - 1, each within half an lsb (units of π)
        self.delta = math.pi * theta.lsb / 2 * pixels * (1 + 1e-12)
        product = rounding_error(c.mul(rom), out, unit.rounding) + max(0.0, 1.0 - out.max_raw * out.lsb)
        w_max = float(rom_contents(unit.addr_bits, self.rom, "cos2").max()) * rom.lsb
        self.e_s, self.e_d = product + _coded(c) * w_max, product + _coded(c)
        # a wrapped read: the lit cell's value and its word's error
        worst = float(cell_errors(unit.addr_bits, self.rom, "cos2", self.delta)[2].max())
        self.wraps = {}
        for n, v in fed.items():
            bound, cut = wrap_error(v, span_deg, self.delta)
            self.wraps[n] = (bound + worst if bound else 0.0, cut)
        #: past ψ = π/2 the angle a·x passes π/2 + δ (a zero cell, no ROM error) unless a is near 1
        self.near = {n: solve_a(v) * math.pi / 2 < math.pi / 2 + self.delta for n, v in fed.items()}

    def specular(self, boxes, h, against):
        """Per box ``(e_s, lo, hi)`` where ``N_s·H ∈ h``: against ``"self"`` the hardware's
        distance from the float form (the ROM's and a wrap's error in it) and the float form's
        range (:func:`~phongfx.certify.lobe.lobe_range`); against Phong the distance from
        ``A^n'·W`` (the product's and ``C``'s rounding) and the range of ``A^n'·W``
        (:func:`~phongfx.certify.lobe.read_range`, a wrap's read added)."""
        e_s, lo, hi = np.full(len(boxes), self.e_s), np.zeros(len(boxes)), np.zeros(len(boxes))
        for n, v in self.fed.items():
            pick = boxes.n == n
            part = (h[0][pick], h[1][pick])
            bound, cut = self.wraps[n]
            wrap = np.where(part[0] > cut, 0.0, bound)
            past = part[0] <= 0
            if against == "self":
                table, top = rom_table(self.unit.addr_bits, self.rom, v, self.delta)
                rom = np.where(past & self.near[n], top, psi_max(table, part))
                e_s[pick] += rom + wrap
                lo[pick], hi[pick] = lobe_range(v, part)
            else:
                lo[pick], hi[pick] = read_range(read_table(self.unit.addr_bits, self.rom, v, self.delta), part)
                hi[pick] = np.where(past & self.near[n], 1.0, hi[pick]) + wrap
        return e_s, lo, hi

    def diffuse(self, cosine):
        """Per box the hardware's distance from ``(N_s·L)₊`` where ``N_s·L >= cosine``."""
        return self.e_d + diffuse_rom(self.unit.addr_bits, self.rom, self.delta, cosine)


def _span_why_not(domain):
    """Why the spherical unit's own assumptions miss ``domain`` (None when they hold)."""
    if not np.allclose(domain.camera[1], VIEWER):
        return "the spherical unit's setup takes the viewer along +z"
    if domain.max_span_angle_deg >= 180.0:
        return "span ends may be 180° apart, where Phong's interpolated normal is undefined"
    return None


class Spherical:
    """Bounds the ``spherical`` unit (module docstring), one copy per light."""

    #: what the certificate names as its method
    name = "interval"
    #: what of a domain its bound reads: every limit (:func:`~phongfx.certify.regions.limits`)
    limits = staticmethod(limits)

    def why_not(self, shader, domain):
        """None when this method bounds ``shader`` on ``domain``, else one sentence why not."""
        return directional_why_not(domain) or _span_why_not(domain)

    def bound(self, shader, spec, domain, *, max_boxes=300_000, enough=None, resume=None):
        """``(bound_levels, parts)`` over ``domain`` (:func:`~phongfx.certify.branch.bound_boxes`)."""
        basis = frame(VIEWER)
        lights = [np.asarray(vector, dtype=np.float64) for _, vector, _ in domain.lights]
        # the host's setup takes a span under sin γ = 1e-9 as not turning: 1e-8 covers its N·H
        eps = slerp_gap(domain.max_span_angle_deg) + 1e-8
        pixels = max_pixels(spec, domain)
        fed = {n: 4.0 * n for n, _ in cases(domain)}  # the units are fed n' = 4n
        copies = [_Copy(unit, pixels, domain.max_span_angle_deg, fed) for unit in shader.units]
        tables = coefficient_tables(shader.blend)
        levels, against = shader.blend.levels, spec.requirement.against

        def errors(boxes, floor):  # one bound for every box: the floor saves nothing
            m = boxes.material
            rounding = np.abs(tables[0][0] - tables[1][0])[m].copy()
            approximation = np.zeros_like(rounding)
            gate = np.zeros(len(boxes))
            for i, (light, copy) in enumerate(zip(lights, copies)):
                q = projection(boxes, basis, light)
                # N_s is within ε of N̂: its N·L within ε of q, its N·H in the widened range
                e_d = copy.diffuse(q[0] - eps)
                d_ideal = np.clip(q[1] + eps, 0.0, 1.0)
                margin = np.maximum(e_d, copy.delta) + eps
                e_s, lo, hi = copy.specular(boxes, widen(projection(boxes, basis, halfway(light)), eps), against)
                add, off = light_rounding(tables, m, i, levels, d_ideal + e_d, e_d, hi + e_s, e_s, q, margin,
                                          ideal=(d_ideal, hi))
                rounding += add
                gate = np.maximum(gate, off)
                shift_d = np.where(q[1] + eps > 0, eps, 0.0)
                if against == "self":
                    shift_s = np.zeros(len(boxes))
                else:
                    c = projection(boxes, basis, light, reflected=True)
                    n = boxes.n.astype(np.float64)
                    g_lo, g_hi = np.maximum(c[0], 0.0) ** n, np.maximum(c[1], 0.0) ** n
                    shift_s = np.maximum(np.maximum(hi - g_lo, g_hi - lo), 0.0)
                de, se = tables[1][1][m, i], tables[1][2][m, i]
                approximation += (de * shift_d[:, None] + se * shift_s[:, None]) * (1 + 1e-12)
            return rounding, approximation, set(), gate

        boxes = cover(domain.view_cos_min, 1.0, cases(domain))
        bound, parts = bound_boxes(errors, domain, max_boxes=max_boxes, enough=enough, boxes=boxes, resume=resume)
        parts.update(slerp_gap_rad=eps, max_span_pixels=pixels)
        return bound, parts


SPHERICAL = Spherical()

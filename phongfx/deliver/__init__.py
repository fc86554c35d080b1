"""What ships with a compiled core, beside its Verilog: everything a user needs to drop it
into a design of their own.

* ``phongfx.deliver.contract`` — the input contract: for every port of the compiled top,
  what the host computes (which vector, in which space, unit or not, per pixel or per span
  end, who normalizes), the meaning of ``a`` and ``init`` where present, the material
  index → name map with each material's constants, and what ``r``, ``g``, ``b`` are and how
  they are rounded.  The top's header, the manifest's ``"contract"`` and
  ``docs/integration.rst`` print it.
* ``phongfx.deliver.constraints`` — the clock the design was compiled for, as an SDC
  (generic and ASIC), an ECP5 LPF, an iCE40 nextpnr clock script and a clock-only SDC for
  nextpnr ``--sdc``.
* ``phongfx.deliver.fusesoc`` — a FuseSoC CAPI2 ``.core`` file: the RTL, the testbench
  and their targets.
* :mod:`phongfx.deliver.component` — the compiled core as an Amaranth
  ``wiring.Component`` with ``lib.stream`` interfaces (``load_core`` of a compiled
  folder); :mod:`phongfx.deliver.manifest` reads the folder's ``manifest.json`` back.
* :mod:`phongfx.deliver.page` — ``DIR/report.html``, the compiled folder on one
  self-contained page (its pixel-rate section :mod:`~phongfx.deliver.rates`, its charts
  :mod:`~phongfx.deliver.chart`, its HTML pieces :mod:`~phongfx.deliver.markup`).

The layer sits above ``phongfx.render`` (it reads scene specs and configs, and may
render) and below ``phongfx.explore`` (whose compiler calls it when it writes a compiled
folder).  Importing ``phongfx.deliver`` loads none of its modules: the names below are
imported on first use.
"""

from importlib import import_module

#: public name -> the module it lives in
_HOMES = {"input_contract": "phongfx.deliver.contract", "contract_lines": "phongfx.deliver.contract",
          "ShadingCore": "phongfx.deliver.component", "load_core": "phongfx.deliver.component",
          "ManifestError": "phongfx.deliver.manifest", "read_manifest": "phongfx.deliver.manifest",
          "clock_of": "phongfx.deliver.constraints", "write_constraints": "phongfx.deliver.constraints",
          "write_flow": "phongfx.deliver.fusesoc", "write_report": "phongfx.deliver.page"}
__all__ = list(_HOMES)


def __getattr__(name):
    if name not in _HOMES:
        raise AttributeError(f"module 'phongfx.deliver' has no attribute {name!r}")
    return getattr(import_module(_HOMES[name]), name)

"""Datapath configurations: plain data saying which formats each block uses.

A configuration is a frozen dataclass of format strings (Lyon's ``n.m`` / ``Sn.m``),
integers and names.  It is validated when built, so both the golden function and the
Amaranth component of a block see only sound parameters, and it declares the block's
ports (:attr:`BlockConfig.inputs`, :attr:`BlockConfig.outputs`): name -> (format,
lanes), lanes being 3 for an X, Y, Z vector.  The golden model, the component's
payload layouts and the checking harness all take port widths from there.

The default formats are our reconstruction of Lyon's Figure 7, whose bit annotations
are lost from our copy; each block's docstring says why each default was chosen.

One module per block, named like the block's files in ``golden/``, ``hdl/`` and
``sim/stimulus/``; :mod:`~phongfx.config.base` holds what they share (the rounding,
pipeline and field checks, the port declarations, the vector width) and
:mod:`~phongfx.config.datapath` the whole datapaths of Figures 7, 8 and 5.

Port names keep the papers' letters, and ``n`` is two of them: the **normal** on the
ports of the LIRP (``n0``, ``n1`` in, ``n`` out), the normalizer, reflect, diffuse and
the halfway unit; the **shininess** on those of difference, Schlick's unit, the
Blinn–Phong baseline and the datapaths (whose normals are ``n0``, ``n1``; Figure 8's
root unit takes ``m = √n``).

May import: ``phongfx.core``.
"""

from .base import MAX_PIPELINE, BlockConfig
from .blend import BlendConfig
from .blinn import BlinnConfig
from .conventional import ConventionalConfig
from .datapath import SPECULAR_UNITS, DatapathConfig, fig7_config, fig8_config, halfway_config
from .difference import DifferenceConfig
from .diffuse import DiffuseConfig
from .euler import EulerConfig
from .gouraud import GouraudConfig
from .halfway import HALFWAY_VARIANTS, HalfwayConfig
from .lirp import LirpConfig
from .normalize import NormalizeConfig
from .reflect import ReflectConfig
from .root import RootConfig
from .schlick import SchlickConfig
from .shader import ShaderConfig
from .shape import ShapeConfig
from .spherical import SphericalConfig

__all__ = [
    "BlockConfig", "LirpConfig", "NormalizeConfig", "ReflectConfig", "DifferenceConfig",
    "ShapeConfig", "DiffuseConfig", "RootConfig", "SchlickConfig", "SphericalConfig", "HalfwayConfig", "HALFWAY_VARIANTS",
    "EulerConfig", "GouraudConfig", "BlinnConfig", "ConventionalConfig", "BlendConfig",
    "DatapathConfig", "SPECULAR_UNITS", "fig7_config", "fig8_config", "halfway_config",
    "ShaderConfig", "MAX_PIPELINE",
]

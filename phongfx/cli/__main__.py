"""``python -m phongfx.cli``: the ``phongfx`` command line, without the installed script."""

import sys

from . import main

sys.exit(main())

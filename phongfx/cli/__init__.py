"""The ``phongfx`` command line.

``phongfx blocks`` lists the datapath blocks; ``phongfx verilog NAME -o FILE`` emits
one as Verilog; ``phongfx sim NAME`` checks it cycle by cycle against its golden
model; ``phongfx compile SCENE.toml -o DIR`` compiles a scene to its cheapest datapath;
``phongfx certify METHOD|DIR`` bounds a design's error over a scene's whole input domain;
``phongfx render`` is ``make sim``: Lyon's scene through Figure 7, golden and
RTL.  ``--set field=value`` (repeatable; ``shape.k=1`` inside a composite) changes
the block's configuration.  Errors go to stderr with exit code 2 (bad input) or 1
(a mismatch).

The top of the house: it may import every layer.  :mod:`~phongfx.cli.parser` holds the
arguments, :mod:`~phongfx.cli.commands` one function per subcommand (``compile``'s in
:mod:`~phongfx.cli.compile`), :mod:`~phongfx.cli.settings` the ``--set`` parsing; :func:`main` here runs a command and
turns every kind of bad input into one line and an exit code.
"""

import os
import sys
import warnings

from phongfx.explore.synth.fpga import SynthError

from .commands import MAX_SIZE
from .parser import build_parser
from .settings import apply_settings

__all__ = ["main", "apply_settings", "MAX_SIZE"]


def _os_error(error):
    """``path: reason`` of a failed read or write (the target, not the temporary, of a rename)."""
    where = error.filename2 if error.filename2 is not None else error.filename
    return f"{where}: {error.strerror}" if where is not None and error.strerror else str(error)


def main(argv=None):
    """Run the command line; returns the exit code (0 ok, 1 mismatch, 2 bad input, 130 interrupted).

    Bad input of any kind (usage, ``ValueError`` from a config, a config whose formats
    overflow in the golden model, a file that cannot be read or written, a frame too
    large for memory) is one ``phongfx: error:`` line on stderr and exit code 2,
    never a traceback (``tests/cli/test_bad_input.py`` fuzzes this).
    """
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as stop:  # --help (0) or a usage error (2, already printed)
        return 0 if stop.code is None else stop.code
    try:
        return args.run(args)
    except KeyboardInterrupt:  # Ctrl-C: one line, not a traceback; temporary folders are gone
        # a design interrupted mid-elaboration leaves Amaranth modules that warn, once collected
        # with this traceback, that they were never used: not news to whoever pressed Ctrl-C
        warnings.filterwarnings("ignore", message=".*created but never used")
        print("phongfx: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # output piped into `head` and the like: not an error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except ValueError as error:
        print(f"phongfx: error: {error}", file=sys.stderr)
        return 2
    except OverflowError as error:
        # golden.fixed.FixedOverflowError: formats a config accepted that cannot hold a value
        # the block computes (e.g. an output without the integer bit 1.0 needs)
        print(f"phongfx: error: overflow: {error}; widen that format", file=sys.stderr)
        return 2
    except OSError as error:  # missing input, unwritable or non-directory output folder
        print(f"phongfx: error: {_os_error(error)}", file=sys.stderr)
        return 2
    except MemoryError as error:
        print(f"phongfx: error: out of memory ({error}); ask for a smaller problem", file=sys.stderr)
        return 2
    except SynthError as error:  # the tools failed (or the design does not fit): not bad input
        first, _, tail = str(error).partition("\n")
        print(f"phongfx: error: synthesis failed: {first}", file=sys.stderr)
        if tail:
            print(tail, file=sys.stderr)
        return 1

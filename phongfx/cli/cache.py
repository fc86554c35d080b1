"""``phongfx cache``: where the per-user cache is, what it holds, and emptying it.

The cache (:mod:`phongfx.core.cache`) keeps Verilator builds, synthesis, timing and proof
results and the scene compiler's journal between runs; this command is how a user finds
it (``--info``: the folder, then entries and size per tool) and frees it (``--clear``).
"""

from phongfx.core.cache import ENVIRONMENT, clear, root, usage

__all__ = ["add_arguments", "cmd_cache", "size_text"]


def add_arguments(p):
    """``phongfx cache``'s arguments, on its subparser ``p``."""
    what = p.add_mutually_exclusive_group()
    what.add_argument("--info", action="store_true",
                      help="the cache folder, then entries and size per tool (the default)")
    what.add_argument("--clear", action="store_true", help="remove everything in the cache folder")


def size_text(count):
    """``count`` bytes in the largest unit that keeps it at 1 or more (``"12.3 MB"``)."""
    for unit in ("B", "kB", "MB", "GB"):
        if count < 1000 or unit == "GB":
            return f"{count:.0f} {unit}" if unit == "B" else f"{count:.1f} {unit}"
        count /= 1000
    raise AssertionError("unreachable")


def cmd_cache(args):
    if args.clear:
        freed = clear()
        print(f"cleared {root()} ({size_text(freed)} freed)")
        return 0
    rows = usage()
    print(f"{root()}  (set {ENVIRONMENT} to move it)")
    for name, entries, size in rows:
        print(f"  {name:10s} {entries:6d} entries  {size_text(size):>9s}")
    total = sum(size for *_, size in rows)
    print(f"  {'total':10s} {sum(n for _, n, _ in rows):6d} entries  {size_text(total):>9s}")
    return 0

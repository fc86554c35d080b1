"""Behaviour identity check: the outputs of two versions of phongfx, compared.

A restructuring must not change what the tool computes.  This script captures, through
the command line only (so it runs against any version that has these commands):

* the Verilog of every block ``phongfx blocks`` lists (``phongfx verilog``);
* the compiled designs of the example scenes (``phongfx compile --no-check``): every
  Verilog file and the manifest (not ``report.html``: :data:`VIEWS`);
* ``make sim``'s outputs (``phongfx render``): both PNGs and the summary;
* ``phongfx figure9``: its PNGs and JSON;
* ``phongfx tables NAME --json`` for the tables that need no synthesis (``--synth-tables``
  adds ``cost`` and ``pipeline``, which synthesize dozens of designs).

Verilog is compared with its ``src`` attributes stripped (they name source files and
lines, which a move changes); JSON with timing fields removed (``seconds``, ``*_per_second``
and the like); PNGs byte for byte.

    python -m bench.identity capture DIR             # this checkout's outputs into DIR
    python -m bench.identity capture DIR --ref REV   # a git revision's, installed aside
    python -m bench.identity compare DIR_A DIR_B     # exit 1 on any difference
    python -m bench.identity check --ref REV         # capture both, then compare
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys

__all__ = ["capture", "compare", "normalize_verilog", "normalize_json", "listed_blocks"]

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ("lyon-balls", "torus", "local-mesh")
TABLES = ("lyon", "szirmay", "schlick", "hast", "extremes")
SYNTH_TABLES = ("cost", "pipeline")

#: JSON keys whose values are measurements of time, or provenance ("cached": whether a
#: synthesis result came from the cache), not results
TIMING = re.compile(r"(seconds|elapsed|per_second|_time$|^time$|wall|duration|speed|mpx_s|^cached$)")
#: Top-level JSON keys changed on purpose since the layout revision 58cdcc7, with why:
#: compared apart, reported as intended rather than as differences.
INTENDED = {
    os.path.join("tables", "pipeline.json"): {"source": "named a GitHub issue; now says what the table is"},
    os.path.join("tables", "extremes.json"): {"source": "named a GitHub issue; now says what the table is"},
}
#: a run folder's random suffix (``build/synth/.<key>.<random>/``)
TEMPORARY = re.compile(r"(/\.[0-9a-f]+)\.[A-Za-z0-9_]+/")
#: where a failed run's folder is kept since the per-user cache (``synth/failed/<key>/``):
#: the same run folder as the one above, under another name
FAILED = re.compile(r"/failed/([0-9a-f]+)/")
SRC = re.compile(r"\(\* src = \"[^\"]*\" \*\)\s*")
#: the compile journal's file (``build/compile/<key>.jsonl``): its key hashes the package's
#: source, so that a changed model never reuses a line, and any change of the code renames it
JOURNAL = re.compile(r"/compile/[0-9a-f]+\.jsonl$")
#: Output files that are views of other outputs, left out of a capture's files: a compiled
#: folder's ``report.html`` is made from its manifest and PNGs (compared themselves) and shows
#: seconds (the certificate's) that differ from run to run; a revision from before the page
#: has none, which is no change of behaviour either.
VIEWS = ("report.html",)


def normalize_verilog(text):
    """Verilog without ``src`` attributes (source paths and line numbers)."""
    return "\n".join(line.rstrip() for line in SRC.sub("", text).splitlines() if line.strip())


def normalize_json(value, root=None):
    """``value`` with every timing field dropped, recursively, and the capture folder
    ``root`` in strings (a failed synthesis names its log) written ``<capture>``."""
    if isinstance(value, dict):
        return {k: normalize_json(v, root) for k, v in value.items() if not TIMING.search(str(k))}
    if isinstance(value, list):
        return [normalize_json(v, root) for v in value]
    if isinstance(value, str) and root:
        value = FAILED.sub(r"/.\1.<random>/", value.replace(os.path.abspath(root), "<capture>"))
        return JOURNAL.sub("/compile/<source key>.jsonl", TEMPORARY.sub(r"\1.<random>/", value))
    return value


def listed_blocks(text):
    """The block names of ``phongfx blocks``'s output ``text``: the first word of each line
    that gives a latency (a block's config wraps onto indented lines, a note follows)."""
    return [match.group(1) for match in re.finditer(r"^(\S+) +latency\b", text, re.M)]


def _run(python, env, cwd, args, log):
    print(f"  phongfx {' '.join(args)}", file=sys.stderr, flush=True)
    with open(log, "a") as out:
        out.write(f"$ phongfx {' '.join(args)}\n")
        out.flush()
        done = subprocess.run([python, "-m", "phongfx.cli", *args], cwd=cwd, env=env,
                              stdout=subprocess.PIPE, stderr=out, text=True)
    if done.returncode not in (0,):
        raise SystemExit(f"phongfx {' '.join(args)} exited {done.returncode}; see {log}")
    return done.stdout


def _install(ref, where):
    """``ref`` of this repository installed (not editable) into ``where``/site."""
    tree, site = os.path.join(where, "tree"), os.path.join(where, "site")
    if os.path.isdir(site):
        return tree, site
    if os.path.isdir(tree):
        subprocess.run(["git", "worktree", "remove", "--force", tree], cwd=ROOT, check=False)
    subprocess.run(["git", "worktree", "add", "--detach", tree, ref], cwd=ROOT, check=True)
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-deps",
                    "--target", site, tree], check=True)
    return tree, site


PARTS = ("verilog", "compile", "sim", "figure9", "tables")


def capture(out, ref=None, synth_tables=False, parts=PARTS, synth_cache=None):
    """Write this checkout's (or ``ref``'s) outputs into the folder ``out`` (only ``parts``).

    ``synth_cache``: another capture whose synthesis cache is copied in first.  Its keys
    hash each design's RTLIL and config, so a table row served from it (``"cached": true``)
    shows that the design is the same as the one synthesized there, at no tool run."""
    out = os.path.abspath(out)
    os.makedirs(out, exist_ok=True)
    env = dict(os.environ)
    source = ROOT
    if ref is not None:
        source, site = _install(ref, os.path.join(out, "install"))
        env["PYTHONPATH"] = site
    work = os.path.join(out, "work")  # the commands' cwd: no source folder shadows the install
    os.makedirs(work, exist_ok=True)
    # the per-user cache in work/build: where revisions before it kept their caches (build/synth ...)
    env["PHONGFX_CACHE"] = os.path.join(work, "build")
    log = os.path.join(out, "commands.log")
    if synth_cache is not None:
        shutil.copytree(os.path.join(synth_cache, "work", "build", "synth"),
                        os.path.join(work, "build", "synth"), dirs_exist_ok=True)
    python = sys.executable
    run = lambda *args: _run(python, env, work, list(args), log)  # noqa: E731

    unknown = sorted(set(parts) - set(PARTS))
    if unknown:
        raise SystemExit(f"unknown part {unknown[0]!r}; parts: {', '.join(PARTS)}")
    if "verilog" in parts:
        names = listed_blocks(run("blocks"))
        os.makedirs(os.path.join(out, "verilog"), exist_ok=True)
        for name in names:
            run("verilog", name, "-o", os.path.join(out, "verilog", f"{name}.v"))
    if "compile" in parts:
        # the manifest records the scene file's path: the same relative one in both captures
        shutil.copytree(os.path.join(source, "scenes"), os.path.join(work, "scenes"), dirs_exist_ok=True)
    for scene in SCENES if "compile" in parts else ():
        run("compile", f"scenes/{scene}.toml", "-o", f"compile/{scene}", "--no-check", "--quiet")
    if "sim" in parts:
        run("render", "--out", "sim", "--quiet")
    if "figure9" in parts:
        run("figure9", "--out", "figure9", "--quiet")
    tables = (TABLES + (SYNTH_TABLES if synth_tables else ())) if "tables" in parts else ()
    os.makedirs(os.path.join(out, "tables"), exist_ok=True)
    for table in tables:
        text = run("tables", table, "--json", "--out", f"tables/{table}")
        with open(os.path.join(out, "tables", f"{table}.json"), "w") as f:
            f.write(text)
    return out


def _files(root):
    found = {}
    for base in ("verilog", "tables", os.path.join("work", "compile"), os.path.join("work", "sim"),
                 os.path.join("work", "figure9")):
        top = os.path.join(root, base)
        for folder, _, files in os.walk(top):
            for name in files:
                if name in VIEWS:
                    continue
                path = os.path.join(folder, name)
                found[os.path.relpath(path, root)] = path
    return found


def _same(path, a, b, root_a, root_b):
    """Whether the captures' files ``a`` and ``b`` (at ``path`` in both) agree; the intended
    changes of :data:`INTENDED` in them are printed, not compared."""
    if a.endswith(".v"):
        return normalize_verilog(open(a).read()) == normalize_verilog(open(b).read())
    if a.endswith(".json"):
        before, after = (json.load(open(name)) for name in (a, b))
        for key, why in INTENDED.get(path, {}).items():
            old, new = before.pop(key, None), after.pop(key, None)
            if old != new:
                print(f"intended: {path} {key}: {old!r} -> {new!r} ({why})")
        return normalize_json(before, root_a) == normalize_json(after, root_b)
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def compare(a, b, common_only=False, ignore=()):
    """(files compared, [differences]) between two captures (``common_only``: files that
    only one of them has are not differences, for a capture of some parts only; paths
    starting with one of ``ignore`` are skipped).  A difference in a key of
    :data:`INTENDED` is listed as ``intended: ...``, not counted."""
    fa, fb = ({k: v for k, v in _files(x).items() if not k.startswith(tuple(ignore))} for x in (a, b))
    if common_only:
        fa = {k: v for k, v in fa.items() if k in fb}
        fb = {k: v for k, v in fb.items() if k in fa}
    differences = [f"only in {a}: {p}" for p in sorted(set(fa) - set(fb))]
    differences += [f"only in {b}: {p}" for p in sorted(set(fb) - set(fa))]
    common = sorted(set(fa) & set(fb))
    differences += [f"differs: {p}" for p in common if not _same(p, fa[p], fb[p], a, b)]
    return len(common), differences


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.identity", description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("capture")
    p.add_argument("out")
    p.add_argument("--ref", help="git revision to install aside and capture (default: this checkout)")
    p.add_argument("--synth-tables", action="store_true", help="also tables cost and pipeline (slow)")
    p.add_argument("--parts", nargs="+", default=PARTS, choices=PARTS, help="what to capture (default all)")
    p.add_argument("--synth-cache", metavar="CAPTURE", help="copy that capture's synthesis cache in first")
    p = sub.add_parser("compare")
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--common-only", action="store_true", help="compare only the files both captures have")
    p = sub.add_parser("check")
    p.add_argument("--ref", required=True, help="git revision to compare this checkout with")
    p.add_argument("--out", default="build/identity", help="folder for both captures")
    p.add_argument("--synth-tables", action="store_true")
    p.add_argument("--head", default="head", help="subfolder of --out for this checkout's capture")
    p.add_argument("--parts", nargs="+", default=PARTS, choices=PARTS,
                   help="what to capture of this checkout (default all); only those are compared")
    args = parser.parse_args(argv)
    if args.command == "capture":
        capture(args.out, args.ref, args.synth_tables, args.parts, args.synth_cache)
        return 0
    if args.command == "check":
        base = os.path.join(args.out, "ref")
        if os.path.isdir(base) and not os.path.isfile(os.path.join(base, "done")):
            raise SystemExit(f"{base} holds an unfinished capture (no 'done' file): wait for it, "
                             f"or remove the folder to capture {args.ref} again")
        if not os.path.isdir(base):
            capture(base, args.ref, args.synth_tables)
            open(os.path.join(base, "done"), "w").close()
        here = os.path.join(args.out, args.head)
        shutil.rmtree(here, ignore_errors=True)
        capture(here, None, args.synth_tables, args.parts, base if args.synth_tables else None)
        args.a, args.b, args.common_only = base, here, tuple(args.parts) != PARTS
        args.ignore = () if args.synth_tables else tuple(f"tables/{t}" for t in SYNTH_TABLES)
    count, differences = compare(args.a, args.b, args.common_only, getattr(args, "ignore", ()))
    for line in differences:
        print(line)
    print(f"{count} file(s) compared, {len(differences)} difference(s)")
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())

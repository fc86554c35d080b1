"""``phongfx certify``: a design's worst input (the witness) and a sound bound on its error
over a scene's whole input domain (the certificate).

Two kinds of target: a method of :data:`phongfx.core.methods.METHODS` at widths given by
``--set`` (``phongfx certify fig7 --set vec_frac=10 --scene scenes/torus.toml``), against the
domain of ``--scene`` or, without one, of exact per-pixel normals of one ``--n`` under one
directional light (a unit sphere's front, :data:`PER_PIXEL`); or a compiled output folder,
whose ``manifest.json`` names the scene file (relative to the folder: the command works from
any directory), the chosen method and its widths (read by
:func:`phongfx.deliver.manifest.read_manifest`, which checks its version).

Exit codes: 0 the bound meets the requirement; 1 the witness already fails it (or a replayed
witness does not reproduce); 3 only the bound misses it (or none was obtained); 2 bad input.
"""

import json
import math
import os
import sys

from phongfx.core.words import levels

__all__ = ["PER_PIXEL", "add_arguments", "cmd_certify", "parse_widths", "per_pixel_scene", "exit_code"]

#: The scene of a method certified without ``--scene``: one unit sphere of exact per-pixel
#: normals (``span = 0``), shininess ``{n}``, one directional light toward ``{light}``, the
#: viewer at infinity along +z, diffuse 0.6 and specular 0.4 (the example torus' material).
PER_PIXEL = """name = "per-pixel n={n}"
[camera]
at = "infinity"
direction = [0, 0, 1]
[[lights]]
direction = [{light}]
[materials.surface]
kd = 0.6
ks = 0.4
[[objects]]
type = "lyon_spheres"
material = "surface"
radius = 16
shininess = [{n}]
span = 0
[output]
bits = 8
[requirement]
max_error_levels = 1.0
against = "phong"
"""


def add_arguments(p):
    """``phongfx certify``'s arguments, on its subparser ``p``."""
    p.add_argument("target", metavar="METHOD|DIR",
                   help="a method (fig7, fig8, conventional, ...), a compiled output folder or its manifest.json")
    p.add_argument("--set", action="append", metavar="WIDTH=VALUE",
                   help="a width of METHOD, as the compiler names them (vec_frac=10, x2_frac, shape_t_frac, k, "
                        "order, coef ...); the others at the method's defaults")
    p.add_argument("--scene", help="certify METHOD against this scene file's domain")
    p.add_argument("--n", type=int, help="without --scene: the one shininess of the per-pixel domain (default 16)")
    p.add_argument("--light", metavar="X,Y,Z",
                   help="without --scene: direction toward the directional light (default 1,1,1)")
    p.add_argument("--max-error", type=float, metavar="LEVELS",
                   help="instead of the scene's requirement.max_error_levels (without --scene: 1)")
    p.add_argument("--bound", choices=("auto", "exhaustive", "interval"), default="auto",
                   help="how to bound: exhaustive enumeration of the input codes (exact per-pixel normals, "
                        "directional lights, viewer at infinity), interval arithmetic with domain splitting, "
                        "or auto: exhaustive where it applies (default)")
    p.add_argument("--samples", type=int, metavar="N",
                   help="domain points of the witness search (default the domain's final_samples)")
    p.add_argument("--seed", type=int, help="seed of the witness search (default the domain's, offset)")
    p.add_argument("--gappa", action="store_true",
                   help="Figure 7: also prove the rounding error of its chain from D·D to the specular amount "
                        "with Gappa (Debian's gappa), over the domain's n")
    p.add_argument("--coq", metavar="FILE", help="with --gappa: write Gappa's proof as a Coq script to FILE")
    p.add_argument("--replay", action="store_true",
                   help="DIR: re-evaluate the manifest's witness through the golden model and print it")
    p.add_argument("--json", action="store_true", help="the result as JSON on stdout")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")


def parse_widths(method, settings):
    """``{width: int}`` of ``--set`` values for ``method``, each checked against its range."""
    from phongfx.explore.compile.search import width_params

    widths = width_params(method, "phong")
    params = {}
    for setting in settings or []:
        name, equals, text = setting.partition("=")
        if not equals:
            raise ValueError(f"--set wants width=value, not {setting!r}")
        if name not in widths:
            raise ValueError(f"--set {name}: {method} has no width {name!r}; widths: {', '.join(widths)}")
        lo, hi = widths[name][1]
        try:
            value = int(text)
        except ValueError:
            value = None
        if value is None or not lo <= value <= hi:
            raise ValueError(f"--set {name} must be an integer in {lo}..{hi}, not {text!r}")
        params[name] = value
    return params


def _light(text):
    try:
        values = [float(x) for x in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise ValueError(f"--light must be three numbers X,Y,Z, not {text!r}")
    return ", ".join(repr(v) for v in values)


def per_pixel_scene(n=16, light="1,1,1"):
    """The :class:`~phongfx.scene.file.SceneSpec` of :data:`PER_PIXEL`."""
    from phongfx.scene.file import N_MAX, parse_scene

    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= N_MAX:
        raise ValueError(f"--n must be an integer in 1..{N_MAX}, not {n!r}")
    return parse_scene(PER_PIXEL.format(n=n, light=_light(light)), name="per-pixel")


def exit_code(witness, certificate, max_error_levels):
    """1 when the witness fails the requirement, else 0 when the bound meets it, else 3."""
    if witness is not None and witness["error_levels"] > max_error_levels:
        return 1
    return 0 if certificate.certified else 3


def _check(args):
    for name, lo in (("samples", 1), ("seed", 0)):
        value = getattr(args, name)
        if value is not None and value < lo:
            kind = "a positive" if lo else "a non-negative"
            raise ValueError(f"--{name} must be {kind} integer, not {value}")
    if args.coq and not args.gappa:
        raise ValueError("--coq writes Gappa's proof: add --gappa")
    if args.max_error is not None and not (args.max_error > 0 and math.isfinite(args.max_error)):
        raise ValueError(f"--max-error must be a positive number of display levels, not {args.max_error:g}")


def _manifest(folder):
    """The manifest of a compiled folder (:func:`phongfx.deliver.manifest.read_manifest`, its
    version checked) with a design to certify."""
    from phongfx.deliver.manifest import ManifestError, manifest_path, read_manifest

    data = read_manifest(folder)
    if data.get("chosen") is None:
        raise ManifestError(f"{manifest_path(folder)}: the compile chose no design (chosen is null); "
                            f"nothing to certify")
    if not data.get("widths"):
        raise ManifestError(f"{manifest_path(folder)}: field 'widths' is missing; compile the scene again")
    return data


def _target(args):
    """``(method, params, spec, manifest)`` of the command line's target."""
    from phongfx.core.methods import METHODS
    from phongfx.scene.file import load_scene

    if os.path.isdir(args.target):
        for name in ("set", "scene", "n", "light"):
            if getattr(args, name) is not None:
                raise ValueError(f"--{name} applies to a METHOD target; {args.target} is a compiled folder, "
                                 f"whose manifest gives the design and the scene")
        from phongfx.deliver.manifest import scene_file

        data = _manifest(args.target)
        return data["chosen"], dict(data["widths"]), load_scene(scene_file(data, args.target)), data
    if args.replay:
        raise ValueError("--replay re-evaluates a compiled folder's witness; give DIR, not a method")
    if args.target not in METHODS:
        raise ValueError(f"METHOD|DIR must be a method ({', '.join(METHODS)}) or a compiled output folder, "
                         f"not {args.target!r}")
    params = parse_widths(args.target, args.set)
    if args.scene is not None:
        for name in ("n", "light"):
            if getattr(args, name) is not None:
                raise ValueError(f"--{name} sets up the per-pixel domain without --scene; the scene gives it")
        return args.target, params, load_scene(args.scene), None
    return args.target, params, per_pixel_scene(16 if args.n is None else args.n, args.light or "1,1,1"), None


def _bound(kind, method, params, spec, domain, analysis, progress):
    """The :class:`~phongfx.certify.certificate.Certificate` by ``kind`` (``auto``: exhaustive
    where it applies, else interval)."""
    from phongfx.certify import exhaustive

    if kind == "auto":
        kind = "exhaustive" if exhaustive.applicable(method, spec, domain) is None else "interval"
        if kind == "exhaustive":
            certificate = exhaustive.exhaustive(method, params, spec, domain, analysis=analysis, progress=progress)
            if certificate.bound_levels is not None:
                return certificate
            kind = "interval"  # too many codes: bound by intervals instead
    if kind == "exhaustive":
        return exhaustive.exhaustive(method, params, spec, domain, analysis=analysis, progress=progress)
    from phongfx.certify.bound import certify

    return certify(method, params, spec, domain, analysis=analysis)


def _gappa(args, method, params, domain, analysis):
    """``{"amount", "levels", "n", "coq"}``: Gappa's bound on Figure 7's chain (--gappa)."""
    from phongfx.certify.gappa import GappaError, gappa_bound, specular_levels
    from phongfx.explore.compile.run import build

    values = [n for _, ns in domain.materials for n in ns]
    config = build(method, params, analysis)
    try:
        amount, _ = gappa_bound(config, {"n": (min(values), max(values))}, coq=args.coq)
    except GappaError as error:
        raise ValueError(f"--gappa: {error}") from None
    return {"amount": amount, "levels": specular_levels(amount, config.blend), "n": [min(values), max(values)],
            "coq": args.coq}


def _report(result, out=None):
    out = out or sys.stdout
    cert, witness, req = result["certificate"], result["witness"], result["requirement"]
    print(f"{result['method']} at {result['params'] or 'its default widths'} on {result['scene']} "
          f"(requirement {levels(req['max_error_levels'])} against {req['against']})", file=out)
    print(f"domain: {result['domain']['description']}", file=out)
    if witness is not None:
        print(f"witness: {levels(witness['error_levels'])} ({witness['unrounded']:.3f} unrounded): outputs "
              f"{[witness['outputs'][c] for c in 'rgb']} against {witness['reference_levels']}, "
              f"found by {witness['found_by']}", file=out)
        print(f"  point: {json.dumps(witness['point'])}", file=out)
    if result["gappa"]:
        g = result["gappa"]
        print(f"gappa: Figure 7c-d's rounding moves the specular amount by at most {g['amount']:.3g} for n in "
              f"{g['n'][0]}..{g['n'][1]}: {g['levels']:.3f} levels at the outputs"
              + (f" (Coq proof: {g['coq']})" if g["coq"] else ""), file=out)
    verdict = "certified" if cert["certified"] else "not certified"
    bound = "none" if cert["bound_levels"] is None else f"{cert['bound_levels']:.3f} levels"
    print(f"bound: {bound} ({cert['method']}, {cert['seconds']:.1f} s): {verdict}"
          + (f": {cert['why']}" if cert["why"] else ""), file=out)


def _replay(args, method, params, spec, data):
    from phongfx.explore.compile.witness import replay

    witness = data.get("witness")
    if not witness:
        raise ValueError(f"{args.target}/manifest.json has no witness to replay")
    again = replay(witness, method, params, spec)
    if args.json:
        print(json.dumps({"witness": witness, "replay": again}, indent=2, default=float))
    else:
        print(f"{method} at {params}: witness of {levels(witness['error_levels'])} replayed: "
              f"{levels(again['error_levels'])} ({again['unrounded']:.3f} unrounded), outputs {again['outputs']} "
              f"against {again['reference_levels']}; "
              f"{'reproduced' if again['matches'] else 'NOT reproduced'}")
    if not again["matches"]:
        print(f"phongfx: the witness of {args.target} does not reproduce", file=sys.stderr)
        return 1
    return 1 if again["error_levels"] > spec.requirement.max_error_levels else 0


def cmd_certify(args):
    from phongfx.certify.bounding import bounding
    from phongfx.explore.compile.analysis import analyse
    from phongfx.explore.compile.witness import search
    from phongfx.scene.domain import domain as scene_domain
    from phongfx.scene.file import with_requirement
    from phongfx.scene.geometry import frames

    _check(args)
    if os.path.basename(args.target) == "manifest.json" and os.path.isfile(args.target):
        args.target = os.path.dirname(args.target) or "."  # the folder the manifest describes
    method, params, spec, data = _target(args)
    if args.gappa and not getattr(bounding(method), "gappa", False):
        raise ValueError(f"--gappa proves Figure 7's chain (fig7), not {method}'s")
    if args.max_error is not None:
        spec = with_requirement(spec, args.max_error)
    if args.replay:
        return _replay(args, method, params, spec, data)

    def progress(text):
        if not args.quiet:
            print(f"certify: {text}", file=sys.stderr, flush=True)
    geometries = frames(spec)
    analysis, domain = analyse(spec, geometries), scene_domain(spec, geometries)
    certificate = _bound(args.bound, method, params, spec, domain, analysis, progress)
    # enumeration's worst input is the witness; a search (asked for, or without enumeration)
    # measures against the exact normal instead of the code's direction: the worse one is kept
    witness = certificate.parts.get("witness") if certificate.method == "exhaustive" else None
    if witness is None or args.samples is not None:
        found = search(method, params, spec, domain, samples=args.samples, seed=args.seed, progress=progress,
                       analysis=analysis)
        if witness is None or (found["error_levels"], found["unrounded"]) > (witness["error_levels"],
                                                                            witness["unrounded"]):
            witness = found
    result = {"method": method, "params": params, "scene": spec.path or spec.name,
              "requirement": {"max_error_levels": spec.requirement.max_error_levels,
                              "against": spec.requirement.against},
              "domain": domain.as_dict(), "witness": witness, "certificate": certificate.as_dict(),
              "gappa": _gappa(args, method, params, domain, analysis) if args.gappa else None}
    code = exit_code(witness, certificate, spec.requirement.max_error_levels)
    if args.json:
        print(json.dumps({**result, "exit": code}, indent=2, default=float))
    else:
        _report(result)
    return code

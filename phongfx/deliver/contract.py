"""The input contract of a compiled core: what the host feeds each input port, and what comes out.

A compiled top (:mod:`phongfx.hdl.top`) names its ports and their formats; this says what
they *mean*, read from the design the compiler chose (its :class:`~phongfx.config.ShaderConfig`)
and the scene file it was compiled for (:class:`~phongfx.scene.file.SceneSpec`): for every
input, the quantity the host computes, in which space, whether it is a unit vector and who
normalizes it (host or core), whether it changes per pixel or is a span end (or a per-span
setup loaded with ``init``), and how it is quantized; the material index → name map with each
material's constants as the scene file gives them and as the blend holds them; and what
``r``, ``g``, ``b`` are and how they are rounded.

The semantics are those of the compiler's streams (:mod:`phongfx.explore.compile.units`, which
calls :mod:`phongfx.scene.span_inputs` and :func:`phongfx.sim.stimulus.datapath.encode`) on
the frames of :mod:`phongfx.scene.geometry`:

* every vector is in eye space: x to the right, y up, z toward the viewer; the camera looks
  down −z (orthographic image), the lights and camera stay put and a scene's frames turn its
  objects (:func:`phongfx.scene.mesh.project`);
* a span is one scanline run of one triangle; its end normals ``N0``, ``N1`` are the
  triangle's vertex normals interpolated along its edges to the span's first and last pixel
  centres, normalized (:func:`phongfx.scene.mesh.rasterize`);
* Lyon's datapaths (Lyon 1993, Figures 5, 7, 8) take the span ends and ``a`` per pixel and
  interpolate and normalize themselves (Figure 7a's LIRP, "Approximate Normalization"); the
  conventional and Blinn units take the interpolated normal as it is and normalize it; the
  spherical unit (Szirmay-Kalos et al. 2000, Figure 12) takes a per-span setup on each span's
  first pixel.

:func:`input_contract` builds the dict the manifest keeps as ``"contract"``;
:func:`contract_lines` prints it as the paragraphs of the top's header.
"""

from phongfx.config import ConventionalConfig, DatapathConfig, ShaderConfig, SphericalConfig
from phongfx.core.methods import METHODS, get_method

__all__ = ["SPACE", "QUANTIZE", "input_contract", "contract_lines", "error_paragraph"]

#: The space every vector is given in (module docstring).
SPACE = ("eye space: x to the right, y up, z toward the viewer; the camera looks down -z (orthographic "
         "image); lights and camera are fixed in it, the scene's frames turn the objects")
#: How the host turns a real value into a port's code.
QUANTIZE = ("a real x goes to the code floor(x * 2^m + 1/2) of the port's format (round half up), "
            "saturated to the format's range (a component of exactly 1 in a format without room for "
            "it takes the largest code)")


def _vec(vector):
    return "(" + ", ".join(f"{float(x):.4g}" for x in vector) + ")"


def _entry(quantity, meaning, *, space=None, unit=None, rate="pixel", by=None, light=None):
    """One input's contract: ``rate`` is ``"pixel"`` (a value per pixel), ``"span end"`` (the
    pixel's span's end value, the same on its every pixel), ``"constant"`` (one value for the
    whole frame) or ``"span setup"`` (loaded on a span's first pixel, zero elsewhere)."""
    return {"quantity": quantity, "meaning": meaning, "space": space, "unit_vector": unit, "rate": rate,
            "normalized_by": by, "light": light}


def _toward(spec, index):
    """``(phrase, local)``: what "toward light ``index``" is in ``spec``."""
    light = spec.lights[index]
    if light.kind == "point":
        return f"light {index}, a point light at {_vec(light.vector)} (scene units)", True
    return f"light {index}, a directional light along {_vec(light.vector)}", False


def _viewer(spec):
    path = spec.frames.camera_path
    if spec.camera.kind == "point":
        where = "the frame's camera_path position" if path else f"the camera at {_vec(spec.camera.vector)}"
        return f"{where} (scene units)", True
    return f"the camera at infinity along {_vec(spec.camera.vector)}", False


def _end(which, target):
    return (f"the unit vector from the surface point at the {which} pixel of the pixel's span toward "
            f"{target}; the host normalizes it, the core interpolates it with a and normalizes per pixel")


def datapath_entry(name, config, spec, light, n_scale):
    """The contract of input ``name`` of Lyon's datapath ``config`` (the ``contract`` face of
    ``fig7``, ``fig8`` and ``halfway``; one copy holds every light, fed ``n`` itself)."""
    if name in ("n0", "n1"):
        which = "first" if name == "n0" else "last"
        return _entry(name.upper(), f"the unit surface normal at the {which} pixel of the pixel's span (a mesh's "
                      "vertex normals interpolated along the triangle's edges, normalized; a sphere's own "
                      "normal); the same on every pixel of the span", space="eye", unit=True, rate="span end",
                      by="host")
    if name == "a":
        return _entry("a", "the pixel's place in its span: k/(length-1) for its k-th pixel counting from 0 (0 on "
                      "the first, 1 on the last, 0 on a one-pixel span); the core forms N' = (1-a)*N0 + a*N1 "
                      "(and L, V likewise where they come as span ends) and normalizes it (Lyon 1993, Figure 7a "
                      "and 'Approximate Normalization')")
    if name in ("n", "m"):
        _, _, top = config.shininess
        what = ("m = round(sqrt(n)) of the pixel's shininess n (Figure 8 takes m)" if name == "m" else
                "the pixel's shininess n itself" + config.unit.shininess_note(config))
        return _entry(name, f"{what}: an integer 1..{top}, from the pixel's material (lyon_spheres: its "
                      "sphere's)")
    if name == "v":
        target, _ = _viewer(spec)
        return _entry("V", f"the unit vector toward the viewer, {target}: the same on every pixel", space="eye",
                      unit=True, rate="constant", by="host")
    if name in ("v0", "v1"):
        target, _ = _viewer(spec)
        return _entry(name.upper(), _end("first" if name == "v0" else "last", target), space="eye",
                      unit=True, rate="span end", by="host")
    index, _, end = name[1:].partition("_")
    target, _ = _toward(spec, int(index))
    if end:
        return _entry(f"L{index}_{end}", _end("first" if end == "0" else "last", target), space="eye",
                      unit=True, rate="span end", by="host", light=int(index))
    return _entry(f"L{index}", f"the unit vector toward {target}: the same on every pixel", space="eye",
                  unit=True, rate="constant", by="host", light=int(index))


_INTERPOLATED = ("N' = (1-a)*N0 + a*N1, the pixel's normal interpolated along its span between the span "
                 "ends' unit normals (a = k/(length-1) at its k-th pixel), NOT normalized: the core "
                 "normalizes it")


def per_pixel_entry(name, config, spec, light, n_scale):
    """The contract of input ``name`` of a conventional or Blinn unit computing ``light`` (their
    methods' ``contract`` face), fed ``n' = n_scale*n``."""
    if name == "normal":
        return _entry("N'", _INTERPOLATED, space="eye", unit=False, by="core")
    target, local = _toward(spec, light) if light is not None else ("every light", False)
    if name == "n":
        scaled = (f"n' = {n_scale}*n, {n_scale} times the pixel's shininess n (Lyon 1993, appendix: "
                  f"(N.H)^(4n) stands for Phong's (R.V)^n)" if n_scale != 1 else
                  "the pixel's shininess n itself (Phong's (R.V)^n)")
        return _entry("n'" if n_scale != 1 else "n", f"{scaled}: an integer 1..{config.n_max}")
    if not isinstance(config, ConventionalConfig):  # Blinn's unit (the conventional one is a kind of it)
        if name == "light":
            return _entry(f"L{light}", f"the exact unit vector from the pixel's surface point toward {target}",
                          space="eye", unit=True, rate="pixel" if local else "constant", by="host", light=light)
        viewer, near = _viewer(spec)
        return _entry(f"H{light}", f"H = normalize(L + V) at the pixel, V the unit vector toward {viewer}",
                      space="eye", unit=True, rate="pixel" if local or near else "constant", by="host",
                      light=light)
    if name == "light":
        if config.local_light:
            return _entry(f"L{light}", f"the unit vector from the pixel's surface point toward {target}, which "
                          f"the core normalizes again: {_ANY_LENGTH}", space="eye", unit=False, by="core",
                          light=light)
        return _entry(f"L{light}", f"the unit vector toward {target}: the same on every pixel", space="eye",
                      unit=True, rate="constant", by="host", light=light)
    viewer, _ = _viewer(spec)
    if config.local_viewer:
        return _entry("V", f"the unit vector from the pixel's surface point toward {viewer}, which the core "
                      f"normalizes again: {_ANY_LENGTH}", space="eye", unit=False, by="core")
    return _entry("V", f"the unit vector toward {viewer}: the same on every pixel", space="eye", unit=True,
                  rate="constant", by="host")


#: What a local L or V of the conventional unit may be besides the unit vector it is fed.
_ANY_LENGTH = ("any length up to 1 gives its direction, but the error measured and certified is for unit length "
               "(a shorter vector's codes round relatively coarser)")


#: The spherical unit's loads (Szirmay-Kalos et al. 2000, equations 15-19, section 4).
_SPHERICAL = {
    "init": ("init", "1 on the first pixel of a span, which loads b, s, c, bd, sd, cd; 0 on every other pixel, "
             "where the core steps its angles by s and sd"),
    "b": ("b", "the specular angle at the span's first pixel, -a(n')*phi, in units of pi (wrapping at +-1): "
          "N.H = A*cos(t*gamma - phi) along the span (N from N0 to N1, H = normalize(L + V)), a(n') the "
          "paper's lobe width for n' = 4n"),
    "s": ("s", "the specular angle's step per pixel, a(n')*gamma/(length-1) (0 on a one-pixel span), units of pi"),
    "c": ("C", "the specular constant A^n' (0 on a span whose lobe stays dark): the unit gives C*cos^2(angle)"),
    "bd": ("bd", "the diffuse angle at the span's first pixel, -phi of N.L = A*cos(t*gamma - phi), units of pi"),
    "sd": ("sd", "the diffuse angle's step per pixel, gamma/(length-1), units of pi"),
    "cd": ("Cd", "the diffuse constant A of N.L = A*cos(t*gamma - phi), the same on the three lanes (the blend "
           "reads lane x): the unit gives Cd*max(cos(angle), 0)"),
}


def spherical_entry(name, config, spec, light, n_scale):
    """The contract of input ``name`` of the spherical unit computing ``light`` (its method's
    ``contract`` face; ``n' = 4n`` is folded into its span setup)."""
    quantity, meaning = _SPHERICAL[name]
    return _entry(quantity if name == "init" else f"{quantity}{light}", meaning,
                  rate="pixel" if name == "init" else "span setup", light=None if name == "init" else light)


def _unit_entry(method, name, unit, spec, copy, n_scale):
    """The contract of input ``name`` of the unit copy ``copy`` (its light; None: shared) of
    ``method``: its ``contract`` face (:data:`phongfx.core.methods.METHODS`)."""
    faces = get_method(method)
    if not faces.has("contract"):
        shipped = ", ".join(name for name, m in METHODS.items() if m.has("contract"))
        raise ValueError(f"method must be one the compiler ships ({shipped}), not {method!r}")
    return faces.load("contract")(name, unit, spec, copy, n_scale)


def _materials(config, spec):
    """Index, name and constants of each material, as the scene file gives them and the blend holds them."""
    blend = config.blend
    out = []
    for index, (name, m) in enumerate(spec.materials.items()):
        n = None if m.n_lo is None else (m.n_lo if m.n_lo == m.n_hi else [m.n_lo, m.n_hi])
        users = [o for o in spec.objects if o.material == name]
        ambient, diffuse, specular = blend.coefficients(index)
        out.append({"index": index, "name": name, "kd": m.kd, "ks": m.ks, "ka": m.ka, "colour": list(m.colour),
                    "n": n, "objects": [o.kind for o in users],
                    "n_per_object": [list(o.params["shininess"]) for o in users if "shininess" in o.params],
                    "codes": {"format": str(blend.coef_format), "ambient": list(ambient),
                              "diffuse": [list(d) for d in diffuse], "specular": [list(s) for s in specular]}})
    return out


def _outputs(config, spec):
    blend, bits = config.blend, config.blend.bits
    top = (1 << bits) - 1
    gate = " * [diff_i > 0]" if blend.gate else ""
    diff = "diff_i*D_ic + " if blend.diff else ""
    meaning = (f"the display level 0..{top} of the pixel's channel c: {blend.rounding.replace('_', ' ')} "
               f"of A_c + sum over lights i of ({diff}spec_i*S_ic{gate}), saturated at {top}, where diff_i and "
               f"spec_i are the unit's terms of light i (diff_i = max(N.L, 0)) and A_c, D_ic, S_ic the "
               f"material's codes (ka*M_c, kd*M_c*L_ic, ks*M_c*L_ic times {top}, {blend.coef_frac} fraction "
               f"bit(s), round half up): the sum is already in display levels, rounded once")
    target = "true Phong" if spec.requirement.against == "phong" else "the method's own float form"
    return [{"port": f"out_{c}", "format": str(blend.out_format), "quantity": c,
             "meaning": meaning,
             "reference": f"floor(I_c * {top} + 1/2) of {target}'s intensity I_c clipped to [0, 1], within "
                          f"{spec.requirement.max_error_levels:g} level(s) (the compile's requirement)"}
            for c in "rgb"]


def _stream(config):
    if isinstance(config.units[0], SphericalConfig):
        return ("one vector per pixel of every span, hidden pixels included (the unit steps along the span), "
                "spans in scanline order (rows top to bottom), pixels left to right; the results of hidden "
                "pixels are dropped by the host")
    return ("one vector per visible pixel, in any order: the core keeps nothing from one pixel to the next")


def input_contract(config, spec, method, *, n_scale, ports=None):
    """The contract of the shader ``config`` compiled for ``method`` from the scene ``spec``.

    ``n_scale``: the compiler feeds the unit ``n' = n_scale*n`` (4 for the ``(N.H)^n'`` units).
    ``ports``: the top's port list (:func:`phongfx.hdl.top.port_map`), to name each input's
    ports; None builds it.  Returns ``{"method", "space", "quantize", "stream", "inputs",
    "outputs", "materials", "lights", "notes"}``, JSON-able: ``inputs`` one entry per shader
    input (its top ports, format, quantity, meaning, space, unit_vector, rate, normalized_by,
    light), ``materials`` one per material in the scene file's order (the ``material`` port's
    codes)."""
    if not isinstance(config, ShaderConfig):
        raise ValueError(f"config must be a ShaderConfig (a compiled shader), not {type(config).__name__}")
    if ports is None:
        from phongfx.hdl.top import port_map
        ports = port_map(config)
    owners = {}
    for copy, unit in enumerate(config.units):
        for name in unit.inputs:
            light = None if name in config.shared else copy  # a shared input serves every light
            owners[config.port_name(copy, name)] = (name, unit, light)
    inputs = []
    for field, (fmt, lanes) in config.inputs.items():
        if field == "material":
            names = ", ".join(f"{i} = {name}" for i, name in enumerate(spec.materials))
            entry = _entry("material", f"the index of the pixel's material in the scene file's order: {names}")
        else:
            name, unit, light = owners[field]
            entry = _unit_entry(method, name, unit, spec, light, n_scale)
        inputs.append({"field": field, "ports": [p["name"] for p in ports if p["field"] == field
                                                  and p["direction"] == "input"],
                       "format": str(fmt), "lanes": lanes, **entry})
    notes = []
    unit = config.units[0]
    if isinstance(unit, DatapathConfig) and unit.shininess is None:
        notes.append(f"No shininess port: n = {unit.shininess_const} is built into the hardware (the scene has "
                     f"one n).")
    if "material" not in config.inputs:
        notes.append(f"No material port: the scene has one material, {next(iter(spec.materials))}, built into "
                     f"the blend.")
    if config.copies > 1:
        turns = ("" if config.interval == 1 else
                 f" (the core's units take the lights in turn, {config.interval} clocks per pixel)")
        notes.append(f"One unit per light{turns}: c<i>_ ports feed light i's; unprefixed ones feed every light.")
    lights = [{"index": i, "kind": light.kind, ("position" if light.kind == "point" else "direction"):
               list(light.vector), "rgb": list(light.rgb)} for i, light in enumerate(spec.lights)]
    return {"method": method, "scene": spec.name, "space": SPACE, "quantize": QUANTIZE, "stream": _stream(config),
            "inputs": inputs, "outputs": _outputs(config, spec), "materials": _materials(config, spec),
            "lights": lights, "notes": notes}


def _ports_text(ports):
    """``in_n0_x/y/z`` for a vector's ports, the name for a scalar."""
    if len(ports) == 3 and all(p.endswith(s) for p, s in zip(ports, ("_x", "_y", "_z"))):
        return f"{ports[0][:-2]}_{{x,y,z}}"
    return ", ".join(ports)


def contract_lines(contract):
    """The header's "Contract" paragraphs of ``contract`` (:func:`input_contract`), one string each."""
    out = [f"Contract: what the host feeds the core ({contract['method']}, compiled for the scene "
           f"{contract['scene']}).",
           f"Space: {contract['space']}.", f"Quantize: {contract['quantize']}.", f"Stream: {contract['stream']}."]
    for entry in contract["inputs"]:
        facts = [f for f in (entry["space"] and f"{entry['space']} space",
                             {True: "unit", False: "not unit"}.get(entry["unit_vector"]),
                             f"per {entry['rate']}" if entry["rate"] != "constant" else "constant",
                             entry["normalized_by"] and f"normalized by the {entry['normalized_by']}") if f]
        named = "" if entry["meaning"].startswith(entry["quantity"]) else f"{entry['quantity']}, "
        out.append(f"{_ports_text(entry['ports'])} ({entry['format']}): {named}{entry['meaning']} "
                   f"[{'; '.join(facts)}].")
    for m in contract["materials"]:
        n = m["n"]
        if n is None:
            n = "per object (" + "; ".join(", ".join(map(str, each)) for each in m["n_per_object"]) + ")"
        elif isinstance(n, list):
            n = f"any integer in {n[0]}..{n[1]}"
        out.append(f"Material {m['index']} = {m['name']}: kd {m['kd']:g}, ks {m['ks']:g}, ka {m['ka']:g}, colour "
                   f"{_vec(m['colour'])}, n {n}; blend codes ({m['codes']['format']}) ambient "
                   f"{m['codes']['ambient']}, diffuse {m['codes']['diffuse']}, specular {m['codes']['specular']}.")
    for light in contract["lights"]:
        where = light.get("position") or light.get("direction")
        out.append(f"Light {light['index']}: {light['kind']} {'at' if 'position' in light else 'along'} "
                   f"{_vec(where)}, RGB intensity {_vec(light['rgb'])}.")
    outputs = contract["outputs"]
    out.append(f"{', '.join(o['port'] for o in outputs)} ({outputs[0]['format']}): "
               f"{outputs[0]['meaning']}; reference: {outputs[0]['reference']}.")
    return out + list(contract["notes"])


def error_paragraph(certificate, requirement):
    """The header's "Error" paragraph: how far ``out_r/g/b`` may be from the reference and how
    that is known: ``certificate`` (a :meth:`~phongfx.certify.certificate.Certificate.as_dict`,
    None for a compile by measurement alone, ``--sampled``), ``requirement`` the manifest's."""
    within = f"{requirement['max_error_levels']:g} level(s) of the reference"
    if certificate and certificate["certified"]:
        return (f"Error: certified: for every input of the scene's domain out_r/g/b are within {within}: a "
                f"sound bound of {certificate['bound_levels']:.3f} levels before the reference's rounding "
                f"({certificate['method']}; phongfx certify).")
    why = f" ({certificate['why']})" if certificate and certificate.get("why") else ""
    return (f"Error: measured, not certified{why}: within {within} on the frames, a sample of the scene's "
            f"domain and the worst input a search found (phongfx compile --sampled; phongfx certify bounds it).")

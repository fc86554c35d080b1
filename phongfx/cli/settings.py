"""``--set field=value``: a block's configuration changed from the command line.

A setting names a field of the block's config dataclass (``out=S1.12``) or, inside a
composite block, a field of one of its sub-configs (``shape.k=1``); the value is parsed
as the field's type (``true`` or ``false``, in any case, for a ``bool`` field such as
``local_light``; an integer for an ``int`` field; the text itself otherwise: the config's
own checks parse formats and names and refuse bad ones).  A config may also
take derived settings (its ``DERIVED_SETTINGS``, integers): ``vec_frac=12`` on a
datapath sets every connected direction-vector format at once.  They are applied after
the field settings, whatever their order on the command line, so that a field such as
``local_viewer=True`` which adds connected formats is set before the width spreads to them.
"""

import dataclasses

from phongfx.core.registry import get_block

__all__ = ["apply_settings", "configured_block", "dry_run"]


def apply_settings(config, settings):
    """``config`` with ``["field=value", "sub.field=value", "vec_frac=12"]`` applied (types
    follow the field; derived settings last)."""
    derived = []
    for setting in settings:
        if "=" not in setting:
            raise ValueError(f"--set wants field=value, not {setting!r}")
        path, text = setting.split("=", 1)
        if path in getattr(config, "DERIVED_SETTINGS", ()):
            derived.append((path, text))
        else:
            config = _set(config, path.split("."), text, path)
    for name, text in derived:
        config = config.replace(**{name: _integer(name, text, name)})
    return config


def _integer(name, text, path):
    try:
        return int(text)
    except ValueError:
        raise ValueError(f"--set {path}: {name} must be an integer, not {text!r}") from None


def _boolean(name, text, path):
    word = text.strip().lower()
    if word not in ("true", "false"):
        raise ValueError(f"--set {path}: {name} must be true or false, not {text!r}")
    return word == "true"


def _set(config, parts, text, path):
    names = [f.name for f in dataclasses.fields(config)]
    if parts[0] not in names:
        derived = getattr(config, "DERIVED_SETTINGS", ())
        also = f"; derived settings: {', '.join(derived)}" if derived else ""
        raise ValueError(f"--set {path}: {type(config).__name__} has no field {parts[0]!r}; "
                         f"fields: {', '.join(names)}{also}")
    current = getattr(config, parts[0])
    if len(parts) == 1 and dataclasses.is_dataclass(current):
        # a whole sub-config cannot be parsed from one string; point at its fields instead
        fields = ", ".join(f"{parts[0]}.{f.name}" for f in dataclasses.fields(current))
        raise ValueError(f"--set {path}: {parts[0]} is a {type(current).__name__}; set one of its "
                         f"fields instead: {fields}")
    if len(parts) > 1:
        if not dataclasses.is_dataclass(current):
            raise ValueError(f"--set {path}: {parts[0]} has no sub-fields")
        value = _set(current, parts[1:], text, path)
    elif isinstance(current, bool):
        value = _boolean(parts[0], text, path)
    elif not isinstance(current, int):
        value = text
    else:
        value = _integer(parts[0], text, path)
    return dataclasses.replace(config, **{parts[0]: value})


def configured_block(name, settings):
    """Registry block ``name`` with ``settings`` (``--set`` values, may be None) applied
    and dry-run (:func:`dry_run`)."""
    block = get_block(name)
    if settings:
        block = get_block(name, config=apply_settings(block.config, settings))
        dry_run(block, settings)
    return block


def dry_run(block, settings):
    """Run the golden model once on the block's directed vectors, so that a setting which
    makes an intermediate format too wide for int64, or a declared-safe quantize overflow,
    is reported against the ``--set`` that caused it rather than the intermediate's name."""
    try:
        block.golden(block.stimulus(count=0, seed=0))
    except ValueError as error:
        raise ValueError(f"--set {' '.join(settings)}: {error}") from None
    except OverflowError as error:
        raise ValueError(f"--set {' '.join(settings)}: {error}; widen that format") from None

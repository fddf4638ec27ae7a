"""The product's accuracy bound (docs/shading.md "Accuracy"), read from its one definition in
tests/accuracy_bound.h: |got - want| <= RELATIVE_BOUND * max(|want|, ERROR_FLOOR) on every shaded
pixel's R, G and B."""
import pathlib
import re

_HEADER = pathlib.Path(__file__).resolve().parents[2] / "tests" / "accuracy_bound.h"


def _constant(name):
    match = re.search(r"constexpr double " + name + r" = ([0-9.eE+-]+);", _HEADER.read_text())
    if not match:
        raise RuntimeError(f"{_HEADER}: no 'constexpr double {name}'")
    return float(match.group(1))


RELATIVE_BOUND = _constant("kRelativeBound")
ERROR_FLOOR = _constant("kErrorFloor")

"""Rewrite the golden files ``tests/golden/<model>.json`` from the current code.

Run from the repository root::

    python -m tests.golden.regenerate                 # every model
    python -m tests.golden.regenerate --model ring    # one (repeat --model for more)
    python -m tests.golden.regenerate --sensitivity   # response to a one-ulp input change

Regenerate only after a change of results that is intended, and say in the commit what moved
and why (``git diff tests/golden`` shows the old and the new values).
"""

from __future__ import annotations

import argparse
import platform
from pathlib import Path
from typing import Any

import numpy as np

from .cases import CASES, REGENERATE

HERE = Path(__file__).resolve().parent
#: input keys that set the time, cage or damage-block grid: not nudged by ``--sensitivity``
_GRID_KEYS = ("duration", "dt_s", "rate", "cage_revs", "points_per_rev", "cage_deg", "delta_d")


def golden_path(model: str) -> Path:
    """Path of the golden file of ``model``."""
    return HERE / f"{model}.json"


def build(model: str) -> dict[str, Any]:
    """The golden record of ``model``: description, command, versions, tolerance, in and out."""
    import numba
    import scipy

    import bearingsim

    case = CASES[model]
    return {
        "model": model,
        "description": case.description,
        "regenerate": f"{REGENERATE} --model {model}",
        "bearingsim_version": bearingsim.__version__,
        "generated_with": {
            "python": platform.python_version(),
            "numpy": np.__version__,
            "scipy": scipy.__version__,
            "numba": numba.__version__,
        },
        "tolerance": case.tolerance_record(),
        "inputs": case.inputs,
        "outputs": case.run(case.inputs),
    }


def _nudge(obj: Any, key: str = "") -> Any:
    """``obj`` with every float input (but the time and cage grid) raised by one ulp."""
    if isinstance(obj, dict):
        return {k: _nudge(v, k) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_nudge(v, key) for v in obj]
    if isinstance(obj, float) and not any(g in key for g in _GRID_KEYS):
        return float(np.nextafter(obj, np.inf))
    return obj


def sensitivity(model: str) -> float:
    """Largest change of an output, relative to that output's largest magnitude, when every
    float input moves by one ulp."""
    case = CASES[model]
    ref, got = case.run(case.inputs), case.run(_nudge(case.inputs))
    worst = 0.0
    for k, v in ref.items():
        a, b = np.asarray(v, dtype=float), np.asarray(got[k], dtype=float)
        scale = float(np.abs(a).max()) or 1.0
        worst = max(worst, float(np.abs(a - b).max()) / scale)
    return worst


def main(argv: list[str] | None = None) -> None:
    from bearingsim.io.atomic import write_json

    ap = argparse.ArgumentParser(prog=REGENERATE, description=__doc__.splitlines()[0])
    ap.add_argument("--model", action="append", choices=sorted(CASES), help="model (repeat)")
    ap.add_argument(
        "--sensitivity", action="store_true", help="print the one-ulp response, write nothing"
    )
    args = ap.parse_args(argv)
    for model in args.model or sorted(CASES):
        if args.sensitivity:
            print(f"{model}: {sensitivity(model):.2g}")
            continue
        write_json(golden_path(model), build(model))
        print(f"wrote {golden_path(model)}")


if __name__ == "__main__":
    main()

"""Golden-regression tier: each model family's small case (``tests/golden/cases.py``) against
its stored outputs ``tests/golden/<model>.json``.

A failure means a result moved. If the change is intended, regenerate the file with the command
it names (``python -m tests.golden.regenerate --model M``) and say in the commit what moved and
why; otherwise find the cause. See tests/golden/README.md.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from golden.cases import CASES, REGENERATE
from numpy.testing import assert_allclose

pytestmark = pytest.mark.golden

GOLDEN = Path(__file__).resolve().parent / "golden"


@pytest.mark.parametrize("model", sorted(CASES))
def test_golden(model):
    path = GOLDEN / f"{model}.json"
    ref = json.loads(path.read_text(encoding="utf-8"))
    case = CASES[model]
    regen = f"{REGENERATE} --model {model}"
    assert ref["regenerate"] == regen
    assert ref["inputs"] == case.inputs, f"the case inputs changed: {regen}"
    assert ref["tolerance"] == case.tolerance_record()
    got = case.run(case.inputs)
    assert sorted(got) == sorted(ref["outputs"]), f"the case outputs changed: {regen}"
    for key, want in ref["outputs"].items():
        rtol, atol_rel = case.tolerance(key)
        atol = atol_rel * float(np.max(np.abs(want)))
        if key.endswith(".mean"):
            # a signal's mean is a cancellation of its values: its magnitude is the signal's
            # (rotor: a 1.4e-5 m/s^2 mean of a +/-0.6 m/s^2 signal moved 5 % between machines)
            sig = key.removesuffix(".mean")
            size = max(abs(ref["outputs"][sig + ".min"]), abs(ref["outputs"][sig + ".max"]))
            atol = max(atol, atol_rel * size)
        assert_allclose(
            got[key],
            want,
            rtol=rtol,
            atol=atol,
            err_msg=f"{model}: {key} vs {path.name} (if intended: {regen})",
        )


def test_every_model_family_has_a_golden_file():
    assert sorted(CASES) == ["hertz", "ias", "life", "qs5", "ring", "rotor"]
    assert sorted(p.stem for p in GOLDEN.glob("*.json")) == sorted(CASES)
    readme = (GOLDEN / "README.md").read_text(encoding="utf-8")
    assert REGENERATE in readme
    for model in CASES:
        assert f"`{model}`" in readme, f"{model} is not described in tests/golden/README.md"

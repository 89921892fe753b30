"""Fit and evaluate the calibration of the fused diagnosis on the CWRU records, and print the
benchmark table of ``docs/validation.md`` (issue 17); see
:mod:`bearingsim.signal.cwru_benchmark` for what is fitted on what.

    python scripts/calibrate_diagnosis.py [--data ../shared/data/cwru] [--markdown OUT.md]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

from bearingsim.signal.cwru_benchmark import evaluate, evidence, markdown

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data" / "cwru"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", type=Path, default=DATA, help="folder with manifest.csv")
    ap.add_argument("--markdown", type=Path, default=None, help="write the tables here")
    a = ap.parse_args(argv)
    if not (a.data / "manifest.csv").is_file():
        print(f"error: data = {str(a.data)!r} has no manifest.csv", file=sys.stderr)
        return 2
    cal, recs = evaluate(evidence(a.data, verbose=True))
    text = markdown(cal, recs)
    print(f"CALIBRATION intercept={cal.intercept:.4f} slope={cal.slope:.4f}")
    if a.markdown:
        fd, tmp = tempfile.mkstemp(dir=a.markdown.parent, suffix=".tmp")
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        os.replace(tmp, a.markdown)
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""``report/published.toml``: the published numbers the report and the literature tests read."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from bearingsim.errors import ConfigError
from bearingsim.report.published import DATA_FILE, Kind, entries, entry, value

ROOT = Path(__file__).resolve().parents[1]
#: ``value("id")`` / ``entry(f"id.{x}")`` calls in the sources and the tests
_CALL = re.compile(r"""\b(?:value|entry)\((f?)"([^"]+)"\)""")


def _references() -> tuple[set[str], list[re.Pattern]]:
    """Literal ids and f-string id patterns (``{...}`` matches one id part) used in the code."""
    literal, patterns = set(), []
    files = [*ROOT.joinpath("src").rglob("*.py"), *ROOT.joinpath("tests").glob("*.py")]
    for p in (f for f in files if f.resolve() != Path(__file__).resolve()):
        for is_f, text in _CALL.findall(p.read_text(encoding="utf-8")):
            if is_f:
                parts = re.split(r"\{[^}]*\}", text)
                patterns.append(re.compile("[^.]+".join(map(re.escape, parts)) + "$"))
            else:
                literal.add(text)
    return literal, patterns


def test_every_entry_is_complete():
    found = entries()
    assert len(found) > 40
    for eid, e in found.items():
        assert e.id == eid and e.source and e.unit, eid
        assert isinstance(e.kind, Kind), eid
        if isinstance(e.value, tuple):
            assert all(len(c) == len(e.value) for c in e.columns.values()), eid
        if e.unit != "%" and not isinstance(e.value, str):
            assert e.si is not None  # every unit but % has an SI form
    kinds = {e.kind for e in found.values()}
    assert kinds == set(Kind), "paper, measured and standard values are all present"


def test_every_id_used_exists_and_every_entry_is_used():
    literal, patterns = _references()
    unknown = sorted(i for i in literal if i not in entries())
    assert not unknown, f"ids read in the code but not in {DATA_FILE}: {unknown}"
    unused = [i for i in entries() if i not in literal and not any(p.match(i) for p in patterns)]
    assert not unused, f"entries of {DATA_FILE} that nothing reads: {unused}"


def test_values_as_printed_and_in_si():
    assert value("vsm.eq20.bpfi_6205_1748rpm") == 157.76
    e = entry("life.table2.inner_pmax_theory")
    assert (e.value, e.unit, e.kind) == (2890.0, "MPa", Kind.PAPER)
    assert e.si == 2890e6
    assert entry("vsm.s2_1.load_zone_half_angle").si == math.radians(68.2)
    assert entry("catalogue.nsk.6203.c_r").si == 9.55e3
    assert entry("life.table4.test_lives").kind is Kind.MEASURED
    assert entry("cwru.drive_end.bpfo_order").kind is Kind.STANDARD
    assert value("ias.fig9.order_peaks") == (4.22, 8.44, 12.66)


def test_table_rows():
    rows = entry("vsm.table2.outer_defect_events").rows("ball", "event")
    assert rows[0] == (143.1, 5, "enters_zone") and len(rows) == 11
    with pytest.raises(ConfigError, match="no column 'angle'; valid: ball, event"):
        entry("vsm.table2.outer_defect_events").rows("angle")
    with pytest.raises(ConfigError, match="is a single value, not a table"):
        entry("vsm.s2_1.radial_load").rows()


def test_unknown_id_is_a_one_line_error():
    with pytest.raises(ConfigError) as exc:
        value("vsm.eq20.bpfi_6205_1784rpm")
    msg = str(exc.value)
    assert "\n" not in msg
    assert "published id = 'vsm.eq20.bpfi_6205_1784rpm' is unknown" in msg
    assert "closest: vsm.eq20.bpfi_6205_1748rpm" in msg
    with pytest.raises(ConfigError, match="has no SI form"):
        _ = entry("rotor.s3.amplitude_drop").si

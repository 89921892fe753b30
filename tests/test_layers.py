"""The layers of ``docs/architecture.md`` stay one-way (issue 13, item 1): no module imports,
at import time, a module of a higher layer, and no model family imports another.

Imports inside functions (lazy, e.g. a result's ``plot_*`` loading Matplotlib, or
:func:`bearingsim.io.read_signal` loading the result classes when it reads a result file) are
outside this check; ``if TYPE_CHECKING:`` blocks too.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"

#: (layer, module prefixes), lowest first (a copy of the table in docs/architecture.md)
LAYERS: list[tuple[str, tuple[str, ...]]] = [
    ("base", ("bearingsim._version", "bearingsim.errors", "bearingsim.plotting")),
    ("io", ("bearingsim.io",)),
    ("bearing data", ("bearingsim.materials", "bearingsim.geometry", "bearingsim.catalog")),
    ("scenarios", ("bearingsim.config",)),
    ("signal", ("bearingsim.signal",)),
    ("results", ("bearingsim.results",)),
    ("contact", ("bearingsim.contact",)),
    ("load distribution", ("bearingsim.load_distribution",)),
    ("integrators", ("bearingsim.dynamics.integrate", "bearingsim.dynamics")),
    (
        "model families",
        (
            "bearingsim.quasistatic",
            "bearingsim.dynamics.ring",
            "bearingsim.dynamics.rotor",
            "bearingsim.dynamics.ias",
            "bearingsim.life",
        ),
    ),
    ("simulation", ("bearingsim.simulation",)),
    ("sweep", ("bearingsim.sweep",)),
    ("report", ("bearingsim.report",)),
    ("cli", ("bearingsim.cli", "bearingsim.__main__", "bearingsim")),
]
FAMILIES = LAYERS[9][1]


def _module(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _match(mod: str, prefixes: tuple[str, ...]) -> str | None:
    best = None
    for p in prefixes:
        if (mod == p or mod.startswith(p + ".")) and (best is None or len(p) > len(best)):
            best = p
    return best


def _layer(mod: str) -> tuple[int, str]:
    found = [(len(m), i, m) for i, (_, ps) in enumerate(LAYERS) if (m := _match(mod, ps))]
    if not found:
        raise AssertionError(f"{mod} is in no layer of docs/architecture.md")
    _, i, m = max(found)
    return i, m


def _import_time_imports(path: Path, mod: str) -> list[str]:
    """Absolute names of the bearingsim modules ``path`` imports at import time."""
    tree = ast.parse(path.read_text())
    pkg = mod.split(".") if path.name == "__init__.py" else mod.split(".")[:-1]
    out = []

    def visit(body):
        for node in body:
            if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
                continue
            if isinstance(node, ast.If | ast.Try):
                visit(node.body)
                visit(getattr(node, "orelse", []))
                for h in getattr(node, "handlers", []):
                    visit(h.body)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = pkg[: len(pkg) - (node.level - 1)]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                if target.startswith("bearingsim"):
                    for a in node.names:
                        sub = f"{target}.{a.name}"
                        out.append(
                            sub
                            if (SRC / sub.replace(".", "/")).exists()
                            or (SRC / (sub.replace(".", "/") + ".py")).exists()
                            else target
                        )
            elif isinstance(node, ast.Import):
                out.extend(a.name for a in node.names if a.name.startswith("bearingsim"))

    visit(tree.body)
    return out


MODULES = sorted(SRC.rglob("*.py"))


def _violations(mod: str, targets: list[str]) -> list[str]:
    li, lp = _layer(mod)
    out = []
    for target in targets:
        ti, tp = _layer(target)
        if ti > li:
            out.append(f"{mod} ({LAYERS[li][0]}) imports {target} ({LAYERS[ti][0]}) at import time")
        elif li == ti == 9 and tp != lp:
            out.append(f"model family {lp} imports family {tp} ({mod} -> {target})")
    return out


@pytest.mark.parametrize("path", MODULES, ids=[_module(p) for p in MODULES])
def test_no_import_reaches_up_a_layer(path):
    mod = _module(path)
    assert _violations(mod, _import_time_imports(path, mod)) == []


def test_the_check_finds_violations():
    """The check itself: an upward import and a cross-family import are both reported."""
    assert _violations("bearingsim.results", ["bearingsim.simulation"])
    assert _violations("bearingsim.dynamics.ring.vsm", ["bearingsim.dynamics.rotor.model"])
    assert _violations("bearingsim.io.atomic", ["bearingsim.geometry"])
    assert not _violations("bearingsim.dynamics.ring.vsm", ["bearingsim.dynamics.integrate"])
    imports = _import_time_imports(SRC / "bearingsim" / "results.py", "bearingsim.results")
    assert "bearingsim.io.atomic" in imports

"""``bearingsim reproduce``: the main job."""

from __future__ import annotations

import click

from ..report import REF_KINDS, SECTIONS, STATUSES, run_report
from .common import check_outputs, cli, deprecated, emit_json, json_option, output_option

__all__ = [
    "reproduce_cmd",
]


@cli.command("reproduce")
@click.option("--quick", is_flag=True, help="Reduced-size variants of long computations.")
@output_option(
    "Output directory for results.json, figures and report.html.",
    required=True,
    kind=click.Path(file_okay=False),
    dest="out_dir",
)
@deprecated("--out", "--output")
@click.option(
    "--section",
    "sections",
    multiple=True,
    type=click.Choice(SECTIONS),
    help="Run only these sections (repeatable).",
)
@json_option
def reproduce_cmd(quick: bool, out_dir: str, sections: tuple[str, ...], as_json: bool) -> None:
    """Reproduce the published numbers: write results.json, PNG figures and report.html."""
    check_outputs(("-o/--output", out_dir), directory=True)
    done = run_report(out_dir, quick=quick, sections=list(sections) or None, progress=not as_json)
    counts: dict[str, int] = {}
    by_kind: dict[str, dict[str, int]] = {}
    for s in done:
        for r in s.rows:
            counts[r.status] = counts.get(r.status, 0) + 1
            k = by_kind.setdefault(r.reference_kind, {})
            k[r.status] = k.get(r.status, 0) + 1
    if as_json:
        emit_json(
            {
                "out_dir": out_dir,
                "counts": counts,
                "counts_by_kind": by_kind,
                "sections": [s.name for s in done],
            }
        )
        return
    click.echo(
        f"wrote {out_dir}/report.html and results.json: "
        + ", ".join(f"{k} {counts[k]}" for k in STATUSES if k in counts)
    )
    for kind in REF_KINDS:
        if kind in by_kind:
            n = by_kind[kind]
            click.echo(f"  {kind:>8}: " + ", ".join(f"{k} {n[k]}" for k in STATUSES if k in n))

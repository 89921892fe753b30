"""``bearingsim sweep plan|run|summary``: parameter sweeps on Dask into one Zarr dataset."""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Any

import click

from ..errors import ConfigError, check_range
from .common import (
    Number,
    check_outputs,
    cli,
    deprecated,
    echo_warnings,
    emit_json,
    json_option,
    output_option,
)

__all__ = [
    "plan_cmd",
    "run_cmd",
    "summary_cmd",
    "sweep_group",
]


def _count(name: str, value: int | None, lo: int = 1) -> int | None:
    if value is None:
        return None
    check_range(name, value, lo)
    return int(value)


def _human_bytes(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if abs(n) < 1000 or unit == "TB":
            return f"{n:.3g} {unit}"
        n /= 1000.0
    return f"{n:.3g} TB"


def _human_s(s: float) -> str:
    if s != s:  # nan
        return "?"
    if s < 120:
        return f"{s:.3g} s"
    if s < 7200:
        return f"{s / 60:.3g} min"
    return f"{s / 3600:.3g} h"


@cli.group("sweep")
def sweep_group() -> None:
    """Parameter sweeps: plan, run (local Dask cluster or --scheduler), summary."""


@sweep_group.command("plan")
@click.argument("spec_file", metavar="SWEEP.toml", type=click.Path(dir_okay=False))
@click.option(
    "--timing-runs",
    type=Number(0, integer=True),
    default=3,
    help="Short timing runs for the estimate (0: none; every run is still checked).",
)
@click.option(
    "--timing-duration-s",
    type=Number(0.0, lo_open=True, unit="s"),
    default=0.1,
    help="Longest simulated time of a timing run [s].",
)
@click.option(
    "--workers",
    type=Number(1, integer=True),
    default=None,
    show_default="CPU count",
    help="Workers for the wall-time estimate.",
)
@json_option
def plan_cmd(
    spec_file: str,
    timing_runs: int,
    timing_duration_s: float,
    workers: int | None,
    as_json: bool,
) -> None:
    """Number of runs and an estimate of compute time and disk from short timing runs."""
    from ..sweep.execute import plan_sweep
    from ..sweep.spec import SweepSpec

    _count("timing_runs", timing_runs, 0)
    check_range("timing_duration_s", timing_duration_s, 0.0, lo_open=True, unit="s")
    workers = _count("workers", workers)
    spec = SweepSpec.from_toml(spec_file)
    plan = plan_sweep(
        spec,
        timing_runs=timing_runs,
        timing_duration_s=timing_duration_s,
        workers=workers,
        progress=not as_json,
    )
    d = plan.as_dict()
    d["spec"] = str(spec_file)
    if (note := spec.unstored_sensor_note) is not None:
        d["notes"] = [note]
    if as_json:
        emit_json(d)
        return
    # zipped axes run side by side: "x" read as a product (a helper, twenty-sixth session)
    zipped = plan.combine == "zip"
    axes = (", " if zipped else " x ").join(f"{k} {v}" for k, v in plan.axes.items())
    axes = (axes + (" side by side" if zipped and len(plan.axes) > 1 else "")) or "no axes"
    ns = plan.n_samples
    samples = f"{ns[0]}" if ns[0] == ns[1] else f"{ns[0]}-{ns[1]}"
    click.echo(f"{spec_file}: {plan.n_runs} runs ({plan.combine}: {axes})")
    click.echo(f"  channels {', '.join(plan.channels)}; {samples} samples per run")
    if timing_runs:
        click.echo(
            f"  estimate from {len(plan.timing)} timing runs: {_human_s(plan.compute_s_per_run)} "
            f"per run, {_human_s(plan.compute_s_total)} on 1 worker, "
            f"~{_human_s(plan.wall_s)} on {plan.workers} worker{'s' if plan.workers != 1 else ''} "
            "(ideal scaling, at least the "
            "longest run)"
        )
    click.echo(
        f"  disk ~{_human_bytes(plan.bytes_estimate)} (signals {_human_bytes(plan.bytes_raw)} "
        "uncompressed, plus each run's record)"
    )
    _echo_invalid(plan.invalid_runs, plan.n_runs)
    if (note := spec.unstored_sensor_note) is not None:
        click.echo(f"  note: {note}")
    for w, runs in plan.run_warnings.items():
        first = ", ".join(str(i) for i in runs[:5]) + (", ..." if len(runs) > 5 else "")
        click.echo(f"  {len(runs)} of {plan.n_runs} runs will warn (runs {first}): {w}")


#: distinct errors of runs that cannot start that ``sweep plan`` prints (``--json`` lists all)
SHOW_ERRORS = 5


def _echo_invalid(invalid: list[dict], n_runs: int) -> None:
    """The runs that cannot start, grouped by their error: the first runs of each group with
    their axis values."""
    if not invalid:
        return
    by: dict[str, list[dict]] = {}
    for d in invalid:
        by.setdefault(d["error"], []).append(d)
    click.echo(
        f"  {len(invalid)} of {n_runs} runs cannot start ('sweep run' records them as failed):"
    )
    for err, ds in list(by.items())[:SHOW_ERRORS]:
        vals = ", ".join(f"{k} = {v!r}" for k, v in ds[0]["values"].items())
        more = f" and {len(ds) - 1} more with this error" if len(ds) > 1 else ""
        click.echo(f"    run {ds[0]['run']} ({vals}){more}: {err}")
    if len(by) > SHOW_ERRORS:
        click.echo(f"    ... {len(by) - SHOW_ERRORS} more errors (--json lists every run)")


@sweep_group.command("run")
@click.argument("spec_file", metavar="SWEEP.toml", type=click.Path(dir_okay=False))
@output_option("Dataset directory (Zarr store).", required=True, kind=click.Path(), dest="out")
@deprecated("--out", "--output")
@click.option(
    "--workers",
    type=Number(1, integer=True),
    default=None,
    show_default="CPU count",
    help="Process workers of the local Dask cluster.",
)
@click.option(
    "--scheduler",
    default=None,
    help="Address of a running Dask scheduler (tcp://HOST:PORT) instead of a local cluster.",
)
@click.option(
    "--connect-timeout-s",
    type=Number(0.0, lo_open=True, unit="s"),
    default=20.0,
    help="How long to try reaching --scheduler [s].",
)
@click.option("--force-new", is_flag=True, help="Replace an existing dataset of a different spec.")
@click.option("--retry-failed", is_flag=True, help="Compute the failed runs again.")
@click.option(
    "--runs-per-task",
    type=Number(1, integer=True),
    default=None,
    show_default="automatic",
    help="Runs per Dask task.",
)
@click.option(
    "--writer",
    type=click.Choice(["auto", "client"]),
    default="auto",
    help="auto: workers that see the dataset commit their runs; client: the client commits.",
)
@json_option
def run_cmd(
    spec_file: str,
    out: str,
    workers: int | None,
    scheduler: str | None,
    connect_timeout_s: float,
    force_new: bool,
    retry_failed: bool,
    runs_per_task: int | None,
    writer: str,
    as_json: bool,
) -> None:
    """Run the sweep (or resume it: only runs not yet committed are computed)."""
    check_outputs(("-o/--output", out), directory=True)
    from ..sweep.execute import SweepInterrupted, check_cluster_args, run_sweep
    from ..sweep.spec import SweepSpec

    workers = _count("workers", workers)
    runs_per_task = _count("runs_per_task", runs_per_task)
    check_cluster_args(workers, scheduler)
    check_range("connect_timeout_s", connect_timeout_s, 0.0, lo_open=True, unit="s")
    p = Path(out)
    if p.exists() and not p.is_dir():
        raise ConfigError(f"-o/--output = {out!r} is a file; valid: a dataset directory")
    try:  # an empty working folder was removed as "a new dataset", then the run crashed
        cwd = Path.cwd().resolve()  # (exploratory testing, twenty-seventh session: -o .)
    except OSError:
        cwd = None
    if cwd is not None and (p.resolve() == cwd or p.resolve() in cwd.parents):
        raise ConfigError(
            f"-o/--output = {out!r} is the working folder or one of its parents; valid: a "
            "dataset directory inside or beside it (e.g. -o sweep.zarr)"
        )
    if force_new and p.is_dir() and p.resolve() in Path(spec_file).resolve().parents:
        # --force-new removes the dataset folder, and the sweep file with it
        raise ConfigError(
            f"SPEC = {spec_file!r} lies inside -o/--output = {out!r}, which --force-new "
            "removes; valid: a sweep file outside the dataset folder"
        )
    if p.is_dir() and not any(p.iterdir()):
        p.rmdir()  # an empty directory is taken as a new dataset
    spec = SweepSpec.from_toml(spec_file)
    if (note := spec.unstored_sensor_note) is not None:
        click.echo(f"note: {note}", err=True)
    stopped: list[int] = []  # SIGTERM / SIGHUP received
    try:
        # warnings raised in this process, each once, as one line; the runs' own warnings are
        # recorded with each run and counted in the report (printed below)
        with echo_warnings(), _terminate_as_interrupt(stopped):
            rep = run_sweep(
                spec,
                out,
                workers=workers,
                scheduler=scheduler,
                force_new=force_new,
                retry_failed=retry_failed,
                runs_per_task=runs_per_task,
                writer=writer,
                progress=not as_json,
                connect_timeout_s=connect_timeout_s,
            )
    except SweepInterrupted as exc:
        click.echo(f"error: {exc}", err=True)
        raise click.exceptions.Exit(128 + stopped[0] if stopped else 130) from None
    except KeyboardInterrupt:  # before any run (the cluster starting, a scheduler awaited)
        if not stopped:
            raise
        click.echo("error: aborted", err=True)
        raise click.exceptions.Exit(128 + stopped[0]) from None
    except OSError as exc:  # a full disk while the dataset is written: one line (it stays
        from ..io.atomic import storage_reason  # consistent: the runs committed are kept)

        reason = storage_reason(exc, out)
        if reason is None and not p.exists():  # removed or moved while the sweep wrote it
            raise ConfigError(
                f"-o/--output = {out!r} was removed or moved while this sweep wrote it; run the "
                "same command again to start it anew"
            ) from None
        if reason is None and isinstance(exc, PermissionError):  # a folder of it not writable
            raise ConfigError(
                f"-o/--output = {out!r} cannot be written: permission denied for "
                f"{str(exc.filename)!r}; valid: a dataset this user can write (the runs "
                "committed are kept)"
            ) from None
        if reason is None:
            raise
        raise ConfigError(
            f"-o/--output = {out!r} cannot be written: {reason}; the runs committed are kept: "
            "free space and run the same command to resume"
        ) from None
    d = rep.as_dict()
    if as_json:
        emit_json(d)
        return
    for w, n in rep.warnings.items():
        click.echo(
            f"warning: {w} (in {n} of the {rep.n_computed} runs computed; 'sweep summary' "
            "lists the runs)",
            err=True,
        )
    thr = d["throughput_runs_per_s"]
    head = f"{out}: {rep.n_runs} runs; {rep.n_skipped} already committed, {rep.n_computed} computed"
    if not rep.cluster:  # nothing to compute: no cluster was started
        click.echo(f"{head}: nothing to do")
    else:
        click.echo(
            f"{head} ({rep.n_computed - rep.n_failed_now} ok, {rep.n_failed_now} failed) in "
            f"{_human_s(rep.wall_s)}"
            + (f" ({thr:.3g} runs/s)" if thr else "")
            + f" on {rep.cluster}"
        )
    click.echo(f"  dataset: {rep.n_ok} ok, {rep.n_failed} failed, {rep.n_pending} pending")


@contextlib.contextmanager
def _terminate_as_interrupt(stopped: list[int]):
    """SIGTERM and SIGHUP (a batch system's time limit, a closed terminal) handled as Ctrl-C:
    the client stops its runs, releases its lock and says what is committed; the exit code
    is 128 + the signal's number. Exploratory testing, twenty-seventh session: the client
    died at once, unsaid, and left its lock (another host then waited 300 s). The signal is
    passed on as a SIGINT, so that the blocks that hold Ctrl-C (:mod:`bearingsim.interrupt`)
    hold it too."""
    import os
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, frame):
        if not stopped:
            stopped.append(signum)
        if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:  # e.g. started with & by a
            signal.signal(signal.SIGINT, signal.default_int_handler)  # script: still stop
        os.kill(os.getpid(), signal.SIGINT)

    old = {}
    for name in ("SIGTERM", "SIGHUP"):
        sig = getattr(signal, name, None)
        if sig is not None:
            with contextlib.suppress(ValueError, OSError):
                old[sig] = signal.signal(sig, handler)
    try:
        yield
    finally:
        for sig, h in old.items():
            signal.signal(sig, h)


@sweep_group.command("summary")
@click.argument("dataset", metavar="DATASET", type=click.Path())
@click.option(
    "--label",
    default=None,
    show_default="the dataset's",
    help="Label key(s), comma-separated.",
)
@click.option(
    "--max-failures", type=Number(0, integer=True), default=10, help="Failures listed (text)."
)
@json_option
def summary_cmd(dataset: str, label: str | None, max_failures: int, as_json: bool) -> None:
    """Counts by label and axis value, failures with their errors."""
    from ..sweep.dataset import open_dataset

    _count("max_failures", max_failures, 0)
    ds = open_dataset(dataset)
    keys = None if label is None else [k.strip() for k in label.split(",") if k.strip()]
    if keys is not None:
        for k in keys:
            if k not in ds.attrs["coordinate_keys"]:
                raise ConfigError(
                    f"label = {k!r} is not stored per run; valid: "
                    + ", ".join(ds.attrs["coordinate_keys"])
                )
    s = ds.summary(keys)
    if as_json:
        emit_json(s)
        return
    click.echo(
        f"{dataset}: {s['n_runs']} runs: {s['n_ok']} ok, {s['n_failed']} failed, "
        f"{s['n_pending']} pending" + ("" if s["complete"] else " (incomplete: resume with run)")
    )
    if s["label"]:
        click.echo(f"  by {'|'.join(s['label'])}:")
        for v, c in s["by_label"].items():
            click.echo(f"    {v:<24} {_counts(c)}")
    for key, by in s["by_axis"].items():  # as promised: by axis value too (--json had them)
        if list(s["label"]) == [key]:
            continue  # already listed as the label
        click.echo(f"  by {key}:")
        for v, c in by.items():
            click.echo(f"    {v:<24} {_counts(c)}")
    for w, runs in s["warnings"].items():
        shown = ", ".join(str(r) for r in runs[:max_failures])
        more = f", ... {len(runs) - max_failures} more" if len(runs) > max_failures else ""
        click.echo(f"  warning in {len(runs)} run(s) ({shown}{more}): {w}")
    for f in s["failures"][:max_failures]:
        params = ", ".join(f"{k}={v}" for k, v in f["params"].items())
        click.echo(f"  failed run {f['run']} ({params}): {f['error']}")
    if len(s["failures"]) > max_failures:
        click.echo(f"  ... {len(s['failures']) - max_failures} more failures (--json lists all)")


def _counts(c: dict[str, Any]) -> str:
    return ", ".join(f"{v} {k}" for k, v in c.items() if v or k == "ok")

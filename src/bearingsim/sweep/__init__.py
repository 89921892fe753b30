"""Parameter sweeps and labelled datasets on Dask (see ``docs/sweeps.md``).

- :mod:`.spec` — sweep files: a base scenario and its axes; canonical hash.
- :mod:`.plan` — run layout, timing probe, time and disk estimates.
- :mod:`.execute` — execution on a local or remote Dask cluster, resumable.
- :mod:`.store` — the Zarr store: layout, atomic per-run commits, claims, checked readers.
- :mod:`.lock` — the client lock: one client writes a dataset at a time; stale locks.
- :mod:`.dataset` — the dataset loader (labels, splits, NumPy arrays for ML).

May import everything below it (config, simulation, results, io); nothing imports it but the
CLI.
"""

from .dataset import SplitWarning, open_dataset
from .execute import SweepInterrupted, SweepReport, Writer, connect, run_sweep
from .plan import SweepPlan, plan_sweep
from .spec import SweepSpec

__all__ = [
    "SplitWarning",
    "SweepInterrupted",
    "SweepPlan",
    "SweepReport",
    "SweepSpec",
    "Writer",
    "connect",
    "open_dataset",
    "plan_sweep",
    "run_sweep",
]

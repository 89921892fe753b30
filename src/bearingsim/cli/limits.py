"""Options and helpers of the commands that run a time-domain model or a large analysis
(``simulate``, ``ias``, ``vsm-trace``, ``rotor-modes``): the resource budget
(``--max-memory-gb``, ``--max-steps``; :mod:`bearingsim.dynamics.budget`), ``--allow-overload``
and model warnings printed as one ``warning: ...`` line each on stderr.

Light: imports neither NumPy nor a model (the budget module is plain Python).
"""

from __future__ import annotations

import contextlib
import functools
import warnings
from collections.abc import Callable, Iterator
from typing import Any

import click

__all__ = ["budget_options", "overload_option", "printed_warnings"]


def budget_options(steps: bool = True) -> Callable:
    """Decorator adding ``--max-memory-gb`` (and ``--max-steps`` with ``steps``); the command
    receives ``budget`` (a :class:`~bearingsim.dynamics.budget.Budget`) instead."""

    def deco(f: Callable) -> Callable:
        @click.option(
            "--max-memory-gb",
            type=float,
            default=None,
            show_default="(half the available memory)",
            help="Memory the run may use [GB]; a run estimated above it is refused.",
        )
        @functools.wraps(f)
        def wrapper(max_memory_gb: float | None, max_steps: float | None = None, **kw: Any):
            from ..dynamics.budget import GB, Budget
            from ..errors import check_positive

            mem = None
            if max_memory_gb is not None:
                mem = check_positive("max_memory_gb", max_memory_gb, "GB") * GB
            return f(budget=Budget(mem, max_steps), **kw)

        if steps:
            wrapper = click.option(
                "--max-steps",
                type=float,
                default=None,
                show_default="(1e9)",
                help="Integration steps the run may take [-]; a run estimated above it is refused.",
            )(wrapper)
        return wrapper

    return deco


overload_option = click.option(
    "--allow-overload",
    is_flag=True,
    help="Run a radial load above twice the bearing's static capacity C0 (ISO 76) instead of "
    "refusing it.",
)


@contextlib.contextmanager
def printed_warnings(seen: set[str] | None = None) -> Iterator[None]:
    """Collect the warnings raised inside and, when the block succeeds, print each as one line
    ``warning: ...`` on stderr (a refusal stays the only line). Messages already in ``seen``
    (shared between blocks: a check warns again when the run repeats it) are not repeated."""
    seen = set() if seen is None else seen
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield
    for w in caught:
        msg = " ".join(str(w.message).split())
        if msg not in seen:
            seen.add(msg)
            click.echo(f"warning: {msg}", err=True)

"""Options and helpers of the commands that run a time-domain model or a large analysis
(``simulate``, ``ias``, ``vsm-trace``, ``rotor-modes``): the resource budget
(``--max-memory-gb``, ``--max-steps``; :mod:`bearingsim.dynamics.budget`). ``--allow-overload``
and the one-line warnings are :func:`.common.allow_overload_option` and
:func:`.common.echo_warnings`.

Light: imports neither NumPy nor a model (the budget module is plain Python).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any

import click

from .common import Number

__all__ = ["budget_options"]


class _Count(Number):
    """A count of steps: an integer, which may be written in exponent form (``--max-steps 1e9``
    is the count 1000000000; ``1.5`` is refused: not an integer)."""

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> Any:
        if isinstance(value, str):
            try:
                x = float(value)
            except ValueError:
                x = math.nan
            if math.isfinite(x) and x.is_integer():
                value = int(x)
        return super().convert(value, param, ctx)


def budget_options(steps: bool = True) -> Callable:
    """Decorator adding ``--max-memory-gb`` (and ``--max-steps`` with ``steps``); the command
    receives ``budget`` (a :class:`~bearingsim.dynamics.budget.Budget`) instead."""

    def deco(f: Callable) -> Callable:
        @click.option(
            "--max-memory-gb",
            type=Number(0.0, lo_open=True, unit="GB"),
            default=None,
            show_default="half the available memory",
            help="Memory the run may use [GB]; a run estimated above it is refused.",
        )
        @functools.wraps(f)
        def wrapper(max_memory_gb: float | None, max_steps: int | None = None, **kw: Any):
            from ..dynamics.budget import GB, Budget
            from ..errors import check_positive

            mem = None
            if max_memory_gb is not None:
                mem = check_positive("max_memory_gb", max_memory_gb, "GB") * GB
            return f(budget=Budget(mem, max_steps), **kw)

        if steps:
            wrapper = click.option(
                "--max-steps",
                type=_Count(1, integer=True),
                default=None,
                show_default="1e9",
                help="Integration steps the run may take [-]; a run estimated above it is refused.",
            )(wrapper)
        return wrapper

    return deco

"""``bearingsim.errors.collect_warnings``: a thread's warnings, every time, and only its own.

Each test starts from Python's own defaults (``resetwarnings``: no filters, action
``default``), as a sweep's worker process does, not from the test suite's ``error`` filter."""

from __future__ import annotations

import threading
import warnings

import pytest

from bearingsim.errors import collect_warnings
from bearingsim.rig import RigRateWarning

#: the registry of one code location in bearingsim (the default action shows a warning once
#: per location and text, recording it here)
REGISTRY: dict = {}


def _warn_from_bearingsim() -> None:
    warnings.warn_explicit(
        "rate too low", RigRateWarning, "rig.py", 405, module="bearingsim.rig", registry=REGISTRY
    )


def test_repeated_warnings_are_collected_every_time():
    with warnings.catch_warnings():
        warnings.resetwarnings()
        with collect_warnings() as first:
            _warn_from_bearingsim()
            _warn_from_bearingsim()  # same text, same code location
        with collect_warnings() as second:
            _warn_from_bearingsim()
    assert first == ["RigRateWarning: rate too low"] * 2
    assert second == ["RigRateWarning: rate too low"]


def test_other_threads_warnings_are_not_collected():
    with warnings.catch_warnings(record=True) as shown:
        warnings.resetwarnings()
        warnings.simplefilter("always")
        with collect_warnings() as mine:
            t = threading.Thread(target=warnings.warn, args=("from another thread",))
            t.start()
            t.join()
            warnings.warn("from this thread", stacklevel=1)
    assert mine == ["UserWarning: from this thread"]
    assert [str(w.message) for w in shown] == ["from another thread"]


def test_nested_blocks_and_the_users_filters():
    with warnings.catch_warnings():
        warnings.resetwarnings()
        with collect_warnings() as outer:
            warnings.warn("outer one", stacklevel=1)
            with collect_warnings() as inner:
                warnings.warn("inner one", stacklevel=1)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                warnings.warn("ignored", stacklevel=1)
            warnings.filterwarnings("error", message="refused")
            try:
                warnings.warn("refused", stacklevel=1)
            except UserWarning as exc:
                raised = str(exc)
    assert (outer, inner, raised) == (
        ["UserWarning: outer one"],
        ["UserWarning: inner one"],
        "refused",
    )


@pytest.mark.parametrize(
    ("value", "lo", "hi", "lo_open", "text"),
    [
        (1.0000001, 0.0, 1.0, False, "x = 1.0000001 Hz is out of range; valid range [0, 1] Hz"),
        (0.19999999, 0.2, 1.0, True, "x = 0.19999999 Hz is out of range; valid range (0.2, 1] Hz"),
        (5.0, 0.0, 1.0, False, "x = 5 Hz is out of range; valid range [0, 1] Hz"),
        (0.2, 0.2, 1.0, True, "x = 0.2 Hz is out of range; valid range (0.2, 1] Hz"),
    ],
)
def test_out_of_range_value_reads_unlike_its_bound(value, lo, hi, lo_open, text):
    """A value just beyond a bound is printed with the digits that tell it from the bound (it
    printed as ``1 Hz is out of range; valid range [0, 1]``); the bound itself, when the value
    sits on an open bound, and values far out keep six digits."""
    from bearingsim.errors import ConfigError, check_range

    with pytest.raises(ConfigError) as e:
        check_range("x", value, lo, hi, lo_open=lo_open, unit="Hz")
    assert str(e.value) == text

"""Marks on some cases of a parametrised test.

The fast lane (``pytest -m "not slow"``) leaves out the cases marked ``slow``; a
parametrised test keeps its quick cases there and its slow ones in the default run.
"""

from __future__ import annotations

import pytest


def slow_cases(values, slow, key=str):
    """``values`` as parameters, those whose ``key`` is in ``slow`` marked ``slow``.

    Parameters
    ----------
    values : iterable
        The parameter values (one argument each, or tuples for several arguments).
    slow : collection
        The keys of the slow cases.
    key : callable
        A value's key (default ``str``: an example's name).

    Returns
    -------
    list
        The values, the slow ones as ``pytest.param(value, marks=pytest.mark.slow)`` (a
        tuple unpacked into the test's arguments); every key in ``slow`` must be a case.
    """
    values = list(values)
    keys = [key(v) for v in values]
    missing = set(slow) - set(keys)
    if missing:
        raise ValueError(f"no case {sorted(missing)!r}")
    out = []
    for v, k in zip(values, keys):
        if k in slow:
            out.append(pytest.param(*(v if isinstance(v, tuple) else (v,)), marks=pytest.mark.slow))
        else:
            out.append(v)
    return out


def fast_cases(values, fast, key=str):
    """``values`` as parameters, all but those whose ``key`` is in ``fast`` marked ``slow``:
    a test run once per shipped example keeps a few examples in the fast lane (the whole
    set runs in the default run).

    Examples
    --------
    >>> [getattr(p, "marks", ()) == () for p in fast_cases(["a", "b"], {"a"})]
    [True, False]
    """
    values = list(values)
    keys = [key(v) for v in values]
    missing = set(fast) - set(keys)
    if missing:
        raise ValueError(f"no case {sorted(missing)!r}")
    return slow_cases(values, set(keys) - set(fast), key=key)

"""Results and what is derived from them, whatever runtime solved them (NumPy only).

``result`` (``Analysis`` and its JSON), ``records`` (a block of its steps
written as JSON records), ``strict_json`` (values that are not
finite left out, and named), ``accuracy`` (per-step relative accuracy),
``transmission`` (transmission angles), ``cycle_average`` (averages over a
sweep's cycle), ``wording`` (how warnings name steps).  It imports nothing else of the numeric core.
"""

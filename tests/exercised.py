"""Property tests count what they check: how many drawn inputs really
exercised the property (and why the others did not), reported and asserted.

    tally = Counter()
    ... tally["checked"] += 1 ... tally["refused: tool does not fit"] += 1 ...
    assert_share("linuxcnc offsets", tally, {"checked"}, at_least=0.8, inputs=300)

The line printed (``pytest -s`` shows it, and a failure repeats it) gives the
count of every outcome.
"""
from __future__ import annotations

from collections import Counter


def share_line(name: str, tally: Counter, exercised: set[str]) -> str:
    total = sum(tally.values())
    done = sum(tally[k] for k in exercised)
    share = done / total if total else 0.0
    outcomes = ", ".join(f"{k}: {v}" for k, v in sorted(tally.items(), key=lambda kv: -kv[1]))
    return f"{name}: {done} of {total} drawn inputs exercised the property ({share:.1%}); {outcomes}"


def assert_share(name: str, tally: Counter, exercised: set[str], at_least: float,
                 inputs: int) -> None:
    """Print the tally, then assert at least ``inputs`` inputs were drawn and
    at least the share ``at_least`` of them had an outcome in ``exercised``."""
    line = share_line(name, tally, exercised)
    print(line)
    total = sum(tally.values())
    assert total >= inputs, line
    assert sum(tally[k] for k in exercised) >= at_least * total, line

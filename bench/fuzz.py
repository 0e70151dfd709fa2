"""Wall time of ccopt's commands on the fuzz's mutated programs, against the
same commands on the programs unmutated (the peer).

tests/test_fuzz.py runs every bundled case's program, mutated from a fixed
seed, through ``ccopt show`` and ``compensate`` and through ``verify`` and
``feed`` in-process, and asserts exits and messages, and a CPU-time bound on
each run against runaways; how long the runs take on the clock is measured
here. For each command: the wall time of every mutated run (with
``--programs 500`` the programs the test runs through show and compensate,
with 100 those through verify and feed: the seed is the test's) and of every unmutated
program, and it prints the median, 95th percentile and largest of each, and
the ratio of the slowest mutated run to the slowest unmutated one (a
mutation that made a command far slower than any real program shows there;
the old test's ceiling was 20 s a run).

    .venv/bin/python bench/fuzz.py [--programs 100] [--commands show,compensate,verify,feed]

Timings on a shared machine are inflated by the other load: compare ratios
from one run, not absolute figures across runs.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from hypothesis import HealthCheck, Phase, given, seed, settings  # noqa: E402

from ccopt.cli import main as ccopt_main  # noqa: E402
import test_fuzz as fuzz  # noqa: E402


def wall(argv: list[str]) -> tuple[int, float]:
    """``ccopt argv`` in-process: exit code and wall time (s)."""
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        try:
            code = ccopt_main(argv)
        except SystemExit as exc:
            code = exc.code
    return code, time.perf_counter() - t0


def stats(times: list[float]) -> str:
    if not times:
        return "no runs"
    q = sorted(times)
    p95 = q[min(len(q) - 1, int(0.95 * len(q)))]
    return f"median {statistics.median(q):7.3f} s  p95 {p95:7.3f} s  max {q[-1]:7.3f} s"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--programs", type=int, default=100,
                    help="mutated programs per command (the test: 500 for show and "
                         "compensate, 100 for verify and feed)")
    ap.add_argument("--commands", default="show,compensate,verify,feed")
    args = ap.parse_args()
    commands = [c.strip() for c in args.commands.split(",") if c.strip()]
    with tempfile.TemporaryDirectory() as d:
        root = Path(d)
        base: dict[str, list[float]] = {c: [] for c in commands}
        (root / "seeds").mkdir()
        for k, (folder, name, text) in enumerate(fuzz.SEEDS):
            dest, _ = fuzz._write_case(root / "seeds", k, folder, name, text)
            for c in commands:
                base[c].append(wall([c, str(dest)])[1])
        mutated: dict[str, list[float]] = {c: [] for c in commands}
        codes: dict[str, dict[int, int]] = {c: {} for c in commands}
        count = [0]
        (root / "mutated").mkdir()

        @seed(fuzz.FUZZ_SEED + args.programs)
        @settings(max_examples=args.programs, deadline=None, database=None,
                  phases=[Phase.generate], suppress_health_check=list(HealthCheck))
        @given(case=fuzz.mutated_case())
        def one(case):
            folder, name, text = case
            count[0] += 1
            dest, _ = fuzz._write_case(root / "mutated", count[0], folder, name, text)
            for c in commands:
                code, dt = wall([c, str(dest)])
                mutated[c].append(dt)
                codes[c][code] = codes[c].get(code, 0) + 1

        one()
    print(f"{count[0]} mutated programs from seed {fuzz.FUZZ_SEED + args.programs}; "
          f"{len(fuzz.SEEDS)} unmutated programs (the peer)")
    for c in commands:
        ratio = max(mutated[c]) / max(base[c]) if mutated[c] and base[c] else float("nan")
        print(f"ccopt {c:10s} mutated   {stats(mutated[c])}  exits {dict(sorted(codes[c].items()))}")
        print(f"{'':16s} unmutated {stats(base[c])}")
        print(f"{'':16s} slowest mutated / slowest unmutated: {ratio:.2f}x")


if __name__ == "__main__":
    main()

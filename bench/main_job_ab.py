"""The main job (``ccopt run`` over the bundled cases) of this tree against an
earlier commit's, in the same session: is it slower?

The earlier commit is checked out into a temporary git worktree and both are
run by this interpreter (the same installed libraries), with ``PYTHONPATH``
pointing at a folder that maps ``ccopt`` and ``ccopt_formulations`` to each
tree (the package layout ``pyproject.toml`` installs). Each round runs the
two either one after the other (``--mode alternate``, the default: on a quiet
machine) or side by side at once (``--mode together``: on a busy machine both
then see the same load), and the order swaps every round. Printed: each
run's wall and CPU seconds (user + system, of the command and its workers),
the medians, and this tree's medians over the earlier commit's.

``--variants`` restricts this tree's comparison to the variants the earlier
commit had (the same work: a variant added since is new work, not a slower
job); ``--same-variants`` takes them from the earlier commit's registry, and
``--same-cases`` runs both on the earlier commit's bundled cases.

::

    .venv/bin/python bench/main_job_ab.py 62b6fe7 --same-variants --same-cases --rounds 3
    .venv/bin/python bench/main_job_ab.py HEAD~5 --mode together
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def package_root(tree: Path, into: Path) -> Path:
    """A folder whose ``ccopt`` and ``ccopt_formulations`` are ``tree``'s (symlinks)."""
    into.mkdir(parents=True, exist_ok=True)
    (into / "ccopt").symlink_to(tree / "ccopt")
    (into / "ccopt_formulations").symlink_to(tree / "formulations")
    return into


def ask(pythonpath: Path, code: str) -> str:
    """What ``code`` prints, run by this interpreter with ``pythonpath``'s packages
    (from that folder: the current one would come first on ``sys.path``)."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=str(pythonpath)), check=True,
                          cwd=pythonpath).stdout.strip()


def which_tree(pythonpath: Path) -> str:
    """Where ``ccopt`` imports from with ``pythonpath`` (a check that the run is that tree's)."""
    return ask(pythonpath, "import ccopt, os; print(os.path.realpath(ccopt.__file__))")


def cases_of(pythonpath: Path) -> list[str]:
    """The bundled case names of that tree (``ccopt run`` with no argument runs them all)."""
    return ask(pythonpath, "from ccopt.cases import bundled_cases_dir; print(','.join(sorted("
                           "p.parent.name for p in bundled_cases_dir().glob('*/case.toml'))))"
               ).split(",")


def variants_of(pythonpath: Path) -> list[str]:
    """The variant names ``ccopt run`` runs by default in that tree (its
    ``main_job_variants`` where it has one, else every variant, as ``run``
    did before the lead families went on demand)."""
    return ask(pythonpath, "import ccopt.compare.registry as r\n"
                           "names = r.main_job_variants() if hasattr(r, 'main_job_variants') "
                           "else r.available()\nprint(','.join(names))").split(",")


def start(pythonpath: Path, out: Path, extra: list[str]) -> subprocess.Popen:
    cmd = [sys.executable, "-m", "ccopt.cli", "run", "-q", "-o", str(out), *extra]
    # stderr into a file beside the output: a pipe nobody reads could fill and block
    # (the child keeps its own copy of the descriptor); from that folder too
    with open(f"{out}.stderr", "w") as err:
        return subprocess.Popen(cmd, env=dict(os.environ, PYTHONPATH=str(pythonpath)),
                                stdout=subprocess.DEVNULL, stderr=err, text=True,
                                cwd=pythonpath)


def finish(procs: dict) -> dict[str, tuple[float, float]]:
    """Wait for every process of ``procs`` (name -> (Popen, t0)): name -> (wall, cpu)
    seconds, each wall time taken when that process ends. CPU is read from
    ``wait4`` (the process and the workers it reaped)."""
    by_pid = {proc.pid: name for name, (proc, _) in procs.items()}
    out = {}
    while by_pid:
        pid, status, usage = os.wait4(-1, 0)
        name = by_pid.pop(pid, None)
        if name is None:
            continue
        proc, t0 = procs[name]
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode not in (0, 1):
            sys.exit(f"{name}: ccopt run failed ({proc.returncode}): "
                     f"{Path(proc.args[proc.args.index('-o') + 1] + '.stderr').read_text()}")
        out[name] = (wall, usage.ru_utime + usage.ru_stime)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("commit", help="the earlier commit (e.g. 62b6fe7)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--mode", choices=("alternate", "together"), default="alternate")
    ap.add_argument("--variants", help="this tree's variants (comma-separated)")
    ap.add_argument("--same-variants", action="store_true",
                    help="this tree runs the earlier commit's default variants")
    ap.add_argument("--same-cases", action="store_true",
                    help="both run the earlier commit's bundled cases (a case added since "
                         "is new work)")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="ccopt-ab-") as tmp:
        tmp = Path(tmp)
        old_tree = tmp / "tree"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", "-q",
                        str(old_tree), args.commit], check=True)
        try:
            paths = {"earlier": package_root(old_tree, tmp / "earlier"),
                     "this": package_root(ROOT, tmp / "this")}
            for name, path in paths.items():
                print(f"{name}: ccopt from {which_tree(path)}")
            extra = {"earlier": [], "this": []}
            variants = args.variants
            if args.same_variants:
                variants = ",".join(variants_of(paths["earlier"]))
            if variants:
                extra["this"] = ["--variants", variants]
            if args.same_cases:
                names = cases_of(paths["earlier"])
                for n in extra:
                    extra[n] = [*names, *extra[n]]
            runs: dict[str, list[tuple[float, float]]] = {"earlier": [], "this": []}
            for k in range(args.rounds):
                order = ["earlier", "this"] if k % 2 == 0 else ["this", "earlier"]
                if args.mode == "together":
                    procs = {n: (start(paths[n], tmp / f"out-{n}-{k}", extra[n]),
                                 time.perf_counter()) for n in order}
                    got = finish(procs)
                else:
                    got = {}
                    for n in order:
                        got.update(finish({n: (start(paths[n], tmp / f"out-{n}-{k}", extra[n]),
                                               time.perf_counter())}))
                for n in order:
                    runs[n].append(got[n])
                    print(f"round {k + 1} {n:8s} wall {got[n][0]:7.2f} s  cpu {got[n][1]:7.2f} s",
                          flush=True)
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force",
                            str(old_tree)], check=False)
    med = {n: (statistics.median(w for w, _ in r), statistics.median(c for _, c in r))
           for n, r in runs.items()}
    load = os.getloadavg()[0]
    print(f"medians of {args.rounds} ({args.mode}, load average now {load:.2f}): "
          f"earlier {args.commit} wall {med['earlier'][0]:.2f} s cpu {med['earlier'][1]:.2f} s; "
          f"this tree wall {med['this'][0]:.2f} s cpu {med['this'][1]:.2f} s")
    print(f"ratio this / earlier: wall {med['this'][0] / med['earlier'][0]:.3f}, "
          f"cpu {med['this'][1] / med['earlier'][1]:.3f}"
          + (f" (this tree's variants: {variants})" if variants else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())

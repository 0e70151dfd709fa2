"""Benchmark: reading and exporting long programs (issue 17).

Two programs are generated here, deterministically:

* a 20,000-block G-code program as CAM writes it: an outside profile (a
  wavy closed curve, radius 100 mm +- 5 mm, 7 lobes) written as short G1
  chords with a G2 arc every 25 blocks, compensated ``G41 D1`` with a tool
  table (diameter 6 mm), lead-in and lead-out lines;
* a 100,000-line PMAC program: the same kind of curve as LINEAR moves with a
  CIRCLE1 move every 25 lines, ``CCR3 CC1`` ... ``CC0``, a few P-variables
  and moves written with them.

It times, in the same run, the medians of ``--repeat`` runs of: reading
each program, compensating it, exporting the G-code one's tool path (written,
read back and verified, as ``ccopt export`` does), and next to them a floor
for reading: a plain regular-expression split of the same text into its
words and numbers (``re.findall`` + ``float``), which any reader must at
least do. Peak memory is the peak resident set (VmHWM) of a fresh
process that imports ccopt, reads, compensates and exports the 20,000-block
program once, and the same process's resident set after the imports alone.

With ``--ring`` it also exports issue 34's second shape: a ring of 20,000
PMAC LINEAR moves (radius 200 + 3 sin 37 theta, each vertex moved up to
+-0.01 radially, uniform, seed 1), ``CCR2 CC2``: the 0.06 mm chords turn by
up to 0.3 rad, so PMAC's offset folds and the path gouges all round (some
200,000 violations); its read-back holds the corner arcs as spirals (their
end radii rounded), whose pairs the certificate bounds one by one.

    python bench/io.py [--blocks 20000] [--lines 100000] [--repeat 3] [--ring] [--docs]

``--docs`` also writes what it prints into its own section of docs/benchmarks.md.

The targets (issue 34): export of the 20,000-block program (and of the ring)
within 2 s and 300 MB; reading 100,000 PMAC lines within 0.4 s. The machine's
speed drifts by half over an hour: the ratios to the floors and peers printed
beside each figure are the steadier measure.
"""
from __future__ import annotations

import argparse
import math
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
# the bench folder's own modules, also when a test loads this file by its path
sys.path.insert(0, str(Path(__file__).resolve().parent))

from ccopt.compensate import compensate  # noqa: E402
from ccopt.export import export  # noqa: E402
from ccopt.program import read_text  # noqa: E402
from ccopt.program.model import unread  # noqa: E402
from ccopt.verify import verify  # noqa: E402
from docs_section import ROOT, printed_section  # noqa: E402

#: Tool diameter of the G-code program's tool table (mm).
TOOL_DIAMETER = 6.0
#: Every ARC_EVERY-th contour block is an arc (the rest are chords).
ARC_EVERY = 25
#: An arc spans this many chords of the curve.
ARC_SPAN = 16
#: Targets of issue 34.
EXPORT_SECONDS, EXPORT_MB, READ_SECONDS = 2.0, 300.0, 0.4
#: The words of a line and their numbers, the reading floor.
WORD_RE = re.compile(r"([A-Z]+)[ \t]*([-+]?[\d.]+)")


def curve(n: int) -> list[tuple[float, float]]:
    """``n`` points of a closed wavy curve, clockwise, r = R (1 + sin(7 theta) / 20)
    with R = 100 mm for 20,000 points and more in proportion (chords about
    0.03 mm long), rounded to 4 decimals as CAM writes them."""
    big = 100.0 * max(1.0, n / 20_000)
    pts = []
    for k in range(n):
        t = -2.0 * math.pi * k / n
        r = big * (1.0 + math.sin(7.0 * t) / 20.0)
        pts.append((round(r * math.cos(t), 4), round(r * math.sin(t), 4)))
    return pts


def circle(p, q, s):
    """Centre of the circle through three points, ``None`` when they are
    nearly collinear (the middle one within 1e-3 of the chord)."""
    bx, by = q[0] - p[0], q[1] - p[1]
    cx, cy = s[0] - p[0], s[1] - p[1]
    d = 2.0 * (bx * cy - by * cx)
    if abs(d) <= 2e-3 * 2.0 * math.hypot(cx, cy):
        return None
    b2, c2 = bx * bx + by * by, cx * cx + cy * cy
    return p[0] + (cy * b2 - by * c2) / d, p[1] + (bx * c2 - cx * b2) / d


def moves(n: int):
    """``(kind, end, centre offset from the start or None)`` of the contour,
    ``n`` moves back to the first point: chords, and every ARC_EVERY-th move an
    arc over the next ARC_SPAN points (through the written ends and middle
    one), or one long chord there where the curve is nearly straight."""
    arcs = [m % ARC_EVERY == ARC_EVERY - 1 and m != n - 1 for m in range(n)]
    pts = curve(n + (ARC_SPAN - 1) * sum(arcs))
    out = []
    k = 0
    for m in range(n):
        q = pts[(k + (ARC_SPAN if arcs[m] else 1)) % len(pts)]
        c = circle(pts[k], pts[k + ARC_SPAN // 2], q) if arcs[m] else None
        if c is None:
            out.append(("line", q, None))
        else:
            p, mid = pts[k], pts[k + ARC_SPAN // 2]
            cross = (mid[0] - p[0]) * (q[1] - p[1]) - (mid[1] - p[1]) * (q[0] - p[0])
            out.append(("cw" if cross < 0 else "ccw", q, (c[0] - p[0], c[1] - p[1])))
        k += ARC_SPAN if arcs[m] else 1
    return out, pts[0]


def gcode_program(blocks: int) -> str:
    """A CAM-like G-code profile with ``blocks`` lines in all."""
    contour, start = moves(blocks - 12)
    lines = ["%", "(ccopt bench: CAM-like profile)", "G21 G17 G90 G94", "T1 M6",
             "G0 Z5", f"G0 X{start[0] + 20:.4f} Y{start[1]:.4f}", "G1 Z-1 F600",
             f"G41 D1 G1 X{start[0]:.4f} Y{start[1]:.4f} F1200"]
    for kind, (x, y), off in contour:
        if kind == "line":
            lines.append(f"G1 X{x:.4f} Y{y:.4f}")
        else:
            g = "G2" if kind == "cw" else "G3"
            lines.append(f"{g} X{x:.4f} Y{y:.4f} I{off[0]:.6f} J{off[1]:.6f}")
    lines += [f"G40 G1 X{start[0] + 20:.4f} Y{start[1]:.4f}", "G0 Z5", "M2", "%"]
    return "\n".join(lines) + "\n"


def pmac_program(n_lines: int) -> str:
    """A PMAC program of ``n_lines`` lines: LINEAR/CIRCLE1 moves, CC1 ... CC0,
    and every 1000 lines a P-variable set and a move written with it."""
    contour, start = moves(n_lines - 12)
    lines = ["CLOSE", "OPEN PROG 1 CLEAR", "P1=0.25 P2=2", "NORMAL K-1 ABS LINEAR F50",
             "CCR3", f"RAPID X{start[0] + 20:.4f} Y{start[1]:.4f}", "LINEAR",
             f"CC1 X{start[0]:.4f} Y{start[1]:.4f} ; lead-in"]
    mode = "LINEAR"
    for m, (kind, (x, y), off) in enumerate(contour):
        word = "LINEAR" if kind == "line" else ("CIRCLE1" if kind == "cw" else "CIRCLE2")
        head = "" if word == mode else word + " "
        mode = word
        if m % 1000 == 500 and kind == "line":
            # the same point through the variables (P1 * 4 = 1, P2 / 2 = 1)
            lines.append(f"{head}X({x:.4f}*P1*4) Y({y:.4f}*P2/2)")
        elif kind == "line":
            lines.append(f"{head}X{x:.4f} Y{y:.4f}")
        else:
            lines.append(f"{head}X{x:.4f} Y{y:.4f} I{off[0]:.6f} J{off[1]:.6f}")
    lines += ["LINEAR" if mode != "LINEAR" else "", f"CC0 X{start[0] + 20:.4f} Y{start[1]:.4f}",
              "DWELL0", "CLOSE"]
    return "\n".join(lines) + "\n"


def ring_program(n: int = 20_000, seed: int = 1) -> str:
    """The noisy ring of ``--ring`` (see the module docstring), as PMAC text."""
    import random
    rng = random.Random(seed)
    lines = ["OPEN PROG 1 CLEAR", "CCR2", "F100", "LINEAR", "X230 Y0", "CC2"]
    for k in range(n + 1):
        t = 2.0 * math.pi * (k % n) / n
        r = 200.0 + 3.0 * math.sin(37.0 * t) + (rng.uniform(-0.01, 0.01) if k % n else 0.0)
        lines.append(f"X{r * math.cos(t):.4f} Y{r * math.sin(t):.4f}")
    lines += ["CC0", "X230 Y0", "CLOSE"]
    return "\n".join(lines) + "\n"


def floor_split(text: str) -> int:
    """Reading floor: every word and number of the text as floats."""
    n = 0
    for line in text.upper().split("\n"):
        for _, num in WORD_RE.findall(line.split(";", 1)[0]):
            try:
                float(num)
            except ValueError:
                continue
            n += 1
    return n


def timed(fn, repeat: int):
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def peak_rss_mb() -> float:
    """This process's peak resident set (MB): Linux's VmHWM, which starts
    afresh at exec (``ru_maxrss`` keeps the parent's peak across fork and
    exec), else ``ru_maxrss``."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return float(line.split()[1]) / 1024.0
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _child(blocks: int, style: str, what: str) -> None:
    """Peak resident memory (MB) after the imports and after one export (or,
    ``what == "verify"``, one verification of the compensated path, as a peer)."""
    base = peak_rss_mb()
    prog = read_text(gcode_program(blocks), "bench.nc", "gcode", tool_table={1: TOOL_DIAMETER})
    path = compensate(prog, style=style)
    if what == "verify":
        verify(path, prog)
    else:
        with tempfile.TemporaryDirectory() as d:
            export(path, Path(d) / "out.nc", program=prog)
    print(f"{base:.1f} {peak_rss_mb():.1f}")


def peak_memory(blocks: int, style: str, what: str) -> tuple[float, float]:
    """``(after the imports, peak)`` MB of a fresh process running ``_child``."""
    out = subprocess.run([sys.executable, __file__, "--child", what, "--blocks", str(blocks),
                          "--style", style], capture_output=True, text=True, check=True)
    base, peak = out.stdout.split()
    return float(base), float(peak)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--blocks", type=int, default=20_000)
    ap.add_argument("--lines", type=int, default=100_000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--style", default="linuxcnc",
                    help="compensation style of the G-code program (default linuxcnc, as "
                         "ccopt export does for G-code)")
    ap.add_argument("--child", choices=("export", "verify"), help=argparse.SUPPRESS)
    ap.add_argument("--skip-export", action="store_true", help="time reading only")
    ap.add_argument("--ring", action="store_true", help="also export the noisy ring (slow)")
    ap.add_argument("--docs", action="store_true",
                    help="also write what it prints into docs/benchmarks.md (its own section)")
    args = ap.parse_args()
    if args.child:
        _child(args.blocks, args.style, args.child)
        return
    command = " ".join(["python bench/io.py", *(a for a in sys.argv[1:] if a != "--docs")])
    with printed_section(ROOT / "docs" / "benchmarks.md" if args.docs else None,
                         "bench/io.py", command,
                         "Reading and exporting long programs (bench/io.py)"):
        io_bench(args)


def io_bench(args) -> None:
    """Read, compensate and export the generated programs (see the module docstring)."""
    gtext = gcode_program(args.blocks)
    ptext = pmac_program(args.lines)
    table = {1: TOOL_DIAMETER}
    print(f"G-code program: {gtext.count(chr(10))} lines; PMAC program: "
          f"{ptext.count(chr(10))} lines; median of {args.repeat}")

    t_pfloor, _ = timed(lambda: floor_split(ptext), args.repeat)
    t_pread, pprog = timed(lambda: read_text(ptext, "bench.pmc", "pmac"), args.repeat)
    t_pcomp, _ = timed(lambda: compensate(unread(pprog), style="pmac"), args.repeat)
    print(f"PMAC   read {t_pread:7.3f} s  (target {READ_SECONDS:g} s: {t_pread / READ_SECONDS:.2f}x)"
          f"  floor (regex split) {t_pfloor:.3f} s: read/floor {t_pread / t_pfloor:.1f}x;"
          f"  compensate {t_pcomp:.3f} s: read/compensate {t_pread / t_pcomp:.2f}x"
          f"  [{len(pprog.blocks)} blocks]")

    t_gfloor, _ = timed(lambda: floor_split(gtext), args.repeat)
    t_gread, gprog = timed(lambda: read_text(gtext, "bench.nc", "gcode", tool_table=table),
                           args.repeat)
    t_gcomp, gpath = timed(lambda: compensate(unread(gprog), style=args.style), args.repeat)
    print(f"G-code read {t_gread:7.3f} s  floor (regex split) {t_gfloor:.3f} s: read/floor "
          f"{t_gread / t_gfloor:.1f}x;  compensate {t_gcomp:.3f} s  "
          f"[{len(gprog.blocks)} blocks, {len(gpath.segments)} segments]")
    if args.skip_export:
        return
    t_ver, _ = timed(lambda: verify(gpath, gprog), args.repeat)
    with tempfile.TemporaryDirectory() as d:
        t_exp, res = timed(lambda: export(gpath, Path(d) / "out.nc", program=gprog), args.repeat)
        t_pexp, _ = timed(lambda: export(gpath, Path(d) / "out.pmc", program=gprog), args.repeat)
    print(f"export .nc  {t_exp:7.3f} s  (target {EXPORT_SECONDS:g} s: "
          f"{t_exp / EXPORT_SECONDS:.2f}x; verified {res.verified}, read back within "
          f"{res.roundtrip_error:.3g})")
    print(f"export .pmc {t_pexp:7.3f} s;  peer: verify of the computed path alone "
          f"{t_ver:.3f} s (export verifies the read-back, and the computed path too when a "
          f"fitted move of the read-back gouges)")
    if args.ring:
        rprog = read_text(ring_program(), "ring.pmc", "pmac")
        rpath = compensate(rprog, style="pmac")
        with tempfile.TemporaryDirectory() as d:
            t_ring, rres = timed(lambda: export(rpath, Path(d) / "ring.nc", program=rprog),
                                 args.repeat)
        cert = rres.verdict
        print(f"export ring {t_ring:7.3f} s  (target {EXPORT_SECONDS:g} s: "
              f"{t_ring / EXPORT_SECONDS:.2f}x; {len(rpath.segments)} segments, verified "
              f"{rres.verified}: {len(cert.violations) if cert else 0} violations, "
              f"{rres.fitted_moves} fitted moves)")
    base, peak = peak_memory(args.blocks, args.style, "export")
    _, peak_verify = peak_memory(args.blocks, args.style, "verify")
    print(f"peak memory (read + compensate + export .nc, fresh process): {peak:.0f} MB "
          f"(target {EXPORT_MB:g} MB: {peak / EXPORT_MB:.2f}x); after the imports alone "
          f"{base:.0f} MB; peer: read + compensate + verify alone {peak_verify:.0f} MB")


if __name__ == "__main__":
    main()

"""Benchmark: ccopt's vectorised distance kernels against shapely 2.

Run as ``python bench/geometry.py [--n 100000] [--repeat 7] [--seed 0]``.

Both libraries see the same 1e5 seeded random segment pairs in the same run,
timed in alternating turns so that load from elsewhere hits both alike;
shapely's ``LineString`` geometries are built outside the timed region, as are
ccopt's coordinate arrays, so only the distance computation is timed. Prints
the median (and minimum) wall time of each, the ratio ccopt/shapely, and the largest
absolute difference between the two sets of distances. ``segment_arc`` and
``arc_arc`` on 1e5 pairs, and ``pair_distance`` on 1e5 index pairs into a
packed mix of lines and arcs (the verifier's call), are timed for information
(shapely has no exact arcs).
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ccopt.geometry import Arc, Line, SegmentArray  # noqa: E402
from ccopt.geometry.distance import (  # noqa: E402
    arc_arc, pair_distance, segment_arc, segment_segment)


def interleaved_times(fns, repeat: int) -> list[tuple[float, float, object]]:
    """``(median, min, last output)`` for each function, timed in turns.

    Each round runs every function once, so a burst of load from elsewhere on
    the machine hits all of them alike and the ratio stays fair.
    """
    outs = [fn() for fn in fns]                   # warm-up (allocations, imports)
    times = [[] for _ in fns]
    for _ in range(repeat):
        for k, fn in enumerate(fns):
            t0 = time.perf_counter()
            outs[k] = fn()
            times[k].append(time.perf_counter() - t0)
    return [(statistics.median(t), min(t), o) for t, o in zip(times, outs)]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100_000)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)

    import shapely

    rng = np.random.default_rng(args.seed)
    n = args.n
    a0 = rng.uniform(-10, 10, (n, 2))
    a1 = rng.uniform(-10, 10, (n, 2))
    b0 = rng.uniform(-10, 10, (n, 2))
    b1 = rng.uniform(-10, 10, (n, 2))
    ga = shapely.linestrings(np.stack([a0, a1], axis=1))
    gb = shapely.linestrings(np.stack([b0, b1], axis=1))

    c = rng.uniform(-8, 8, (n, 2))
    R = rng.uniform(0.2, 5, n)
    th = rng.uniform(-np.pi, np.pi, n)
    sw = rng.uniform(-2 * np.pi, 2 * np.pi, n)
    c2 = rng.uniform(-8, 8, (n, 2))
    R2 = rng.uniform(0.2, 5, n)
    th2 = rng.uniform(-np.pi, np.pi, n)
    sw2 = rng.uniform(-2 * np.pi, 2 * np.pi, n)

    (t_ccopt, tmin_ccopt, (d_ccopt, _, _)), (t_shapely, tmin_shapely, d_shapely) = interleaved_times(
        [lambda: segment_segment(a0, a1, b0, b1), lambda: shapely.distance(ga, gb)], args.repeat)
    diff = float(np.max(np.abs(d_ccopt - d_shapely)))
    (t_sa, tmin_sa, _), (t_aa, tmin_aa, _) = interleaved_times(
        [lambda: segment_arc(a0, a1, c, R, th, sw),
         lambda: arc_arc(c, R, th, sw, c2, R2, th2, sw2)], args.repeat)

    print(f"pairs: {n}  repeats: {args.repeat}  seed: {args.seed}  "
          f"numpy {np.__version__}  shapely {shapely.__version__}")
    print(f"segment_segment  ccopt    median {t_ccopt * 1e3:8.2f} ms   min {tmin_ccopt * 1e3:8.2f} ms")
    print(f"segment_segment  shapely  median {t_shapely * 1e3:8.2f} ms   min {tmin_shapely * 1e3:8.2f} ms")
    print(f"ratio ccopt/shapely (medians): {t_ccopt / t_shapely:.3f}  "
          f"({'ccopt no slower' if t_ccopt <= t_shapely else 'ccopt SLOWER'})")
    print(f"max |d_ccopt - d_shapely|: {diff:.3g}")
    print(f"segment_arc      ccopt    median {t_sa * 1e3:8.2f} ms   min {tmin_sa * 1e3:8.2f} ms")
    print(f"arc_arc          ccopt    median {t_aa * 1e3:8.2f} ms   min {tmin_aa * 1e3:8.2f} ms")

    # What the verifier calls: arbitrary index pairs over packed lines and arcs.
    segs = []
    for k in range(2000):
        if k % 2:
            segs.append(Line(tuple(rng.uniform(-10, 10, 2)), tuple(rng.uniform(-10, 10, 2))))
        else:
            segs.append(Arc(tuple(rng.uniform(-8, 8, 2)), rng.uniform(0.2, 5),
                            rng.uniform(-np.pi, np.pi), rng.uniform(-2 * np.pi, 2 * np.pi)))
    packed = SegmentArray.from_segments(segs)
    ia = rng.integers(0, len(segs), n)
    ib = rng.integers(0, len(segs), n)
    [(t_pd, tmin_pd, _)] = interleaved_times([lambda: pair_distance(packed, ia, packed, ib)],
                                             args.repeat)
    print(f"pair_distance    ccopt    median {t_pd * 1e3:8.2f} ms   min {tmin_pd * 1e3:8.2f} ms"
          f"   ({n} pairs, half lines half arcs)")
    return 0 if diff <= 1e-9 else 1


if __name__ == "__main__":
    raise SystemExit(main())

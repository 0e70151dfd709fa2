"""``ccopt compare`` and ``ccopt smooth`` (added to the parser by :func:`add_commands`)."""
from __future__ import annotations

import argparse
import math

from ccopt.errors import ProgramError


def add_commands(sub, commands: dict, program_args, axis_values, nonneg_float, positive_float):
    """Register the two subcommands on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("compare", help="compare lead-in/lead-out/corner variants, certified "
                                       "and timed")
    p.add_argument("program", metavar="PROGRAM", help="program file, case folder or case name")
    program_args(p)
    p.add_argument("--variants", type=variant_names, action="append", metavar="NAME[,NAME]",
                   help="variants to compare (default: every available one; see --list)")
    p.add_argument("--list", action="store_true", help="list the available variants and exit")
    _common(p, axis_values, nonneg_float, positive_float)
    p.add_argument("--lead-radius", type=positive_float, metavar="R",
                   help="radius of the tangent-arc and line-arc leads (default: the cutter radius)")
    p.add_argument("--plot", metavar="FILE", help="plot the variants over the contour (PNG/SVG/PDF)")
    commands["compare"] = cmd_compare

    p = sub.add_parser("smooth", help="G2 blends at every corner within a tolerance band")
    p.add_argument("program", metavar="PROGRAM", help="program file, case folder or case name")
    program_args(p)
    _common(p, axis_values, nonneg_float, positive_float)
    p.add_argument("-o", "--out", metavar="FILE",
                   help="export the smoothed path (.nc/.pmc/.svg/.json, read back and verified)")
    commands["smooth"] = cmd_smooth


def _common(p, axis_values, nonneg_float, positive_float):
    p.add_argument("--delta", type=positive_float, metavar="D",
                   help="tolerance band of the smoother, program units (default: 1%% of the "
                        "cutter radius)")
    p.add_argument("--radius", type=nonneg_float, metavar="R",
                   help="cutter radius in program units, overriding the program")
    p.add_argument("--side", choices=["left", "right"],
                   help="compensation side wherever it is on, overriding the program")
    p.add_argument("--vmax", type=axis_values, metavar="X,Y[,Z]",
                   help="axis velocity limits, units/s (default: the case's [limits] v)")
    p.add_argument("--amax", type=axis_values, metavar="X,Y[,Z]",
                   help="axis acceleration limits, units/s^2 (default: the case's [limits] a)")


def variant_names(text: str) -> list[str]:
    """``A,B`` -> ``["A", "B"]`` (argparse type of ``--variants``)."""
    return [n.strip() for n in text.split(",") if n.strip()]


def _limits(inp, args):
    from ccopt.feed import AxisLimits
    vmax = args.vmax or (inp.case.vmax if inp.case else None)
    amax = args.amax or (inp.case.amax if inp.case else None)
    if vmax is None or amax is None:
        raise ProgramError("no axis limits: give --vmax and --amax (X,Y[,Z]) or use a case "
                           "whose case.toml has [limits]", str(inp.program))
    try:
        return AxisLimits(vmax, amax)
    except ValueError as exc:
        raise ProgramError(f"bad limits: {exc}", str(inp.program)) from None


def _radius(inp, args):
    r = args.radius
    if r is None and inp.case is not None:
        r = inp.case.radius
    return r


def _f(x, fmt="{:.4f}"):
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, float) and not math.isfinite(x):
        return str(x)
    return fmt.format(x) if isinstance(x, (int, float)) else str(x)


def cmd_compare(args: argparse.Namespace) -> int:
    from ccopt.cli import EXIT_OK, emit_json, load, resolve_input
    from ccopt.compare import available, compare
    from ccopt.compare.registry import require_known
    if args.list:
        for n in available():
            print(n)
        return EXIT_OK
    names = [n for group in (args.variants or []) for n in group] or None
    if names:
        require_known(names, args.program)
    inp = resolve_input(args.program)
    prog = load(inp, args)
    limits = _limits(inp, args)
    options = {}
    if args.lead_radius is not None:
        options["lead_radius"] = args.lead_radius
    cmp = compare(prog, names, limits=limits, delta=args.delta, radius=_radius(inp, args),
                  side=args.side, options=options)
    doc = cmp.to_json()
    if args.plot:
        from ccopt.compare.plot import plot_comparison
        doc["plot"] = plot_comparison(cmp, args.plot, f"{inp.label}: variants")
    if args.json:
        emit_json(doc)
        return EXIT_OK
    r = doc["radius"]
    print(f"{prog.file}: reference pmac, cutter radius {_f(r, '{:g}')} {prog.units}, limits "
          f"v={list(limits.v)} a={list(limits.a)}")
    cols = [("variant", "name", "{}"), ("status", "status", "{}"), ("cycle_s", "duration", "{:.4f}"),
            ("vs_pmac", "duration_ratio", "{:.4f}"), ("length", "length", "{:.3f}"),
            ("max_curv", "max_curvature", "{:.3f}"), ("curv_jump", "max_curvature_jump", "{:.3f}"),
            ("joins", "continuity", "{}"), ("path", "path_continuity", "{}"),
            ("min_clear", "min_clearance", "{:.6f}"), ("certified", "certified", "{}"),
            ("max_dev", "max_deviation", "{:.4f}"), ("solve_s", "solve_time", "{:.3f}")]
    rows = [[h for h, _, _ in cols]]
    for v in doc["variants"]:
        rows.append([_f(v.get(k), f) for _, k, f in cols])
    w = [max(len(r[c]) for r in rows) for c in range(len(cols))]
    for r in rows:
        print("  ".join(c.ljust(wi) for c, wi in zip(r, w)).rstrip())
    for v in doc["variants"]:
        if v["status"] != "ok" or v.get("message"):
            print(f"  {v['name']}: {v['message']}")
    if args.plot:
        print(f"plot: {doc['plot']}")
    return EXIT_OK


def _feed_floor(path, limits) -> float | None:
    """:func:`ccopt.feed.feed_limited_time` (s), ``None`` when the limits do not fit the path
    (the cycle time says why)."""
    from ccopt.feed import feed_limited_time
    try:
        return feed_limited_time(path, limits)
    except ValueError:
        return None


def cmd_smooth(args: argparse.Namespace) -> int:
    from ccopt.cli import EXIT_FAILED, EXIT_OK, emit_json, load, resolve_input
    from ccopt.compare import BlendOutcome, BlendProblem, measure
    from ccopt.compare.registry import load as load_blend
    from ccopt.compensate import compensate
    inp = resolve_input(args.program)
    prog = load(inp, args)
    limits = _limits(inp, args)
    try:
        blend = load_blend("smooth")
    except KeyError:
        raise ProgramError("the smoother is not installed: no 'smooth' entry point in group "
                           "ccopt.blends (install ccopt with its formulations)",
                           args.program) from None
    radius = _radius(inp, args)
    ref = compensate(prog, "pmac", radius=radius, side=args.side)
    problem = BlendProblem(prog, ref, limits, args.delta, {}, radius, args.side)
    import time
    t0 = time.perf_counter()
    out = blend(problem)
    solve = time.perf_counter() - t0
    info = dict(out.info) if isinstance(out, BlendOutcome) else {}
    path = out.toolpath if isinstance(out, BlendOutcome) else out
    cert = info.pop("certificate", None)
    row = measure("smooth", path, problem, solve, info, cert)
    base = measure("pmac", ref, problem, 0.0)
    fig = row.figures
    ratio = fig["duration"] / base.figures["duration"] if fig.get("duration") and \
        base.figures.get("duration") else None
    doc = {"program": prog.file, "delta": problem.band, "radius": ref.radius,
           "duration": fig.get("duration"), "pmac_duration": base.figures.get("duration"),
           "duration_ratio": ratio,
           # what neither path can beat (no acceleration limit at all): how much any
           # smoothing of PMAC's path could buy
           "feed_floor": _feed_floor(path, limits), "pmac_feed_floor": _feed_floor(ref, limits),
           **{k: fig.get(k) for k in ("min_clearance", "certified", "max_deviation",
                                      "max_deviation_bound", "continuity", "path_continuity",
                                      "max_curvature", "tangent_breaks", "solve_time")},
           "joins": info.get("joins", []), "certificate": row.certificate.to_json(),
           "toolpath": path.to_json()}
    exported = None
    if args.out:
        from ccopt.export import export
        try:
            exported = export(path, args.out, program=prog)
            doc["export"] = exported.to_json()
        except ValueError as exc:  # the arc fit of a blend curve gave up (too many pieces)
            raise ProgramError(f"cannot export the smoothed path: {exc}", args.out) from None
    if args.json:
        emit_json(doc)
    else:
        blended = sum(1 for j in doc["joins"] if j["status"] == "blended")
        print(f"{prog.file}: smoothed within delta {problem.band:g} {prog.units} "
              f"(cutter radius {ref.radius:g}): {blended} of {len(doc['joins'])} joins blended")
        floor = doc["pmac_feed_floor"]
        floor_txt = "" if floor is None or not doc["pmac_duration"] else (
            f"; feed-limited floor {floor:.4f} s ({floor / doc['pmac_duration']:.4f})")
        print(f"  cycle time {_f(doc['duration'])} s vs PMAC {_f(doc['pmac_duration'])} s "
              f"(ratio {_f(ratio)}){floor_txt}")
        print(f"  certified {_f(doc['certified'])}, min clearance {_f(doc['min_clearance'], '{:.9f}')}"
              f", max deviation {_f(doc['max_deviation'], '{:.6f}')} (bound "
              f"{_f(doc['max_deviation_bound'], '{:.6f}')}), joins {doc['continuity']}, "
              f"max curvature {_f(doc['max_curvature'], '{:.3f}')}")
        for j in doc["joins"]:
            if j["status"] != "blended":
                print(f"  join at segment {j['segment']} ({j['kind']}): {j['status']}")
        if exported is not None:
            verdict = {True: "verified OK", False: "verification FAILED",
                       None: "not verified"}[exported.verified]
            print(f"  exported {exported.file}: read back within "
                  f"{exported.roundtrip_error:.3g} {prog.units}, {verdict}")
    # the written file is what runs on the machine: its own verdict counts too
    ok = row.certificate.ok and (exported is None or exported.verified is not False)
    return EXIT_OK if ok else EXIT_FAILED

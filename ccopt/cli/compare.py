"""``ccopt compare`` and ``ccopt smooth``: blend variants side by side, and the smoother alone."""
from __future__ import annotations

import argparse

from ccopt.cases import Job
from ccopt.cli.inputs import limits_text, limits_words, reading
from ccopt.cli.options import (add_limit_options, add_output_option, add_program,
                               add_quiet_option, add_radius_side, add_reading_options,
                               add_tolerance_option, add_ts_option, add_variants_option,
                               add_workers_option, chosen_variants, describe, nonneg_int,
                               positive_float)
from ccopt.cli.output import EXIT_FAILED, EXIT_OK, aligned, emit_json, figure, nothing_to_do
from ccopt.compare import REFERENCE, BlendProblem, Comparison, available
from ccopt.compare.plot import check_plot_name, plot_comparison
from ccopt.compare.registry import require_known
from ccopt.errors import ProgramError
from ccopt.export import ExportResult, export
from ccopt.feed import AxisLimits
from ccopt.feed.bounds import feed_limited_time
from ccopt.pipeline import StageClock, pipeline
from ccopt.program.model import Program
from ccopt.toolpath import ToolPath
from ccopt.workers import resolve_workers

#: the comparison table: header, figure of :meth:`Comparison.to_json`'s variants, format
COLUMNS = [("variant", "name", "{}"), ("status", "status", "{}"), ("cycle_s", "duration", "{:.4f}"),
           ("vs_pmac", "duration_ratio", "{:.4f}"),
           ("gain_best", "gain_vs_fastest_controller", "{:+.4f}"), ("length", "length", "{:.3f}"),
           ("max_curv", "max_curvature", "{:.3f}"), ("curv_jump", "max_curvature_jump", "{:.3f}"),
           ("joins", "continuity", "{}"), ("path", "path_continuity", "{}"),
           ("min_clear", "min_clearance", "{:.6f}"), ("certified", "certified", "{}"),
           ("max_dev", "max_deviation", "{:.4f}"), ("solve_s", "solve_time", "{:.3f}")]

#: the figures of the smoothed path ``ccopt smooth`` reports as they are
SMOOTH_FIGURES = ("min_clearance", "certified", "max_deviation", "max_deviation_bound",
                  "continuity", "path_continuity", "max_curvature", "tangent_breaks",
                  "solve_time")


COMPARE_DESCRIPTION = """\
Every lead-in, lead-out and corner variant of PROGRAM side by side: the
controller styles, the geometric leads (tangent-arc, line-arc), HEIDENHAIN's
APPR/DEP leads (heidenhain-lt, -ln, -ct, -lct) and the optimised G2 blends registered as ccopt.blends entry points (opt-casadi,
opt-cvxpy, smooth). Each is certified by the verifier (an optimised blend is
only accepted certified) and timed under the axis limits (--vmax/--amax/--jmax,
else the case's [limits], else 100 units/s and 1000 units/s^2 per axis; the
output prints them and where they come from) against PMAC's path; a
variant a controller refuses is listed with its message. Variants run in
--workers processes (default one per core)."""

COMPARE_EXAMPLE = """\
  ccopt compare cases/leadin-inside-line
  ccopt compare pocket --variants pmac,opt-casadi -o variants.png"""

SMOOTH_DESCRIPTION = """\
The whole-path smoother alone: a G2 blend at every tangent break and
curvature jump of PMAC's path, within --delta of it (default 1% of the cutter
radius) and at least the cutter radius from the contour, certified and timed
against PMAC's path under the axis limits (as compare's; the output prints
them and where they come from). -o exports the smoothed path
(.nc/.pmc/.svg/.json, read back and verified). Exit 1 when the result or the
written file is not certified."""

SMOOTH_EXAMPLE = """\
  ccopt smooth cases/pocket-chords -o pocket-smooth.nc"""


def cmd_compare(args: argparse.Namespace) -> int:
    """Every blend variant (or ``--variants``) of the program, certified and timed."""
    if args.list:
        for n in available():
            print(n)
        return EXIT_OK
    names = chosen_variants(args)
    if names:
        require_known(names, args.program)
    with reading(args, "compare") as (work, prog, say):
        if args.output:
            check_plot_name(args.output)        # before the comparison, not after it
        if prog.nothing_to_verify():
            return nothing_to_do(args, prog, "compare")
        done = pipeline(work, program=prog, compensate=False, feed=False, verify=False,
                        compare=True, workers=resolve_workers(args.workers),
                        clock=StageClock(say)).result()
        cmp, limits = done.comparison, done.limits
    doc = cmp.to_json()
    if args.output:
        doc["plot"] = plot_comparison(cmp, args.output, f"{work.label}: variants")
    if args.json:
        emit_json(doc)
        return EXIT_OK
    if args.quiet:
        return EXIT_OK
    print(f"{prog.file}: reference pmac, cutter radius {figure(doc['radius'], '{:g}')} "
          f"{prog.units}, {limits_text(limits, work)}")
    rows = [[h for h, _, _ in COLUMNS]]
    for v in doc["variants"]:
        rows.append([figure(v.get(k), f) for _, k, f in COLUMNS])
    print(aligned(rows))
    for v in doc["variants"]:
        if v["status"] != "ok" or v.get("message"):
            print(f"  {v['name']}: {v['message']}")
    if args.output:
        print(f"plot: {doc['plot']}")
    return EXIT_OK


def _feed_floor(path: ToolPath, limits: AxisLimits) -> float | None:
    """:func:`ccopt.feed.feed_limited_time` (s), ``None`` when the limits do not fit the path
    (the cycle time says why)."""
    try:
        return feed_limited_time(path, limits)
    except ValueError:
        return None


def _smoothed(cmp: Comparison, work: Job, prog: Program,
              limits: AxisLimits) -> tuple[dict, ToolPath, bool]:
    """The smoother's row of the comparison ``cmp`` (of PMAC's path and the
    smoother's, :func:`ccopt.pipeline.pipeline`) measured against the
    reference: the JSON document of ``ccopt smooth``, the path, and whether
    its certificate holds. A ProgramError when PMAC refuses the program or the
    smoother gives no path (its row says why)."""
    row, base = cmp["smooth"], cmp[REFERENCE]
    for r in (base, row):
        if r.toolpath is None:
            raise ProgramError(f"{r.name} {r.status}: {r.message}", prog.file)
    path, ref = row.toolpath, cmp.reference
    fig, info = row.figures, row.info
    ratio = fig["duration"] / base.figures["duration"] if fig.get("duration") and \
        base.figures.get("duration") else None
    doc = {"program": prog.file, "delta": BlendProblem(prog, ref, delta=work.delta).band,
           "radius": ref.radius, "duration": fig.get("duration"),
           "pmac_duration": base.figures.get("duration"), "duration_ratio": ratio,
           # what neither path can beat (no acceleration limit at all): how much any
           # smoothing of PMAC's path could buy
           "feed_floor": _feed_floor(path, limits), "pmac_feed_floor": _feed_floor(ref, limits),
           **{k: fig.get(k) for k in SMOOTH_FIGURES},
           "joins": info.get("joins", []), "certificate": row.certificate.to_json(),
           "toolpath": path.to_json()}
    if limits.j is not None:
        doc.update(_jerk_figures(row, base, doc["feed_floor"]))
    return doc, path, row.certificate.ok


def _jerk_figures(row, base, floor: float | None) -> dict:
    """Cycle times (s) of the smoothed (``row``) and PMAC's path (``base``) under
    the jerk planner, their ratio, and the share of the possible gain reached:
    ``(T_pmac - T_smooth) / (T_pmac - floor)`` with ``floor`` the smoothed path's
    feed-limited time (what no smoothing can beat). Under jerk limits the rows'
    durations are already the jerk planner's (:func:`ccopt.feed.certified_planner`),
    so nothing is planned again (the smoothed ``freeform-hsm`` takes about a
    minute). A path the planner failed on gets ``None`` and its message."""
    out: dict = {}
    for key, r in (("jerk_duration", row), ("pmac_jerk_duration", base)):
        out[key] = r.figures.get("duration")
        if out[key] is None and r.message:
            out[key + "_message"] = r.message
    t, t_ref = out["jerk_duration"], out["pmac_jerk_duration"]
    both = t is not None and t_ref is not None
    out["jerk_duration_ratio"] = t / t_ref if both else None
    out["jerk_share_of_gain"] = (t_ref - t) / (t_ref - floor) if both and floor is not None \
        and t_ref > floor else None
    return out


def cmd_smooth(args: argparse.Namespace) -> int:
    """G2 blends at every corner within ``--delta``, certified, timed against
    PMAC's path and exported with ``-o`` (exit 1 when the certificate or the
    exported file's read-back fails)."""
    if "smooth" not in available():
        raise ProgramError("the smoother is not installed: no 'smooth' entry point in "
                           "group ccopt.blends (install ccopt with its formulations)",
                           args.program)
    with reading(args, "smooth", variants=(REFERENCE, "smooth")) as (work, prog, say):
        if prog.nothing_to_verify():
            return nothing_to_do(args, prog, "smooth")
        done = pipeline(work, program=prog, compensate=False, feed=False, verify=False,
                        compare=True, clock=StageClock(say)).result()
        limits = done.limits
        doc, path, certified = _smoothed(done.comparison, work, prog, limits)
        exported = None
        if args.output:
            say("export")
            exported = _export_smoothed(path, args.output, prog)
            doc["export"] = exported.to_json()
    doc.update(limits=limits.to_json(), limits_from=work.limits_from)
    if args.json:
        emit_json(doc)
    elif not args.quiet:
        _print_smoothed(doc, prog, exported)
    # the written file is what runs on the machine: its own verdict counts too
    ok = certified and (exported is None or exported.verified is not False)
    return EXIT_OK if ok else EXIT_FAILED


def _export_smoothed(path: ToolPath, output: str, prog: Program) -> ExportResult:
    """``path`` exported to ``output`` (read back and verified)."""
    try:
        return export(path, output, program=prog)
    except ValueError as exc:  # the arc fit of a blend curve gave up (too many pieces)
        raise ProgramError(f"cannot export the smoothed path: {exc}", output) from None


def _print_smoothed(doc: dict, prog: Program, exported: ExportResult | None) -> None:
    """The human-readable report of ``ccopt smooth``."""
    blended = sum(1 for j in doc["joins"] if j["status"] == "blended")
    print(f"{prog.file}: smoothed within delta {doc['delta']:g} {prog.units} "
          f"(cutter radius {doc['radius']:g}): {blended} of {len(doc['joins'])} joins blended")
    print(f"  {limits_words(doc['limits'], doc['limits_from'])}")
    floor = doc["pmac_feed_floor"]
    floor_txt = "" if floor is None or not doc["pmac_duration"] else (
        f"; feed-limited floor {floor:.4f} s ({floor / doc['pmac_duration']:.4f})")
    print(f"  cycle time {figure(doc['duration'])} s vs PMAC {figure(doc['pmac_duration'])} s "
          f"(ratio {figure(doc['duration_ratio'])}){floor_txt}")
    if "jerk_duration" in doc:
        print(f"  under jerk limits: {figure(doc['jerk_duration'])} s vs PMAC "
              f"{figure(doc['pmac_jerk_duration'])} s (ratio {figure(doc['jerk_duration_ratio'])}, "
              f"share of the possible gain {figure(doc['jerk_share_of_gain'])})")
        for key in ("jerk_duration_message", "pmac_jerk_duration_message"):
            if key in doc:
                print(f"  jerk planner: {doc[key]}")
    print(f"  certified {figure(doc['certified'])}, min clearance "
          f"{figure(doc['min_clearance'], '{:.9f}')}, max deviation "
          f"{figure(doc['max_deviation'], '{:.6f}')} (bound "
          f"{figure(doc['max_deviation_bound'], '{:.6f}')}), joins {doc['continuity']}, "
          f"max curvature {figure(doc['max_curvature'], '{:.3f}')}")
    for j in doc["joins"]:
        if j["status"] != "blended":
            print(f"  join at segment {j['segment']} ({j['kind']}): {j['status']}")
    if exported is not None:
        verdict = {True: "verified OK", False: "verification FAILED",
                   None: "not verified"}[exported.verified]
        print(f"  exported {exported.file}: read back within "
              f"{exported.roundtrip_error:.3g} {prog.units}, {verdict}{exported.where_written()}")


def _add_blend_options(p: argparse.ArgumentParser) -> None:
    """The smoother's band, the compensation overrides and the axis limits."""
    p.add_argument("--delta", type=positive_float, metavar="D",
                   help="tolerance band of the smoother, program units (default: 1%% of the "
                        "cutter radius)")
    add_radius_side(p)
    add_limit_options(p)
    add_ts_option(p)
    add_tolerance_option(p)
    add_quiet_option(p)


def add_commands(sub, commands: dict) -> None:
    """Register ``compare`` and ``smooth`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("compare", help="compare lead-in/lead-out/corner variants, certified "
                                       "and timed", **describe(COMPARE_DESCRIPTION,
                                                               COMPARE_EXAMPLE))
    add_program(p)
    add_reading_options(p)
    add_variants_option(p, "variants to compare (default: every available one; see --list)")
    p.add_argument("--list", action="store_true", help="list the available variants and exit")
    _add_blend_options(p)
    p.add_argument("--lead-radius", type=positive_float, metavar="R",
                   help="radius of the tangent-arc and line-arc leads (default: the cutter radius)")
    p.add_argument("--search", type=nonneg_int, metavar="N",
                   help="planner runs each optimised lead may spend searching for a blend of "
                        "lower cycle time, timed by the comparison's planner (default: 0, the "
                        "models' blends as they are)")
    add_output_option(p, "FILE", help="plot the variants over the contour (.png/.svg/.pdf)",
                      old=("--plot",))
    add_workers_option(p, "variants run in N worker processes (default: one per core; 1: one "
                          "after the other)")
    commands["compare"] = cmd_compare

    p = sub.add_parser("smooth", help="G2 blends at every corner within a tolerance band",
                       **describe(SMOOTH_DESCRIPTION, SMOOTH_EXAMPLE))
    add_program(p)
    add_reading_options(p)
    _add_blend_options(p)
    add_output_option(p, "FILE",
                      help="export the smoothed path (.nc/.pmc/.svg/.json, read back and verified)")
    commands["smooth"] = cmd_smooth

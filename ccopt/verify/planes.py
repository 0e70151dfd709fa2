"""Verifying a path that compensates in more than one plane, plane by plane.

A program may compensate in ``G17`` and, after ``G40``, in ``G18``. The
verifier's geometry is that of one plane (exact 2-D distances in ``(u, v)``),
so the path is cut where the program's plane changes: each *run* of blocks in
one plane is a program of its own whose contour checks the tool segments
made from those blocks (the segments of a block, or with no block those that
follow, in the segment's own plane). The certificate joins the runs'
certificates: every check holds when it holds in every run, its figure is
the worst of theirs (the smallest gouge and side margin, the largest contact
excess and jump), counts add up, and violations name the whole path's tool
segments and contour elements (numbered across the runs in order) with the
``plane`` their witness points lie in. Continuity is also checked where the
runs meet, in machine coordinates; the feed limits once, on the whole
profile. ``certificate.context`` is the context of the run where the
clearance is smallest (cross-checks look at that run).
"""
from __future__ import annotations

import math
from dataclasses import replace

from ccopt.program.columns import columns_of
from ccopt.program.model import Program
from ccopt.toolpath import FITTED_PIECES, ToolPath
from ccopt.verify.certificate import EXACT, Certificate, Check, Violation
from ccopt.verify.limits import check_limits

#: How a check's figure joins over the runs: the worst is the smallest
#: margin (gouge, side) or the largest excess (contact, jump).
WORST = {"gouge": min, "side": min, "contact": max, "continuity": max}


def plane_runs(toolpath: ToolPath, program: Program):
    """``[(tool path, program, segment indices)]`` per run of program blocks
    in one plane, or ``None`` when the program and the path lie in one plane
    (the plain route)."""
    # one plane in every block (the common case) is seen on the blocks' few
    # distinct modal objects, without walking the blocks in Python
    if len(columns_of(program).planes()) <= 1 and len(toolpath.planes) <= 1:
        return None
    runs: list[list] = []
    for blk in program.blocks:
        if not runs or blk.modal.plane != runs[-1][0]:
            runs.append([blk.modal.plane, []])
        runs[-1][1].append(blk)
    if len(runs) <= 1 and len(toolpath.planes) <= 1:
        return None
    run_of = {id(b): r for r, (_, blocks) in enumerate(runs) for b in blocks}
    members: list[list[int]] = [[] for _ in runs]
    cur = 0
    for i, seg in enumerate(toolpath.segments):
        r = run_of.get(id(seg.block)) if seg.block is not None else None
        if r is None:       # no block of the program: the next run in its plane
            r = next((q for q in range(cur, len(runs)) if runs[q][0] == seg.plane), cur)
        members[r].append(i)
        cur = r
    out = []
    for (plane, blocks), idx in zip(runs, members):
        start = program.start if blocks is runs[0][1] else blocks[0].start
        sub = Program(tuple(blocks), file=program.file, dialect=program.dialect,
                      units=program.units, start=start, meta=program.meta)
        local = {g: q for q, g in enumerate(idx)}
        fitted = tuple(local[g] for g in toolpath.meta.get(FITTED_PIECES, ()) if g in local)
        path = ToolPath(tuple(toolpath.segments[g] for g in idx), plane=plane,
                        style=toolpath.style, radius=toolpath.radius, units=toolpath.units,
                        meta={FITTED_PIECES: fitted})
        out.append((path, sub, idx))
    return out


def _remap(item: dict, idx: list[int], first_element: int) -> dict:
    """A detail entry with its tool segment and element numbered in the whole path."""
    out = dict(item)
    if isinstance(out.get("tool_segment"), int):
        out["tool_segment"] = idx[out["tool_segment"]]
    if isinstance(out.get("element"), int):
        out["element"] += first_element
    return out


def _join_detail(parts: list[tuple[dict, list[int], int]]) -> dict:
    """Counts add up, lists join (entries renumbered), anything else is the first run's."""
    out: dict = {}
    for detail, idx, first in parts:
        for key, value in detail.items():
            if isinstance(value, list):
                out.setdefault(key, []).extend(
                    _remap(v, idx, first) if isinstance(v, dict) else v for v in value)
            elif isinstance(value, int) and not isinstance(value, bool):
                out[key] = out.get(key, 0) + value
            else:
                out.setdefault(key, value)
    return out


def _join_check(name: str, checks: list[Check], parts) -> Check:
    figures = [c for c in checks if c.figure is not None]
    worst = WORST.get(name, max)(figures, key=lambda c: c.figure) if figures else checks[0]
    return replace(checks[0], ok=all(c.ok for c in checks), figure=worst.figure,
                   basis=worst.basis, count=sum(c.count for c in checks),
                   violations=sum(c.violations for c in checks),
                   detail=_join_detail([(c.detail, idx, first)
                                        for c, (idx, first) in zip(checks, parts)]))


def _junctions(toolpath: ToolPath, runs, eps: float) -> tuple[list[float], list[Violation]]:
    """Jumps (machine coordinates) where one run's segments give way to the next's."""
    run_of = {g: r for r, (_, _, idx) in enumerate(runs) for g in idx}
    segs = toolpath.segments
    jumps, viol = [], []
    for i in range(1, len(segs)):
        if run_of[i] == run_of[i - 1]:
            continue
        a, b = segs[i - 1].end_xyz, segs[i].start_xyz
        jump = math.dist(a, b)
        jumps.append(jump)
        if jump > eps:
            blk = segs[i].block
            viol.append(Violation("gap", jump, i, blk.source.line if blk else None,
                                  segs[i].role.value, None, None, None, None, EXACT,
                                  {"previous_end_xyz": list(a), "start_xyz": list(b),
                                   "plane": segs[i].plane}))
    return jumps, viol


def join_certificates(certs: list[Certificate], runs, toolpath: ToolPath, profile,
                      eps: float, limits_tol: float) -> Certificate:
    """One certificate of the runs' (module docstring)."""
    firsts, n = [], 0
    for cert in certs:
        firsts.append(n)
        n += len(cert.context.contour) if cert.context is not None else 0
    parts = [(idx, first) for (_, _, idx), first in zip(runs, firsts)]
    checks, violations = [], []
    jumps, gaps = _junctions(toolpath, runs, eps)
    for c0 in certs[0].checks:
        name = c0.name
        if name == "limits":
            check, viol = check_limits(profile, limits_tol)
            checks.append(check)
            violations += viol
            continue
        check = _join_check(name, [cert.check(name) for cert in certs], parts)
        for cert, (path, _, idx), first in zip(certs, runs, firsts):
            for v in cert.violations_of({"continuity": "gap"}.get(name, name)):
                violations.append(replace(
                    v, tool_segment=None if v.tool_segment is None else idx[v.tool_segment],
                    element=None if v.element is None else v.element + first,
                    detail={**v.detail, "plane": path.plane}))
        if name == "continuity":
            violations += gaps
            worst = max([check.figure or 0.0, *jumps])
            check = replace(check, ok=check.ok and not gaps, figure=worst,
                            count=check.count + len(jumps), violations=check.violations + len(gaps))
        checks.append(check)
    clear = [c for c in certs if c.min_clearance is not None]
    near = min(clear, key=lambda c: c.min_clearance) if clear else certs[0]
    planes = ", ".join(f"{path.plane} lines {sub.blocks[0].source.line}-"
                       f"{sub.blocks[-1].source.line}" for path, sub, _ in runs if sub.blocks)
    notes = [f"checked plane by plane, each against its own contour: {planes}"]
    notes += [note for c in certs for note in c.notes if note not in notes]
    surface = _join_detail([(c.surface, [], 0) for c in certs]) if certs[0].surface else {}
    return Certificate(all(c.ok for c in checks), near.min_clearance, near.min_clearance_basis,
                       max(c.radius for c in certs), float(eps), tuple(checks),
                       tuple(violations), toolpath.units, tuple(notes), near.context,
                       surface=surface)

"""``verify``: every check on one tool path, gathered into a Certificate."""
from __future__ import annotations

import gc
from dataclasses import dataclass
from itertools import repeat
from operator import attrgetter, itemgetter

import numpy as np

from ccopt.errors import ProgramError
from ccopt.program.model import Program
from ccopt.sides import side_sign
from ccopt.tolerances import VERIFY_EPS
from ccopt.toolpath import ROLES, Role, ToolPath, tool_centre_path
from ccopt.verify import decisions
from ccopt.verify.certificate import CERTIFIED, EXACT, Certificate, Check, Violation
from ccopt.verify.clearance import PairDistances, pair_distances
from ccopt.verify.contact import check_contact
from ccopt.verify.continuity import check_continuity
from ccopt.verify.contour import STATUS_NAMES, STATUS_STEADY, Contour, contour_of
from ccopt.verify.limits import LIMITS_TOL, check_limits
from ccopt.verify.planes import join_certificates, plane_runs
from ccopt.verify.rows import ROLE_CODES, SegmentRows
from ccopt.verify.segments import Packed, lengths
from ccopt.verify.side import check_side
from ccopt.verify.tolerance import apply_tolerance, resolve_tolerance

_LINE = attrgetter("source.line")


@dataclass(frozen=True, eq=False)
class SegmentTable:
    """Per tool segment: ``role`` (index into :class:`Role`), source ``line``
    (-1 when unknown), contour ``element`` (-1 when not a contour element's
    segment), ``steady`` (its element is steady), radius ``r`` in force, and
    ``move``: its block's index into :attr:`Contour.moves` (the program's
    in-plane moves in order; -1 for a block that is not one, e.g. a Z-only
    move, or no block); ``tool_r``: the cutter radius the segment was made
    with, its move's radius or, for a lead-out (compensation off over the
    move), the radius in force before it (``inf`` when not known)."""

    role: np.ndarray
    line: np.ndarray
    element: np.ndarray
    steady: np.ndarray
    r: np.ndarray
    move: np.ndarray
    tool_r: np.ndarray

    @classmethod
    def build(cls, rows: SegmentRows, contour: Contour) -> "SegmentTable":
        """From the tool segments' rows (their roles and blocks)."""
        n = len(rows)
        role = rows.role
        # each distinct block once (a path read from columns indexes the
        # program's blocks; one read from its segments has a block per row)
        try:
            line_of = np.fromiter(map(_LINE, rows.blocks), np.int64, len(rows.blocks))
        except AttributeError:                       # a segment without a block
            line_of = np.fromiter((-1 if b is None else b.source.line for b in rows.blocks),
                                  np.int64, len(rows.blocks))
        has = rows.block_index >= 0
        at = np.where(has, rows.block_index, 0)
        line = np.where(has, line_of[at], -1) if n else np.zeros(0, np.int64)
        q = np.where(has, contour.move_indices(rows.blocks)[at], -1) if n \
            else np.zeros(0, np.intp)
        hit = q >= 0
        qq = np.where(hit, q, 0)
        if len(contour.moves):
            elem = np.where(hit, contour.move_element[qq], -1)
            steady = hit & (contour.move_status[qq] == STATUS_NAMES.index(STATUS_STEADY))
            r = np.where(hit, contour.move_r[qq], 0.0)
            # a lead-out is made with the radius in force before compensation goes off
            before = contour.move_r[np.maximum(qq - 1, 0)]
            tool_r = np.where(hit, np.maximum(r, np.where(qq > 0, before, 0.0)), np.inf)
        else:
            elem, steady, r = np.full(n, -1, np.intp), np.zeros(n, bool), np.zeros(n)
            tool_r = np.full(n, np.inf)
        return cls(role, line, elem, steady, r, q, tool_r)

    def is_role(self, role: Role) -> np.ndarray:
        return self.role == ROLE_CODES[role]

    def infos(self, idx: np.ndarray) -> tuple[list, list]:
        """``(source lines, roles)`` of the tool segments ``idx``, as
        :meth:`~ccopt.verify.rows.SegmentRows.info` gives each (``None``: no block)."""
        line = self.line[idx]
        lines = line.tolist()
        if (line < 0).any():
            lines = [None if x < 0 else x for x in lines]
        return lines, _picked(ROLE_VALUES, self.role[idx])


@dataclass(frozen=True, eq=False)
class VerifyContext:
    """What the figures were computed from (for cross-checks and reports)."""

    toolpath: ToolPath
    program: Program
    contour: Contour
    tool: Packed
    pairs: PairDistances
    eps: float

    def nearest_pairs(self, count: int = 100) -> np.ndarray:
        """Indices into ``pairs`` of the ``count`` smallest margins among the pairs
        that count as gouges (most critical first)."""
        # distances only: a tapered margin past an open end is no distance to check
        c = np.flatnonzero(self.pairs.counted & ~self.pairs.tapered)
        m = self.pairs.margin[c]
        if m.size > count:
            part = np.argpartition(m, count)[:count]
            c, m = c[part], m[part]
        return c[np.argsort(m, kind="stable")]


#: Each role's name, by its code.
ROLE_VALUES = tuple(r.value for r in ROLES)

#: Uncompensated approaches listed in the gouge check's detail.
LISTED_APPROACHES = 20


def _gouge_detail(pairs: PairDistances, q: int, clearance: float) -> dict:
    if pairs.tapered[q]:
        # past an open end: the distance to the end point plus how far past it
        return {"past_open_end": True, "tapered_distance": float(clearance + pairs.margin[q]),
                "distance": float(np.hypot(*(pairs.wt[q] - pairs.we[q]))),
                "clearance": clearance}
    return {"distance": float(pairs.d[q]), "clearance": clearance}


def _gouge_details(pairs: PairDistances, sel: np.ndarray, required: list) -> list[dict]:
    """:func:`_gouge_detail` of each pair ``sel`` with its clearance ``required``."""
    details = [{"distance": d, "clearance": c} for d, c in zip(pairs.d[sel].tolist(), required)]
    for k in np.flatnonzero(pairs.tapered[sel]).tolist():
        details[k] = _gouge_detail(pairs, int(sel[k]), required[k])
    return details


def _points(xy: np.ndarray) -> list[tuple[float, float]]:
    """Rows ``(N, 2)`` as tuples of two Python floats."""
    return list(zip(xy[:, 0].tolist(), xy[:, 1].tolist()))


def _picked(values: list, idx: np.ndarray) -> list:
    """``[values[i] for i in idx]``."""
    if idx.size == 0:
        return []
    return [values[int(idx[0])]] if idx.size == 1 else list(itemgetter(*idx.tolist())(values))


def check_gouge(pairs: PairDistances, contour: Contour, eps: float, table: SegmentTable):
    bad = pairs.margin < -eps
    sel = np.flatnonzero(bad & pairs.counted)
    # deepest first (a stable sort of the margins: ties in pair order)
    sel = sel[np.argsort(pairs.margin[sel], kind="stable")]
    # the numbers as Python floats and ints, column by column (tolist gives the
    # values float() and int() give, element by element): a long path has
    # hundreds of thousands of gouges, and a loop of numpy scalars costs more
    # than the rest of the check
    tool, elem = pairs.tool[sel], pairs.elem[sel]
    lines, roles = table.infos(tool)
    uniq, at = np.unique(elem, return_inverse=True)
    elem_lines = _picked([contour.element_line(j) for j in uniq.tolist()], at.reshape(-1))
    required = pairs.required[sel].tolist()
    basis = _picked((CERTIFIED, EXACT), pairs.exact[sel].astype(np.intp))
    viol = Violation.many(repeat("gouge", sel.size), (-pairs.margin[sel]).tolist(),
                          tool.tolist(), lines, roles, elem.tolist(), elem_lines,
                          _points(pairs.wt[sel]), _points(pairs.we[sel]), basis,
                          _gouge_details(pairs, sel, required))
    approaches = []
    listed = np.flatnonzero(bad & ~pairs.counted)[:LISTED_APPROACHES]
    for q, (line, role) in zip(listed, zip(*table.infos(pairs.tool[listed]))):
        i, j = int(pairs.tool[q]), int(pairs.elem[q])
        approaches.append({"tool_segment": i, "tool_block": line, "tool_role": role,
                           "element": j, "element_block": contour.element_line(j),
                           "depth": float(-pairs.margin[q]),
                           "witness_tool": [float(pairs.wt[q, 0]), float(pairs.wt[q, 1])]})
    c = np.flatnonzero(pairs.counted)
    if c.size:
        k = c[int(np.argmin(pairs.margin[c]))]
        figure, basis = float(pairs.margin[k]), EXACT if pairs.exact[k] else CERTIFIED
    else:
        figure, basis = None, EXACT
    made = "made with compensation in force " if decisions.GOUGE_ONLY_WHILE_COMPENSATED else ""
    return Check("gouge", not viol, figure, eps, basis, "length",
                 f"every tool position {made}at least the element's "
                 "clearance r - eps from every contour element (figure: smallest distance - r)",
                 int(c.size), len(viol),
                 {"elements": len(contour), "certified_pairs": int((~pairs.exact).sum()),
                  "uncompensated_within_clearance": int((bad & ~pairs.counted).sum()),
                  "uncompensated_listed": approaches}), viol


def verify(toolpath: ToolPath, program: Program, profile=None, *, eps: float = VERIFY_EPS,
           radius: float | None = None, side=None,
           limits_tol: float = LIMITS_TOL, part_lines=None,
           tolerance: float | None = None) -> Certificate:
    """Certify that ``toolpath`` keeps the radius offset of ``program``'s contour.

    Parameters
    ----------
    toolpath: the tool-centre path (from :func:`ccopt.compensate` or elsewhere).
    program: the program it was made from; its fully compensated moves are the
        contour (see :func:`ccopt.verify.contour.contour_of`).
    profile: optional feed profile (:class:`ccopt.feed.FeedProfile` or samples
        shaped like it) for the limits check.
    eps: tolerance in program units (default ``VERIFY_EPS`` = 1e-6).
    radius, side: the overrides the path was compensated with, if any
        (``side``: ``"left"``/``"right"`` or +1/-1).
    limits_tol: relative tolerance of the limits check (default
        :data:`~ccopt.verify.limits.LIMITS_TOL` = 1e-3: a sample may exceed
        its limit by 0.1 %); the certificate's ``limits_ok`` and
        ``geometry_ok`` tell the two verdicts apart.
    part_lines: the program lines whose moves are part surface (``"A-B,C-D"``,
        or ``[(A, B), ...]``); the others are air. Default: the markers and the
        closed-loop rule decide (:mod:`ccopt.verify.surface`). The
        certificate's ``surface`` says what was taken as part and why.
    tolerance: program units; a gouge, contact excess or wrong-side offset
        no deeper than it is a warning (verdict "ok within tolerance"), a
        deeper one fails (:mod:`ccopt.verify.tolerance`). Default
        :data:`~ccopt.tolerances.GOUGE_TOLERANCE` by the program's units
        (1e-3 mm, 4e-5 inch); 0 makes every violation beyond ``eps`` fail.

    Returns a :class:`~ccopt.verify.certificate.Certificate`: checks ``gouge``,
    ``contact``, ``side``, ``continuity`` and ``limits``, each with its figure.
    """
    # The cyclic garbage collector is paused meanwhile: verification makes no
    # reference cycles, only arrays and short-lived objects, and on a long
    # program each automatic full collection would walk its million objects
    # (measured: a third of the time at 100,000 segments).
    paused = gc.isenabled()
    gc.disable()
    try:
        tol = resolve_tolerance(tolerance, program.units, program.file)
        cert = _verify(toolpath, program, profile, eps, radius, side, limits_tol, part_lines)
        return apply_tolerance(cert, tol, tool_centre_path(toolpath))
    finally:
        if paused:
            gc.enable()


def _verify(toolpath, program, profile, eps, radius, side, limits_tol,
            part_lines) -> Certificate:
    # a lathe path carries the imaginary tool tip; the nose centre is what cuts
    toolpath = tool_centre_path(toolpath)
    if not (eps > 0.0):
        raise ProgramError(f"eps must be > 0, got {eps!r}", program.file)
    if not (0.0 <= limits_tol < np.inf):
        raise ProgramError(f"limits_tol must be a finite number >= 0, got {limits_tol!r}",
                           program.file)
    try:
        side = side_sign(side)
    except ValueError as exc:
        raise ProgramError(str(exc), program.file) from None
    if radius is None and side is None and toolpath.compensation is not None:
        # a path ccopt made says the overrides it was made with: apply them
        # as compensation did, rather than infer them from its radius
        radius = toolpath.compensation.get("radius")
        side = toolpath.compensation.get("side")
    runs = plane_runs(toolpath, program)
    if runs is not None:
        # in several planes: each run of one plane against its own contour
        certs = [_verify(path, sub, None, eps, radius, side, limits_tol, part_lines)
                 for path, sub, _ in runs]
        return join_certificates(certs, runs, toolpath, profile, eps, limits_tol)
    contour = contour_of(program, radius=radius, side=side,
                         toolpath_radius=toolpath.radius if radius is None else None,
                         part_lines=part_lines, eps=eps)
    rows = SegmentRows.of(toolpath)
    tool = rows.tool
    seg_len = lengths(tool)
    table = SegmentTable.build(rows, contour)
    info = rows.info

    if decisions.GOUGE_ONLY_WHILE_COMPENSATED:
        # rapids and uncompensated moves run at the programmer's own points:
        # listed in the gouge check's detail, not counted
        counted = ~(table.is_role(Role.RAPID) | table.is_role(Role.UNCOMPENSATED))
    else:
        counted = np.ones(len(rows), bool)
    pairs = pair_distances(tool, contour, eps, counted, table.tool_r)
    results = [check_gouge(pairs, contour, eps, table),
               check_contact(rows, toolpath, contour, eps, seg_len, info, table),
               check_side(tool, contour, eps, seg_len, info, table),
               check_continuity(tool, rows.w0, rows.w1, eps, seg_len, info),
               check_limits(profile, limits_tol)]
    checks = tuple(c for c, _ in results)
    violations = tuple(v for _, vs in results for v in vs)
    # the headline clearance is the gouge check's own figure as a distance:
    # the pair with the smallest margin (past an open end, its tapered distance)
    c = np.flatnonzero(pairs.counted & np.isfinite(pairs.margin))
    if c.size:
        k = c[int(np.argmin(pairs.margin[c]))]
        min_clear = float(pairs.required[k] + pairs.margin[k])
        basis = EXACT if pairs.exact[k] else CERTIFIED
    else:
        min_clear, basis = None, EXACT
    rad = float(contour.radius.max()) if len(contour) else float(toolpath.radius)
    ctx = VerifyContext(toolpath, program, contour, tool, pairs, eps)
    return Certificate(all(c.ok for c in checks), min_clear, basis, rad, float(eps), checks,
                       violations, toolpath.units, contour.notes, ctx, surface=contour.surface)

"""The move written on a PMAC line, and the centre of a CIRCLE move.

The axis words of one line form one move (``docs/pmac.md``, "Moves"); a
CIRCLE move's centre comes from the ``I J K`` vector or the radius ``R``
("Circles"). Coordinates here are absolute ``(x, y, z)`` in program units;
``(u, v)`` are the in-plane axes of :data:`~ccopt.program.model.PLANE_AXES`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ccopt.errors import ProgramError
from ccopt.program.model import MAX_PROGRAM_COORDINATE, PLANE_AXES, Vec3, out_of_range
from ccopt.tolerances import POINT_EPS, R_CHORD_REL_TOL

_VECTORS = "IJK"


@dataclass(slots=True)
class PendingMove:
    """Axis words of the move being written on the current line.

    Attributes
    ----------
    line, col: where its first axis word is (1-based).
    words: ``"X"`` -> value for each of ``X Y Z I J K R`` written (each at
        most once), in the order written. An axis value is read ``ABS`` or
        ``INC`` by the mode in force when the move runs, the mode it was
        written in: ``ABS``/``INC`` runs the move written before it first.
    """

    line: int
    col: int
    words: dict = field(default_factory=dict)

    @property
    def vector(self) -> dict:
        """Centre-vector components written, ``"I"`` -> value."""
        return {k: v for k, v in self.words.items() if k in _VECTORS}

    @property
    def radius(self) -> float | None:
        """``R`` (signed), or ``None``."""
        return self.words.get("R")


def finite_point(p, file: str, line: int, col: int, what: str) -> Vec3:
    """``p`` as a tuple of three floats; ProgramError when one is not finite."""
    x, y, z = p
    bound = MAX_PROGRAM_COORDINATE
    if -bound <= x <= bound and -bound <= y <= bound and -bound <= z <= bound:
        return (float(x), float(y), float(z))      # the common case, in one test
    if not all(math.isfinite(v) for v in p):
        raise ProgramError(f"{what} is not a finite number (values too large)", file, line, col)
    if any(out_of_range(v) for v in p):
        # incremental moves add up and an R arc's centre is computed: bound what they make
        raise ProgramError(f"{what} is beyond +-{MAX_PROGRAM_COORDINATE:g} program units: "
                           "check the values on this line", file, line, col)
    return (float(p[0]), float(p[1]), float(p[2]))


@dataclass(frozen=True)
class CircleMode:
    """Modal state a CIRCLE move's centre depends on.

    Attributes
    ----------
    mode: ``"CIRCLE1"`` (clockwise) or ``"CIRCLE2"`` (counter-clockwise).
    plane: ``"XY" | "ZX" | "YZ"``.
    vector_absolute: ``ABS(R)``: the vector is the centre itself, not the
        offset from the start (``INC(R)``, the power-on default).
    file: for error messages.
    """

    mode: str
    plane: str
    vector_absolute: bool
    file: str


def circle_centre(pend: PendingMove, start: Vec3, end: Vec3,
                  cm: CircleMode) -> tuple[Vec3, Vec3]:
    """Absolute centre of a CIRCLE move, and its end (snapped onto the start
    for a full circle). The centre lies in the plane through the start."""
    iu, iv, iw = PLANE_AXES[cm.plane]
    if pend.vector and pend.radius is not None:
        raise ProgramError("give either the centre vector I/J/K or the radius R, not both",
                           cm.file, pend.line, pend.col)
    if not pend.vector and pend.radius is None:
        raise ProgramError(f"{cm.mode} move without a centre: give the vector I/J/K or "
                           "the radius R", cm.file, pend.line, pend.col)
    su, sv = start[iu], start[iv]
    eu, ev = end[iu], end[iv]
    if pend.radius is not None:
        cu, cv = _centre_from_radius(pend, (su, sv), (eu, ev), cm)
    else:
        end, (cu, cv) = _centre_from_vector(pend, start, end, cm)
    centre = [0.0, 0.0, 0.0]
    centre[iu], centre[iv], centre[iw] = cu, cv, start[iw]
    return end, finite_point(centre, cm.file, pend.line, pend.col, "arc centre")


def _same_point_tol(s: tuple[float, float], e: tuple[float, float]) -> float:
    """In-plane distance under which start and end are the same point."""
    return POINT_EPS * max(1.0, abs(s[0]), abs(s[1]), abs(e[0]), abs(e[1]))


def _centre_from_radius(pend: PendingMove, s: tuple[float, float], e: tuple[float, float],
                        cm: CircleMode) -> tuple[float, float]:
    """Centre ``(u, v)`` of an ``R`` arc: ``R > 0`` the short arc, ``R < 0`` the long one."""
    (su, sv), (eu, ev) = s, e
    r = pend.radius
    if r == 0:
        raise ProgramError("R0: the arc radius must not be zero", cm.file, pend.line, pend.col)
    chord = math.hypot(eu - su, ev - sv)
    if chord <= _same_point_tol(s, e):
        raise ProgramError("R cannot make a full circle (PMAC: the end must differ from "
                           "the start); use the centre vector I/J/K", cm.file, pend.line,
                           pend.col)
    half = chord / 2.0
    if abs(r) < half * (1.0 - R_CHORD_REL_TOL):
        raise ProgramError(f"R{r:g} is too small for the chord {chord:g} from the start "
                           f"to the end point (|R| must be at least {half:g})",
                           cm.file, pend.line, pend.col)
    h = math.sqrt(max(0.0, (abs(r) - half) * (abs(r) + half)))
    # Unit normal to the left of the chord start -> end.
    nu, nv = -(ev - sv) / chord, (eu - su) / chord
    ccw = cm.mode == "CIRCLE2"
    side = (1.0 if ccw else -1.0) * (1.0 if r > 0 else -1.0)
    return (su + eu) / 2.0 + side * h * nu, (sv + ev) / 2.0 + side * h * nv


def _centre_from_vector(pend: PendingMove, start: Vec3, end: Vec3,
                        cm: CircleMode) -> tuple[Vec3, tuple[float, float]]:
    """Centre ``(u, v)`` of an ``I J K`` arc, and the end (snapped onto the
    start when the arc is a full circle)."""
    iu, iv, _ = PLANE_AXES[cm.plane]
    su, sv = start[iu], start[iv]
    eu, ev = end[iu], end[iv]
    tol = _same_point_tol((su, sv), (eu, ev))
    vec = [pend.vector.get(k, 0.0) for k in _VECTORS]
    if cm.vector_absolute:
        cu, cv = vec[iu], vec[iv]
    else:
        cu, cv = su + vec[iu], sv + vec[iv]
    if math.hypot(su - cu, sv - cv) <= tol:
        raise ProgramError("the arc centre is on the start point: the centre vector "
                           "I/J/K must not be zero (INC(R)) or the start (ABS(R))",
                           cm.file, pend.line, pend.col)
    if math.hypot(eu - su, ev - sv) <= tol:
        end_l = list(end)
        end_l[iu], end_l[iv] = su, sv
        end = (end_l[0], end_l[1], end_l[2])
    elif math.hypot(eu - cu, ev - cv) <= tol:
        raise ProgramError("the arc centre is on the end point", cm.file, pend.line, pend.col)
    return end, (cu, cv)

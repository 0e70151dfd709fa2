"""The contour segments of the lathe cycles G70-G72 (LinuxCNC ``interp_g7x.cc``:
``segment``, ``straight_segment``, ``round_segment``, ``fillet_segment``,
``chamfer_segment``), ported move for move.

A point is a complex number ``z + x*1j`` in program units, work coordinates
of the ZX plane: the real part is Z, the imaginary part X (a radius, also in
``G7`` diameter mode). ``ccw`` is True for a ``G3`` arc, False for ``G2``, in
that (Z, X) plane as LinuxCNC reads them. The roughing code
(:mod:`.g7x_path`) first turns and mirrors the contour so that it runs
towards decreasing Z and X; the methods below assume that orientation.

``dive``/``climb``/``climb_only`` take the tool's location and return the new
one (LinuxCNC passes it by reference); ``dive`` and ``climb`` also return
LinuxCNC's flag (True: "not this segment's business", the caller moves on).
Moves go to ``out``, an object with ``straight_move(end)``,
``straight_rapid(end)`` and ``circular_move(ccw, center, end)``.

Where LinuxCNC's arithmetic divides by zero (a zero-length segment), the C++
gives NaN and carries on; :func:`div` does the same here so the port behaves
alike (Python would raise).
"""
from __future__ import annotations

import copy
import math

#: LinuxCNC's ``tolerance`` in ``interp_g7x.cc``, program units.
TOLERANCE = 1e-6
#: A segment shorter than this (program units) is dropped (LinuxCNC ``1e-3``).
MIN_RADIUS = 1e-3
_NAN = complex(math.nan, math.nan)


class G7xError(Exception):
    """A contour LinuxCNC refuses; its message follows ``G7X error:``."""


def div(a: complex, b) -> complex:
    """``a / b`` as C++ ``std::complex`` gives it: NaN for a zero ``b``."""
    if b == 0:
        return _NAN
    if isinstance(b, complex):
        return a / b
    return complex(a.real / b, a.imag / b)


def norm(v: complex) -> float:
    """``std::norm``: the squared magnitude."""
    return v.real * v.real + v.imag * v.imag


def cpp_str(p: complex) -> str:
    """A point as C++ ``ostream << std::complex`` prints it: ``(z,x)``."""
    return f"({p.real:g},{p.imag:g})"


class Segment:
    """A contour element from ``start`` to ``end``; ``finish`` is the size of a
    corner fillet or chamfer still to be cut into the corner (0 otherwise)."""

    __slots__ = ("start", "end", "finish")

    def __init__(self, start: complex, end: complex):
        self.start = start
        self.end = end
        self.finish = 0.0

    def dup(self) -> "Segment":
        return copy.copy(self)

    def monotonic(self) -> bool:
        """Not running towards +Z (beyond 1e-3)."""
        return (self.end - self.start).real <= 1e-3

    def do_finish(self, prev: "Segment", nxt: "Segment") -> None:
        """Cut a fillet or chamfer into the corner (only those segments do)."""

    def flip_imag(self) -> None:
        self.start = self.start.conjugate()
        self.end = self.end.conjugate()

    def flip_real(self) -> None:
        self.start = -self.start.conjugate()
        self.end = -self.end.conjugate()

    def rotate(self) -> None:
        self.start = -self.start * 1j
        self.end = -self.end * 1j

    def move(self, d: complex) -> None:
        self.start += d
        self.end += d

    def intersect(self, nxt: "Segment") -> None:
        """Move this segment's end and ``nxt``'s start to where they cross."""
        nxt.intersect_end(self)

    def corner_finish(self, prev: "Segment", nxt: "Segment") -> complex:
        """Fit this corner segment between ``prev`` and ``nxt`` at ``finish``
        from both (trying the other side when the offsets do not meet); the
        centre of a fillet."""
        p, n = prev.dup(), nxt.dup()
        p.offset(self.finish)
        n.offset(self.finish)
        if (p.end - n.start).real > 1e-2:
            self.finish = -self.finish
            p, n = prev.dup(), nxt.dup()
            p.offset(self.finish)
            n.offset(self.finish)
        if (p.end - n.start).real > 1e-2:
            raise G7xError(f"Corner finish failed at {cpp_str(prev.end)}")
        p.intersect(n)
        center = (p.end + n.start) / 2.0
        p.offset(-self.finish)
        n.offset(-self.finish)
        self.start = prev.end = p.end
        self.end = nxt.start = n.start
        return center


class Straight(Segment):
    """A line of the contour (``G0``/``G1``)."""

    __slots__ = ()

    def radius(self) -> float:
        return abs(self.start - self.end)

    def draw(self, out) -> None:
        out.straight_move(self.end)

    def offset(self, distance: float) -> None:
        """Shift sideways by ``distance`` (positive: to the left of the direction of travel)."""
        d = div(1j * distance * (self.start - self.end), abs(self.start - self.end))
        self.start += d
        self.end += d

    def intersection_z(self, x: float) -> list[float]:
        """Z of the points at X = ``x`` (both ends of a line along Z there)."""
        s, e = self.start, self.end
        if min(s.imag, e.imag) > x + TOLERANCE or max(s.imag, e.imag) < x - TOLERANCE:
            return []
        if abs((s - e).imag) < TOLERANCE:
            return [s.real, e.real]
        return [(x - s.imag) / (e.imag - s.imag) * (e.real - s.real) + s.real]

    def climb(self, location: complex, out) -> tuple[bool, complex]:
        if self.end.imag + TOLERANCE < self.start.imag:
            return True, location          # not climbing
        if abs(location - self.start) > TOLERANCE:
            raise G7xError("How did we get here?")
        out.straight_move(self.end)
        return False, self.end

    def climb_only(self, location: complex, out) -> complex:
        if self.end.imag < self.start.imag:
            return location                # not climbing
        found = self.intersection_z(location.imag)
        if not found:
            return location
        location = complex(found[0], location.imag)
        out.straight_move(location)
        out.straight_move(self.end)
        return self.end

    def dive(self, location: complex, x: float, out, fast: bool) -> tuple[bool, complex]:
        if self.start.imag <= self.end.imag + TOLERANCE:
            return True, location          # not a diving segment
        move = out.straight_rapid if fast else out.straight_move
        if x < self.end.imag:
            move(self.end)
            return False, self.end
        found = self.intersection_z(x)
        if not found:
            raise G7xError("x too large in straight dive")
        ep = complex(found[0], x)
        move(ep)
        return False, ep

    def intersect_end(self, p: Segment) -> None:
        """Correct ``p``'s end and this line's start to where they meet."""
        if isinstance(p, Round):
            self._after_arc(p)
            return
        rot = div(self.start.conjugate() - self.end.conjugate(), abs(self.start - self.end))
        ps = (p.start - self.end) * rot
        pe = (p.end - self.end) * rot
        if (ps - pe).imag == 0:
            raise G7xError("Cannot intersect parallel lines")
        f = ps.imag / (ps - pe).imag
        point = div(ps + f * (pe - ps), rot) + self.end
        self.start = p.end = point

    def _after_arc(self, p: "Round") -> None:
        """An arc ``p`` followed by this line."""
        if abs(self.start - p.end) < TOLERANCE:
            return
        self.start = p.end = _line_meets_circle(self.start, self.end, p.end, p.center,
                                                self.start)


def _line_meets_circle(a: complex, b: complex, on_circle: complex, center: complex,
                       near: complex) -> complex:
    """Where the line through ``a`` and ``b`` meets the circle about ``center``
    through ``on_circle``, the crossing nearer ``near`` (LinuxCNC's
    ``intersect_end`` of a line and an arc, in the frame of the line at ``b``;
    a line that misses the circle gives its closest point)."""
    rot = div(a.conjugate() - b.conjugate(), abs(a - b))
    pe = (on_circle - b) * rot
    pc = (center - b) * rot
    disc = norm(pc - pe) - pc.imag * pc.imag
    root = 0.0 if disc < 0 else math.sqrt(disc)
    s1 = div(complex(pc.real + root), rot) + b
    s2 = div(complex(pc.real - root), rot) + b
    return s1 if abs(near - s1) < abs(near - s2) else s2


class Round(Segment):
    """An arc of the contour (``G2``/``G3``) about ``center``."""

    __slots__ = ("ccw", "center")

    def __init__(self, ccw: bool, start: complex, center: complex, end: complex):
        super().__init__(start, end)
        self.ccw = ccw
        self.center = center

    def radius(self) -> float:
        return min(abs(self.start - self.end), abs(self.start - self.center))

    def draw(self, out) -> None:
        out.circular_move(self.ccw, self.center, self.end)

    def offset(self, distance: float) -> None:
        """Grow (``G3``) or shrink (``G2``) the radius by ``distance``."""
        r = abs(self.start - self.center)
        factor = (r + (1 if self.ccw else -1) * distance) / r if r else math.nan
        self.start = factor * (self.start - self.center) + self.center
        self.end = factor * (self.end - self.center) + self.center

    def flip_imag(self) -> None:
        self.ccw = not self.ccw
        super().flip_imag()
        self.center = self.center.conjugate()

    def flip_real(self) -> None:
        self.ccw = not self.ccw
        super().flip_real()
        self.center = -self.center.conjugate()

    def rotate(self) -> None:
        super().rotate()
        self.center = -self.center * 1j

    def move(self, d: complex) -> None:
        super().move(d)
        self.center += d

    def monotonic(self) -> bool:
        """Running towards -Z on the side of the centre the tool cuts from."""
        if self.finish != 0:
            return True
        entry = (self.start - self.center).imag
        leave = (self.end - self.center).imag
        dz = (self.end - self.start).real
        if self.ccw:
            return entry >= -1e-3 and leave >= -1e-3 and dz <= -1e-3
        return entry <= 1e-3 and leave <= 1e-3 and dz <= -1e-3

    def _on_segment(self, p: complex) -> bool:
        a = ((self.start - self.center).conjugate() * (p - self.center)).imag
        b = ((self.end - self.center).conjugate() * (p - self.center)).imag
        if self.ccw:
            return a >= -TOLERANCE and b <= TOLERANCE
        return a <= TOLERANCE and b >= -TOLERANCE

    def intersection_z(self, x: float) -> list[float]:
        c = self.center
        r = abs(self.start - c)
        s = -(x - r - c.imag) * (x + r - c.imag)
        if s < -TOLERANCE:
            return []
        s = math.sqrt(max(s, 0.0))
        found = []
        for z in (c.real + s, c.real - s):
            if self._on_segment(complex(z, x)):
                found.append(z)
        return found

    def _top(self) -> complex:
        """The end, or the arc's highest point when a ``G3`` passes it."""
        if self.end.real < self.center.real:
            return complex(self.center.real, self.center.imag + abs(self.start - self.center))
        return self.end

    def climb(self, location: complex, out) -> tuple[bool, complex]:
        if not self.ccw:
            if location.real > self.center.real:
                return True, location
            if abs(location - self.end) > 1e-3:
                out.circular_move(self.ccw, self.center, self.end)
            return False, self.end
        if location.real < self.center.real:
            return True, location
        ep = self._top()
        if abs(location - ep) > 1e-3:
            out.circular_move(self.ccw, self.center, ep)
        return True, ep

    def dive(self, location: complex, x: float, out, fast: bool) -> tuple[bool, complex]:
        c, e = self.center, self.end
        if abs(location - e) < TOLERANCE or (location - e).real <= TOLERANCE:
            return False, e
        found = self.intersection_z(x) or self.intersection_z(x - TOLERANCE)
        if self.ccw:
            if location.real - TOLERANCE > c.real:
                return True, location
            if not found or found[-1] > c.real:
                out.circular_move(self.ccw, c, e)
                return False, e
            ep = complex(found[-1], x)
            out.circular_move(self.ccw, c, ep)
            return False, ep
        if location.real <= c.real:
            return True, location      # already climbing
        if not found:
            out.circular_move(self.ccw, c, e)   # curve not hit: to the end
            return False, e
        if found[0] < c.real:
            return False, location     # hit at the back side only: the pocket lowers x
        ep = complex(found[0], x)      # cut twice: to the front intersection
        out.circular_move(self.ccw, c, ep)
        return False, ep

    def climb_only(self, location: complex, out) -> complex:
        found = self.intersection_z(location.imag)
        if not found:
            return location
        if not self.ccw:
            if found[-1] > self.center.real:
                return location
            location = complex(found[-1], location.imag)
            out.straight_move(location)
            if abs(location - self.end) > 1e-3:
                out.circular_move(self.ccw, self.center, self.end)
            return self.end
        if found[0] < self.center.real:
            return location
        location = complex(found[0], location.imag)
        out.straight_move(location)
        ep = self._top()
        if abs(location - ep) > 1e-3:
            out.circular_move(self.ccw, self.center, ep)
        return ep

    def intersect_end(self, p: Segment) -> None:
        """Correct ``p``'s end and this arc's start to where they meet."""
        if isinstance(p, Round):
            self._after_arc(p)
            return
        if abs(self.start - p.end) < TOLERANCE:
            return
        self.start = p.end = _line_meets_circle(p.start, p.end, self.end, self.center,
                                                self.start)

    def _after_arc(self, p: "Round") -> None:
        """Two arcs: the crossing of their circles by the law of cosines."""
        a = abs(self.start - self.center)
        b = abs(p.start - p.center)
        c = abs(self.center - p.center)
        cos_b = (c * c + a * a - b * b) / 2.0 / a / c if a and c else math.nan
        cos_b2 = min(cos_b * cos_b, 1.0) if not math.isnan(cos_b) else math.nan
        rot = complex(cos_b, math.sqrt(1 - cos_b2) if not math.isnan(cos_b2) else math.nan)
        point = div(rot * (p.center - self.center), c) * a + self.center
        p.end = self.start = point


class Fillet(Round):
    """A corner rounded with radius ``finish`` (the ``A`` word of a contour move)."""

    __slots__ = ()

    def __init__(self, size: float, corner: complex):
        super().__init__(False, corner, corner, corner)
        self.finish = size

    def do_finish(self, prev: Segment, nxt: Segment) -> None:
        self.center = self.corner_finish(prev, nxt)
        self.ccw = (self.start - self.center).imag > 0 or (self.end - self.center).imag > 0
        self.finish = 0.0


class Chamfer(Straight):
    """A corner cut off at ``finish`` from it (the ``C`` word of a contour move)."""

    __slots__ = ()

    def __init__(self, size: float, corner: complex):
        super().__init__(corner, corner)
        self.finish = size

    def do_finish(self, prev: Segment, nxt: Segment) -> None:
        self.corner_finish(prev, nxt)

"""The passes of the lathe cycles G70-G72 (LinuxCNC ``interp_g7x.cc``: class
``g7x`` with ``pocket``, ``add_distance``, ``do_g70``, ``do_g71``, and
``swapped_motion``), ported move for move.

Points are complex ``z + x*1j`` in program units (work coordinates, X a
radius), segments those of :mod:`.g7x_contour`. The profile is first turned
(``G72``: by -90 degrees, so facing becomes turning) and mirrored so that it
runs towards decreasing Z and X; the moves are mapped back by
:class:`Swapped` on their way out.

LinuxCNC's loops have no bound; a few can run for ever on some contours
(its ``g71-endless-loop`` tests record fixed ones). Every loop here is
bounded by :class:`Budget` and by a no-progress check; both raise
:class:`~.g7x_contour.G7xError`, never loop.
"""
from __future__ import annotations

import math

from ccopt.program.gcode.g7x_contour import (MIN_RADIUS, TOLERANCE, G7xError, Round,
                                             Segment, Straight, div)

#: Steps the passes of one cycle may take (loop iterations of ``pocket`` and
#: ``add_distance`` together; the moves are bounded apart, by
#: ``lathe_cycles.MAX_CYCLE_MOVES``). A pass costs a step per segment it
#: looks at, an offset step one per segment; 300,000 steps take the reader
#: about a second and allow, e.g., 6,000 passes over a contour of 50 segments.
#: LinuxCNC has no bound.
MAX_STEPS = 300_000
#: A drop of more than this many depths of cut in one go is computed in one
#: subtraction, not one by one (LinuxCNC subtracts one at a time: with
#: ``I`` near its floor of 2e-6 that is millions of steps; the rounding of
#: the two ways differs by far less than a printed digit).
_FAST_DROP = 1000


class Budget:
    """Counts the steps of one cycle against :data:`MAX_STEPS`."""

    def __init__(self):
        self.limit = self.left = MAX_STEPS

    def step(self, n: int = 1) -> None:
        self.left -= n
        if self.left < 0:
            raise G7xError(f"the cycle needs more than {self.limit} steps (depth of cut I "
                           "too small for the contour?); ccopt stops it here")


class Swapped:
    """``swapped_motion``: maps the moves of the turned and mirrored profile
    (``flip_state`` bit 1: Z mirrored, 2: X mirrored, 4: turned) back to the
    program's (Z, X) plane; mirroring once reverses an arc's direction."""

    _MAPS = {
        0: (lambda p: p, False),
        1: (lambda p: -p.conjugate(), True),
        2: (lambda p: p.conjugate(), True),
        3: (lambda p: -p, False),
        4: (lambda p: 1j * p, False),
        5: (lambda p: (1j * p).conjugate(), True),
        6: (lambda p: -(1j * p).conjugate(), True),
        7: (lambda p: -1j * p, False),
    }

    def __init__(self, out, flip_state: int):
        self.out = out
        self.map, self.reverse = self._MAPS[flip_state]

    def straight_move(self, end: complex) -> None:
        self.out.straight_move(self.map(end))

    def straight_rapid(self, end: complex, comp_off: bool = False) -> None:
        self.out.straight_rapid(self.map(end), comp_off)

    def circular_move(self, ccw: bool, center: complex, end: complex) -> None:
        self.out.circular_move(ccw != self.reverse, self.map(center), self.map(end))


class Profile:
    """The contour as LinuxCNC's ``g7x`` list: ``segs[0]`` runs from the
    cycle's start point to the contour's first point."""

    def __init__(self, segs: list[Segment], budget: Budget):
        self.segs = segs
        self.budget = budget
        self.delta = 0.5                    # depth of cut (I)
        self.escape = complex(0.3, 0.3)     # retract (R) along Z and X
        self.flip_state = 0
        self.pocket_starts: list[complex] = []

    def copy(self) -> "Profile":
        """The copy constructor: segments, delta, escape and flip state."""
        other = Profile([s.dup() for s in self.segs], self.budget)
        other.delta, other.escape, other.flip_state = self.delta, self.escape, self.flip_state
        return other

    # -- orientation --------------------------------------------------
    def rotate(self) -> None:
        """Turn the profile by -90 degrees (``G72``: facing as turning)."""
        for s in self.segs:
            s.rotate()
        self.flip_state ^= 4

    def swap(self) -> None:
        """Mirror the profile so that Z and X decrease from its start to its end."""
        d = self.segs[0].end - self.segs[-1].end
        if d.imag > 0:
            for s in self.segs:
                s.flip_imag()
            self.flip_state ^= 2
        if d.real < 0:
            for s in self.segs:
                s.flip_real()
            self.flip_state ^= 1

    def motion(self, out) -> Swapped:
        return Swapped(out, self.flip_state)

    def monotonic(self) -> None:
        """Refuse a contour that turns back along Z (LinuxCNC cannot rough it)."""
        first = self.segs[0]
        if (first.end - first.start).real > 0:
            first.start = complex(first.end.real, first.start.imag)
        for s in self.segs:
            if not s.monotonic():
                raise G7xError("Not monotonic")

    def do_finish(self) -> None:
        """Cut the fillets and chamfers into their corners; drop what is left
        shorter than 1e-3."""
        segs = self.segs
        h = 1
        while h < len(segs) - 1:
            segs[h].do_finish(segs[h - 1], segs[h + 1])
            h += 1
        _drop_short(segs)

    def should_rotate_paths(self) -> bool:
        """G70: whether the contour only runs monotonically when turned."""
        paths = self.copy()
        paths.segs.pop(0)
        paths.swap()
        return any(not s.monotonic() for s in paths.segs)

    # -- cycles ---------------------------------------------------------
    def do_g70(self, out, x: float, z: float, d: float, e: float, passes: int) -> None:
        """Finishing passes from distance ``d`` down to ``e`` off the contour
        (``passes`` of them, the last at ``e``), each from a rapid to
        (``x``, ``z``) made with compensation off."""
        self.segs[0].start = complex(z, x)
        if self.should_rotate_paths():
            self.rotate()
        self.swap()
        self.do_finish()
        self.monotonic()
        swapped = self.motion(out)
        for n in range(passes, 0, -1):
            distance = (n - 1) * (d - e) / passes + e
            # only the last pass cuts the part's surface; the ones before are
            # off it by what the next passes remove (the verifier's air)
            out.surface = "air" if n > 1 else None
            paths = self.copy()
            paths.add_distance(distance)
            swapped.straight_rapid(paths.segs[0].start, comp_off=True)
            swapped.straight_rapid(paths.segs[0].end)
            for s in paths.segs[1:]:
                self.budget.step()
                s.draw(swapped)

    def do_g71(self, out, cycle: int, x: float, z: float, u: float, w: float, d: float,
               i: float, r: float, do_rotate: bool = False) -> None:
        """Roughing from (``x``, ``z``): ``cycle`` 0 cuts everything, 1 no
        pocket, 2 only what 1 left; ``d`` is left on the contour, shifted by
        (``w``, ``u``); ``i`` is the depth of cut, ``r`` the retract."""
        self.segs[0].start = complex(z, x)
        if do_rotate:
            self.rotate()
        self.swap()
        self.do_finish()
        self.monotonic()
        self.add_distance(d)
        for s in self.segs:
            s.move(complex(w, u))
        swapped = self.motion(out)
        self.delta = max(i, 2 * TOLERANCE)
        self.escape = r * complex(1, 1)
        first, last = self.segs[0], self.segs[-1]
        swapped.straight_rapid(first.start)
        if last.end.imag < first.start.imag:
            self.segs.append(Straight(last.end, complex(last.end.real, first.start.imag)))
        self.pocket_starts.append(first.start)
        self.pocket(cycle, first.start, 0, swapped)

    # -- roughing -----------------------------------------------------
    def pocket(self, cycle: int, location: complex, p: int, out) -> None:
        """LinuxCNC's ``pocket``: cut passes down the profile; its tail
        recursion (a new pocket found while climbing) is the outer loop."""
        segs = self.segs
        while True:
            x = self.pocket_starts[-1].imag
            if cycle == 2:
                # skips the initial roughing pass
                while p < len(segs):
                    self.budget.step()
                    done, location = segs[p].dive(location, -1e9, out, p == 0)
                    if done:
                        break
                    p += 1
                cycle = 3
            found = self._passes(cycle, location, p, x, out)
            if found is None:
                return
            location, p = found

    def _passes(self, cycle: int, location: complex, p: int, x: float, out):
        """The body of ``pocket``'s loop; ``(location, p)`` of a new pocket to
        cut, or None when the profile is done."""
        segs = self.segs
        while p < len(segs):
            self.budget.step()
            before = (p, x, location)
            x = self._drop_to(x, location)
            done, location = segs[p].dive(location, x, out, p == 0)
            if done:
                return self._climb(cycle, location, p, out)
            if p == len(segs) - 1:
                return None      # the moves of the last path are made
            if abs(location.imag - x) > TOLERANCE or segs[p].end == location:
                p += 1           # x is beyond this segment: on to the next
                continue
            p, x, location = self._cut(p, x, location, out)
            if (p, x, location) == before:
                raise G7xError(f"no progress at {location.real:g}, {location.imag:g} "
                               "(LinuxCNC's interpreter loops for ever here)")
        return None

    def _drop_to(self, x: float, location: complex) -> float:
        """``x`` lowered by whole depths of cut to the location's X (one at a
        time as LinuxCNC, a long drop in one subtraction)."""
        if x - TOLERANCE > location.imag:
            n = math.floor((x - TOLERANCE - location.imag) / self.delta)
            if n > _FAST_DROP:
                x -= (n - 1) * self.delta
        while x - TOLERANCE > location.imag:
            self.budget.step()
            x -= self.delta
        return x

    def _climb(self, cycle: int, location: complex, p: int, out):
        """After the last dive: along the contour (``cycle`` 1: to its end;
        else until a pocket starts, returned as ``(location, p)``)."""
        segs = self.segs
        if cycle == 1:
            while p < len(segs):
                self.budget.step()
                location = segs[p].climb_only(location, out)
                p += 1
            return None
        while p < len(segs):
            self.budget.step()
            pocket, location = segs[p].climb(location, out)
            if pocket:
                if cycle == 3:
                    starts = self.pocket_starts
                    if location.imag > starts[-1].imag and len(starts) > 1:
                        starts.pop()
                    if len(starts) == 1:
                        starts.append(location)
                return location, p
            p += 1
        return None

    def _cut(self, p: int, x: float, location: complex, out) -> tuple[int, float, complex]:
        """One pass at X = ``location.imag``: feed along Z to the profile,
        retract by the escape and come back; ``(p, x, location)`` after it."""
        segs = self.segs
        for ip in range(p, len(segs)):
            self.budget.step()
            found = segs[ip].intersection_z(location.imag)
            if not found:
                continue
            # the diving curve can be hit, if it is a circle
            dest_z = found[0] if ip != p else found[-1]
            distance = abs(dest_z - location.real)
            if dest_z - TOLERANCE > location.real:
                continue         # hitting the diving curve at the starting point only
            if distance < TOLERANCE:
                if p == ip:
                    continue     # the diving curve, at the starting point
                if abs(location - segs[ip].start) < TOLERANCE:
                    return ip, x, location   # another curve at its entry: move onto it
                return p, x - self.delta, location   # a zero-length segment: done
            dest = complex(dest_z, location.imag)
            out.straight_move(dest)
            # a short pass retracts less than the whole escape
            scale = min(1.0, distance / 2 / self.escape.real) if self.escape.real else 1.0
            dest += scale * self.escape
            out.straight_rapid(dest)
            out.straight_rapid(location - (scale * self.escape).conjugate())
            if p == 0:
                out.straight_rapid(location)
            else:
                out.straight_move(location)
            return p, x - self.delta, location
        return p, x, location

    # -- offset -------------------------------------------------------
    def add_distance(self, distance: float) -> None:
        """Offset the contour (not ``segs[0]``) by ``distance`` away from the
        stock side, in steps of at most half the shortest segment, joining
        the pieces with arcs and intersections as LinuxCNC does."""
        segs = self.segs
        angle = div(segs[0].end - segs[0].start, segs[-1].start - segs[0].start)
        if angle.imag < 0:
            distance = -distance
        first = segs.pop(0)
        current = 0.0
        while current != distance:
            self.budget.step(len(segs) + 1)
            step = 1e9
            for s in segs:
                step = min(step, s.radius() / 2)
            step = min(step, abs(distance - current))
            if distance < 0:
                step = -step
            if step == 0 or math.isnan(step):
                raise G7xError("the contour's offset does not advance (a segment of zero "
                               "length?); LinuxCNC's interpreter loops for ever here")
            self._offset_step(step, distance)
            current += step
        for k in range(len(segs) - 1):
            mid = (segs[k].end + segs[k + 1].start) / 2.0
            segs[k].end = segs[k + 1].start = mid
        if not segs:
            raise G7xError("the offset contour vanished")
        first.end = segs[0].start
        segs.insert(0, first)

    def _offset_step(self, step: float, distance: float) -> None:
        """One step of :meth:`add_distance`: offset, join, intersect."""
        segs = self.segs
        k = 0
        while k < len(segs):
            segs[k].offset(step)
            if segs[k].radius() < MIN_RADIUS:
                del segs[k]
                k -= 1
            k += 1
        k = 0
        while k < len(segs) - 1:
            a, b = segs[k], segs[k + 1]
            if (a.end - b.start).real > 1e-2:
                # the offsets parted: a connecting arc about the old corner
                s, e = a.dup(), b.dup()
                s.offset(-step)
                e.offset(-step)
                center = (s.end + e.start) / 2.0
                segs.insert(k + 1, Round(distance > 0, a.end, center, b.start))
                k += 1
            k += 1
        k = 0
        while k < len(segs) - 1:
            if not segs[k].monotonic():
                if k == 0:
                    raise G7xError("Not monotonic")  # LinuxCNC reads before its list here
                del segs[k if segs[k].radius() < segs[k - 1].radius() else k - 1]
                k = 0
                if len(segs) < 2:
                    break
            if segs[k].radius() < MIN_RADIUS:
                del segs[k]
                k = 0
            else:
                segs[k].intersect(segs[k + 1])
            k += 1


def _drop_short(segs: list[Segment]) -> None:
    """Remove the segments shorter than :data:`MIN_RADIUS`, in place."""
    segs[:] = [s for s in segs if not s.radius() < MIN_RADIUS]

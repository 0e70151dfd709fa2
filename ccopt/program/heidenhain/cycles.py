"""``CYCL DEF``: tolerance (32), datum shift (7), rotation (10), dwell (9), datum setting
(247: one preset per program) and the drilling
cycles of the 200 series, run as moves at ``CYCL CALL`` / ``M99`` / ``M89``.

Every other cycle is refused where it is defined, as a located
:class:`~ccopt.errors.ProgramError`: contour (SL: 14, 20-25, 27-29, 270-276)
and pocket cycles (4, 5, 251-258) would need the TNC's own machining
strategy, the coordinate transformations (8, 11, 19, 26) a frame ccopt
does not model. The rotation (10) turns the working plane about the tool
axis, after the datum shift (:meth:`Machine.to_machine`).

The drilling moves (TNC 640 User's Manual, Cycles Programming, "Fixed
cycles: drilling"): rapid along the tool axis to the set-up clearance
``Q200`` above the surface ``Q203``; feed ``Q206`` to the depth ``Q201``
(below the surface, so negative; rigid tapping 207: the pitch ``Q239`` times
the spindle speed), in infeeds of ``Q202`` (200, 203, 205)
each followed by a rapid retract to the set-up clearance and a rapid return
to the set-up clearance above the depth reached; dwell ``Q211`` seconds at
the depth; retract (at rapid, or at the feed ``Q208`` for reaming and
boring, ``Q206`` for tapping, the pitch feed for 207) to the set-up clearance, then to the second
set-up clearance ``Q204`` when it is higher. Tapping with chip breaking
(209) taps in infeeds of ``Q257`` with a retract of ``Q256`` pitches after
each (:meth:`Cycles._chip_breaking_tap`).
"""
from __future__ import annotations

from ccopt.errors import ProgramError
from ccopt.program.heidenhain.lexer import Statement
from ccopt.program.heidenhain.machine import Machine
from ccopt.program.model import PLANE_AXES, Motion, Source

#: ``Program.meta`` key: each ``CYCL DEF 32`` as ``{"line", "tolerance"}``
#: (``None``: the machine's default tolerance restored).
TOLERANCES = "cycle32_tolerance"
#: ``Program.meta`` key: each ``CYCL DEF 247`` as ``{"line", "preset"}``.
PRESETS = "cycle247_preset"
DRILLING = {200: "DRILLING", 201: "REAMING", 202: "BORING", 203: "UNIVERSAL DRILLING",
            205: "UNIVERSAL PECKING", 206: "TAPPING", 207: "RIGID TAPPING",
            209: "TAPPING W/ CHIP BRKG", 240: "CENTERING"}
_PITCH_FEED = {207, 209}
_PECKING = {200, 203, 205}
#: ``Q208= MAX``: the retraction at rapid traverse.
RAPID = float("inf")
_FEED_RETRACT = {201: "Q208", 202: "Q208", 206: "Q206", 207: "Q206"}
_SL = {14, 20, 21, 22, 23, 24, 25, 27, 28, 29, 39, 270, 271, 272, 273, 274, 275, 276}
_POCKETS = {4, 5, 251, 252, 253, 254, 256, 257, 258}


class Cycles:
    """The defined cycle and the modal cycle call of one run."""

    def __init__(self, m: Machine):
        self.m = m
        self.defined: tuple[int, dict, Source] | None = None
        self.modal_call = False
        m.meta[TOLERANCES] = []

    def err(self, msg: str, st: Statement, col: int | None = None) -> ProgramError:
        return ProgramError(msg, self.m.file, st.line, col or st.words[0].col)

    def define(self, st: Statement) -> None:
        words = st.words
        if len(words) < 3 or words[1].text != "DEF":
            raise self.err("expected CYCL DEF <number> or CYCL CALL", st)
        num_text = words[2].text
        try:
            number = float(num_text)
        except ValueError:
            raise self.err(f"CYCL DEF {num_text}: expected a cycle number", st,
                           words[2].col) from None
        major = int(number)
        sub = round((number - major) * 10)
        rest = words[3:]
        if major == 32:
            self._tolerance(st, sub, rest)
        elif major == 7:
            self._datum(st, sub, rest)
        elif major == 10:
            self._rotation(st, sub, rest)
        elif major == 9:
            self._dwell(st, sub, rest)
        elif major == 247:
            self._preset(st, rest)
        elif major in DRILLING:
            self.modal_call = False
            self.defined = (major, self._qvalues(st, rest), Source(self.m.file, st.line,
                                                                   words[0].col))
        elif major in _SL:
            raise self.err(f"CYCL DEF {num_text}: SL contour cycles are not read by ccopt "
                           "(the TNC computes their paths itself)", st, words[2].col)
        elif major in _POCKETS:
            raise self.err(f"CYCL DEF {num_text}: pocket and stud milling cycles are not read "
                           "by ccopt (the TNC computes their paths itself)", st, words[2].col)
        else:
            raise self.err(f"CYCL DEF {num_text}: this cycle is not read by ccopt (7, 9, 10, "
                           f"32, 247 and the drilling cycles {sorted(DRILLING)} are)", st,
                           words[2].col)

    def _qvalues(self, st: Statement, rest) -> dict:
        """The ``Qn=value`` words of a cycle definition. A value may stand
        apart (``Q208= MAX``, as a post writes it); ``MAX``/``FMAX`` (rapid)
        is read for the retraction feed ``Q208`` only, ``AUTO``/``FAUTO`` as
        the feed of TOOL CALL."""
        out = {}
        words = list(rest)
        for k, w in enumerate(words):
            if "=" not in w.text:
                continue                      # the cycle's name: DRILLING, ...
            name, _, value = w.text.partition("=")
            if not value and k + 1 < len(words) and "=" not in words[k + 1].text:
                value = words[k + 1].text
            out[name] = self._qvalue(st, w, name, value)
        return out

    def _qvalue(self, st: Statement, w, name: str, value: str) -> float:
        word = value.removeprefix("F")
        if word == "MAX":
            if name != "Q208":
                raise self.err(f"{name}={value}: a rapid feed is read for the retraction "
                               "feed Q208 only", st, w.col)
            return RAPID
        if word == "AUTO":
            if self.m.tool_feed is None:
                raise self.err(f"{name}={value}: the feed of TOOL CALL is not given", st,
                               w.col)
            return self.m.tool_feed           # as written, per minute
        return self.m.q.number(value, st.line, w.col, name + "=")

    def _tolerance(self, st: Statement, sub: int, rest) -> None:
        if sub != 1:
            return
        tol = None
        for w in rest:
            if w.text.startswith("T") and len(w.text) > 1:
                tol = self.m.q.number(w.text[1:], st.line, w.col, "T")
        self.m.meta[TOLERANCES].append({"line": st.line, "tolerance": tol})

    def _datum(self, st: Statement, sub: int, rest) -> None:
        if self.m.rot != 0.0 and sub > 0:
            raise self.err("CYCL DEF 7 while the working plane is turned (CYCL DEF 10): "
                           "ccopt reads the datum shift before the rotation only (shift "
                           "first, then turn)", st)
        for w in rest:
            t = w.text
            inc = t.startswith("I")
            axis = t[1:2] if inc else t[:1]
            if axis not in "XYZ" or len(t) < (3 if inc else 2):
                if sub == 0:
                    continue                  # 7.0 DATUM SHIFT
                raise self.err(f"CYCL DEF 7: {t} is not read by ccopt (X, Y, Z shifts are; "
                               "datum tables are not)", st, w.col)
            i = "XYZ".index(axis)
            v = self.m.q.number(t[2 if inc else 1:], st.line, w.col, axis)
            self.m.datum[i] = self.m.datum[i] + v if inc else v

    def _rotation(self, st: Statement, sub: int, rest) -> None:
        """``CYCL DEF 10.0 ROTATION`` / ``CYCL DEF 10.1 ROT+a`` (or ``IROT+a``,
        added): the working plane turned about the tool axis by ``a`` degrees
        about the datum, counter-clockwise from its first axis; ``ROT+0`` ends it."""
        if sub == 0:
            return
        for w in rest:
            t = w.text
            if t.startswith(("ROT", "IROT")) and len(t) > (4 if t[0] == "I" else 3):
                inc = t.startswith("I")
                v = self.m.q.number(t[4 if inc else 3:], st.line, w.col, "ROT")
                self.m.rot = self.m.rot + v if inc else v
                return
            raise self.err(f"CYCL DEF 10.1: expected ROT+<degrees> or IROT+<degrees>, not "
                           f"{t}", st, w.col)
        raise self.err("CYCL DEF 10.1: give the angle, ROT+30", st)

    def _preset(self, st: Statement, rest) -> None:
        """``CYCL DEF 247 DATUM SETTING Q339=n``: activate row ``n`` of the
        preset table, the origin of the workpiece coordinate system. ccopt
        does not know the table: the program is read in the frame of the
        first preset it selects (as the G-code reader takes unknown origins
        at 0); selecting another row is refused, located."""
        q = self._qvalues(st, rest)
        if "Q339" not in q:
            raise self.err("CYCL DEF 247: give the preset number Q339", st)
        preset = int(round(q["Q339"]))
        seen = self.m.meta.setdefault(PRESETS, [])
        if seen and seen[0]["preset"] != preset:
            raise self.err(f"CYCL DEF 247: preset {preset} after preset {seen[0]['preset']} "
                           f"(line {seen[0]['line']}) is not read by ccopt: the offset "
                           "between two presets is in the preset table, not in the program",
                           st)
        seen.append({"line": st.line, "preset": preset})

    def _dwell(self, st: Statement, sub: int, rest) -> None:
        if sub != 1:
            return
        nums = [w for w in rest if w.text != "DWELL"]
        if not nums:
            raise self.err("CYCL DEF 9.1: give the dwell time in seconds", st)
        t = self.m.q.number(nums[0].text, st.line, nums[0].col, "DWELL ")
        if t > 0:
            self.m.emit(Source(self.m.file, st.line, st.words[0].col), Motion.DWELL,
                        self.m.pos, dwell=t)

    # -- calls ---------------------------------------------------------------------------
    def call(self, src: Source, surface: float | None = None) -> None:
        """Run the defined drilling cycle where the tool stands; ``surface``
        (``CYCL CALL POS``) replaces its ``Q203``."""
        if self.defined is None:
            raise ProgramError("cycle call without a drilling cycle defined (CYCL DEF 200 ...)",
                               src.file, src.line, src.col)
        number, q, _ = self.defined
        m = self.m
        if surface is not None:
            q = {**q, "Q203": surface}
        for name in ("Q200", "Q201", "Q203"):
            if name not in q:
                raise ProgramError(f"CYCL DEF {number}: {name} is missing", src.file, src.line,
                                   src.col)
        if number == 240 and q.get("Q343", 0.0) != 0.0:
            raise ProgramError("CYCL DEF 240 with Q343=1 (depth from a diameter) is not read by "
                               "ccopt: give the depth (Q343=0)", src.file, src.line, src.col)
        if number in _PITCH_FEED:
            # rigid tapping feeds one thread pitch Q239 per spindle turn
            if "Q239" not in q or not m.speed:
                raise ProgramError(f"CYCL DEF {number}: the feed is the pitch Q239 times the "
                                   "spindle speed S of TOOL CALL: give both", src.file, src.line,
                                   src.col)
            q = {**q, "Q206": abs(q["Q239"]) * m.speed}
        depth = q["Q201"]
        if depth > 0:
            raise ProgramError(f"CYCL DEF {number}: Q201={depth:g} must be negative (a depth "
                               "below the surface)", src.file, src.line, src.col)
        if depth == 0:
            return
        if number == 209:
            self._chip_breaking_tap(src, q)
            return
        self._moves(src, number, q)

    def _moves(self, src: Source, number: int, q: dict) -> None:
        m = self.m
        iw = PLANE_AXES[m.plane][2]
        sign = 1.0      # the tool axis points away from the work
        surf = q["Q203"] + m.datum[iw]
        clear = surf + sign * abs(q["Q200"])
        bottom = surf + q["Q201"]
        second = surf + sign * abs(q.get("Q204", 0.0))
        feed = q.get("Q206", 0.0)
        if feed <= 0:
            raise ProgramError(f"CYCL DEF {number}: the feed Q206 must be positive", src.file,
                               src.line, src.col)
        fps = self._per_second(feed)
        go = self._axis_move(src, f"CYCL {number}")

        go(clear, True)
        step = q.get("Q202", 0.0)
        level = surf
        while number in _PECKING and 0 < step < level - bottom:
            level -= step
            go(level, False, fps)
            go(clear, True)
            go(level + abs(q["Q200"]), True)
        go(bottom, False, fps)
        if q.get("Q211", 0.0) > 0:
            m.emit(src, Motion.DWELL, m.pos, dwell=q["Q211"], cycle=f"CYCL {number}")
        back = _FEED_RETRACT.get(number)
        back_feed = q.get(back, 0.0) if back else 0.0
        if back and back_feed <= 0:
            back_feed = feed
        rapid_back = back is None or back_feed == RAPID
        go(clear, rapid_back, None if rapid_back else self._per_second(back_feed))
        if second > clear:
            go(second, True)

    def _per_second(self, feed: float) -> float:
        """A cycle feed (per minute, as programmed) in program units per second."""
        return feed / 60.0 / (10.0 if self.m.units == "inch" else 1.0)

    def _axis_move(self, src: Source, tag: str):
        """``go(w, rapid, feed)``: a move along the tool axis to ``w``."""
        m = self.m
        iw = PLANE_AXES[m.plane][2]

        def go(w: float, rapid: bool, f: float | None = None) -> None:
            p = list(m.pos)
            if abs(p[iw] - w) > 0.0:
                p[iw] = w
                m.emit(src, Motion.LINE, p, rapid=rapid, feed=f, side=0, cycle=tag)
        return go

    def _chip_breaking_tap(self, src: Source, q: dict) -> None:
        """Cycle 209, tapping with chip breaking (TNC 640 Cycle Programming
        34059x-01, 4.4, cycle parameters): tap at the pitch feed ``Q206`` (set
        from ``Q239`` and S) in infeeds of ``Q257`` below the surface; after
        each, retract by ``Q256`` times the pitch at the pitch feed and tap on,
        or with ``Q256=0`` retract to the set-up clearance and tap back down to
        the depth reached; at the depth ``Q201`` retract to the set-up
        clearance at the pitch feed times the RPM factor ``Q403`` (the faster
        retraction from the hole; default 1), which also applies to the full
        ``Q256=0`` retractions; then to the second set-up clearance at
        rapid when it is higher. ``Q257=0``: no chip breaking."""
        m = self.m
        iw = PLANE_AXES[m.plane][2]
        surf = q["Q203"] + m.datum[iw]
        clear = surf + abs(q["Q200"])
        bottom = surf + q["Q201"]
        second = surf + abs(q.get("Q204", 0.0))
        tap = self._per_second(q["Q206"])
        if tap <= 0:
            raise ProgramError("CYCL DEF 209: the pitch Q239 must not be 0", src.file, src.line,
                               src.col)
        factor = q.get("Q403", 1.0)
        if factor <= 0:
            raise ProgramError(f"CYCL DEF 209: Q403={factor:g} must be positive (the RPM "
                               "factor for retraction)", src.file, src.line, src.col)
        out = tap * factor
        back = abs(q.get("Q256", 0.0) * q["Q239"])
        step = q.get("Q257", 0.0)
        go = self._axis_move(src, "CYCL 209")
        go(clear, True)
        level = surf
        while 0 < step < level - bottom:
            level -= step
            go(level, False, tap)
            if back > 0:
                go(min(level + back, clear), False, tap)
            else:
                go(clear, False, out)
                go(level, False, tap)
        go(bottom, False, tap)
        go(clear, False, out)
        if second > clear:
            go(second, True)

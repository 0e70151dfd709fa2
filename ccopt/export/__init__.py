"""Export a tool path: G-code (``.nc``/``.ngc``), PMAC (``.pmc``), SVG, JSON.

Every program export is **read back** with ccopt's own reader before it is
kept: the read-back path must lie within the export tolerance of the computed
one (rounding of the written numbers plus the certified error of the arcs
and lines fitted to spirals and Bezier blend curves, :mod:`.arcfit`), and,
when the programmed contour is given, it is verified against it. The verdict
goes into the file's header comments and into the returned
:class:`ExportResult`. Writes are atomic (:mod:`ccopt.atomic`): a failure
leaves no partial file and never replaces a good one. An export whose
verification fails is written, but never over an existing file: when
``NAME.EXT`` exists it goes to ``NAME.failed.EXT`` beside it
(:func:`failed_name`) and the result says so (:attr:`ExportResult.kept_existing`).
Every text the writers put in a file (titles, headers) passes through
:mod:`ccopt.export.text`, so the file's commands are the path's alone.
An export never writes over a file its program was read from (the program,
its subroutine files, tool table, parameter file; a link to one included):
that is a :class:`~ccopt.errors.ProgramError` before anything is computed or
written (:func:`ccopt.atomic.refuse_overwriting_inputs`).
"""
from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

from ccopt.atomic import refuse_overwriting_inputs, write_text_atomic
from ccopt.errors import ProgramError
from ccopt.export.arcfit import DEFAULT_TOL
from ccopt.export.gcode import write_gcode
from ccopt.export.pmacprog import write_pmac
from ccopt.export.readback import readback_path
from ccopt.export.roundtrip import roundtrip_error
from ccopt.export.svg import write_svg
from ccopt.export.text import with_header
from ccopt.program.gcode.execute import LATHE_DIAMETER_MODE_USED
from ccopt.program.model import INPUT_FILES, START_PARAMETERS, Program
from ccopt.tolerances import EXPORT_REFIT_MIN_TOL, EXPORT_REFIT_ROUNDS, EXPORT_REFIT_SHRINK
from ccopt.toolpath import ToolPath, programmed_path
from ccopt.verify import verify
from ccopt.version import __version__

FORMATS = {".nc": "gcode", ".ngc": "gcode", ".gcode": "gcode", ".tap": "gcode",
           ".pmc": "pmac", ".pmac": "pmac", ".svg": "svg", ".json": "json"}


@dataclass
class ExportResult:
    """What was written and how it was checked.

    roundtrip_error: largest distance between the read-back path and the
        computed one (program units): rounding of written numbers plus the
        certified fit error of arcs and lines replacing spirals and curves.
    fit_error: largest certified bound of the arcs (and lines) fitted to
        spirals (G-code only: PMAC runs spirals natively) and to Bezier blend
        curves (both formats); 0 if none.
    fitted_moves: how many moves replace spirals and blend curves.
    verified: verdict of the verifier on the read-back path (``None`` when no
        program was given to verify against, or it has nothing to verify).
    nothing_to_verify: why the export was not verified though a program was
        given (``"nothing to verify: the program has no moves"``), else ``None``.
    kept_existing: the existing file a failing export was not written over
        (then ``file`` is its ``NAME.failed.EXT``); ``None`` otherwise.
    """

    file: str
    format: str
    tolerance: float
    roundtrip_error: float = 0.0
    fit_error: float = 0.0
    fitted_moves: int = 0
    verified: bool | None = None
    notes: list[str] = field(default_factory=list)
    kept_existing: str | None = None
    nothing_to_verify: str | None = None
    #: the verifier's :class:`~ccopt.verify.Certificate` of the read-back path,
    #: or None; :attr:`certificate` is its JSON, made when first asked (a path
    #: with many violations or warnings takes long to put in dicts)
    verdict: object = field(default=None, repr=False)

    @cached_property
    def certificate(self) -> dict | None:
        """The certificate as JSON (:meth:`Certificate.to_json`), or None."""
        return None if self.verdict is None else self.verdict.to_json()

    def to_json(self) -> dict:
        return {"file": self.file, "format": self.format, "tolerance": self.tolerance,
                "roundtrip_error": self.roundtrip_error, "fit_error": self.fit_error,
                "fitted_moves": self.fitted_moves, "verified": self.verified,
                "certificate": self.certificate, "notes": self.notes,
                "kept_existing": self.kept_existing, "nothing_to_verify": self.nothing_to_verify}

    def where_written(self) -> str:
        """For messages: ``""``, or where a failing export went instead of the
        existing file."""
        if self.kept_existing is None:
            return ""
        return (f"; written as {self.file}, not over the existing {self.kept_existing} "
                f"(left as it was)")


#: What marks a file ccopt wrote, by suffix: the header line of every exported
#: program (``ccopt 0.1.0 export: style ...``) and the report's title.
_MADE_BY_CCOPT = {".nc": re.compile(r"ccopt \S+ export: style "),
                  ".pmc": re.compile(r"ccopt \S+ export: style "),
                  ".html": re.compile(r"<title>ccopt run(: [^<]*)?</title>")}
#: How much of a file's beginning :func:`written_by_ccopt` reads (its header).
_HEADER_BYTES = 4096


def written_by_ccopt(path: str | os.PathLike) -> bool | None:
    """Whether ``path`` (a .nc or .pmc program, or a run's index.html) is one
    ccopt wrote: its header says so; ``None`` for other kinds (no mark to tell)."""
    mark = _MADE_BY_CCOPT.get(Path(path).suffix.lower())
    if mark is None:
        return None
    try:
        with open(path, "rb") as fh:
            head = fh.read(_HEADER_BYTES).decode("utf-8", "replace")
    except OSError:
        return False
    return mark.search(head) is not None


def refuse_foreign_files(outputs) -> None:
    """:class:`ProgramError` (exit 2, naming the file) when one of the files
    ``outputs`` a command would write under names it chose itself (``ccopt
    run -o DIR``) exists and was not written by ccopt (:func:`written_by_ccopt`:
    programs and the report's index.html; other kinds are not checked): a
    program of the user's (``part.pmc`` beside the ``part.nc`` being run), or
    the ``index.html`` of a folder, which the run's own would replace. An
    explicit ``-o FILE`` is the user's choice and replaces its file as any
    command does."""
    for out in outputs:
        out = Path(out)
        if (out.exists() or out.is_symlink()) and written_by_ccopt(out) is False:
            raise ProgramError("not written: a file ccopt did not write is there (one of "
                               "yours?); give -o another folder, or move it", str(out))


def failed_name(out: Path) -> Path:
    """``NAME.failed.EXT`` beside ``out`` (``NAME.EXT``): where a failing export
    goes when ``out`` exists."""
    return out.with_name(f"{out.stem}.failed{out.suffix}")


def inputs_of(program: Program | None, path: ToolPath | None = None) -> tuple[str, ...]:
    """The files ``program`` was read from (:data:`~ccopt.program.model.INPUT_FILES`;
    none for a program read from text), and those ``path``'s moves and dwells
    come from (their blocks' source files: the program even when none is given)."""
    files = dict.fromkeys(program.meta.get(INPUT_FILES, ()) if program is not None else ())
    if path is not None:
        files.update(dict.fromkeys(
            [seg.block.source.file for seg in path.segments if seg.block is not None]
            + [blk.source.file for _, _, blk in path.dwells if blk is not None]))
    return tuple(files)


def _write_checked(res: ExportResult, out: Path, text: str, program: Program | None) -> None:
    """Write ``text`` to ``out``, or to :func:`failed_name` when the export
    failed its verification and ``out`` exists (recorded in ``res``); never
    over one of ``program``'s input files."""
    if res.verified is False and (out.exists() or out.is_symlink()):
        res.kept_existing = str(out)
        out = failed_name(out)
        res.file = str(out)
        res.notes.append(f"verification failed: written as {out.name}, the existing "
                         f"{res.kept_existing} left as it was")
    refuse_overwriting_inputs([out], inputs_of(program))
    write_text_atomic(out, text)


def _tighter_fits(cert, moves: list, seg_tol: dict[int, float], tol: float) -> dict[int, float]:
    """``seg_tol`` with a tighter fit for every source segment one of whose
    fitted moves (a move with a fit bound) gouges in ``cert``: its bound over
    :data:`~ccopt.tolerances.EXPORT_REFIT_SHRINK`, never below
    :data:`~ccopt.tolerances.EXPORT_REFIT_MIN_TOL` (the written numbers'
    rounding, which no fit can beat)."""
    out = dict(seg_tol)
    # exact lines and arcs have no bound: nothing to refit, and a path of
    # them alone (the common case) needs no look at its gouges
    fitted = {m: (src, bound) for m, (src, _, bound) in enumerate(moves)
              if src >= 0 and bound > 0.0}
    if not fitted:
        return out
    # each move once, in the order it first gouges: tightening is monotone,
    # so a move's later gouges change nothing
    for m in dict.fromkeys(v.tool_segment for v in cert.violations_of("gouge")):
        if m not in fitted:
            continue
        src, bound = fitted[m]
        now = out.get(src, tol)
        new = max(min(now, bound / EXPORT_REFIT_SHRINK), EXPORT_REFIT_MIN_TOL)
        if new < now:
            out[src] = new
    return out


def _verify(path: ToolPath, program: Program | None):
    """Certificate of ``path`` against ``program``'s contour, or ``None`` (no
    program, or one with nothing to verify: no moves)."""
    if program is None or program.nothing_to_verify():
        return None
    return verify(path, program)


@dataclass
class _ProgramExport:
    """One G-code or PMAC export: write, read back with ccopt's reader, verify.

    ``seg_tol`` maps a tool-path segment index to a fit tolerance tighter than
    ``tol`` (program units) for the spiral or curve it holds.
    """

    path: ToolPath
    fmt: str
    tol: float
    out: Path
    program: Program | None
    header: list[str]

    #: The last text written without a header, its moves and the fit
    #: tolerances it was written with: the final file differs from the attempt
    #: that was read back only in its header comments.
    _last: tuple | None = None

    def write(self, header: list[str], seg_tol: dict[int, float]) -> tuple[str, list]:
        """Program text and its moves ``(source segment, meant geometry, fit bound)``."""
        if self._last is None or self._last[0] != seg_tol:
            self._last = (dict(seg_tol), *self._write(seg_tol))
        _, body, moves = self._last
        return with_header(body, header, self.fmt), moves

    def _write(self, seg_tol: dict[int, float]) -> tuple[str, list]:
        """:meth:`write` without a header."""
        if self.fmt == "gcode":
            # a program that used G7 (lathe diameter mode) is written in radii under G8
            radius_mode = bool(self.program is not None
                               and self.program.meta.get(LATHE_DIAMETER_MODE_USED))
            return write_gcode(self.path, self.tol, None, seg_tol=seg_tol,
                               radius_mode=radius_mode, program=self.program)[:2]
        # the program number the PMAC program was read from, kept
        number = (self.program.meta.get("program") if self.program is not None
                  and self.program.dialect == "pmac" else None)
        return write_pmac(self.path, None, tol=self.tol, seg_tol=seg_tol,
                          program_number=number if isinstance(number, int) else 1)

    def attempt(self, seg_tol: dict[int, float]):
        """Write, read back, verify: ``(moves, round-trip error, certificate)``."""
        text, moves = self.write(self.header, seg_tol)
        params = self.program.meta.get(START_PARAMETERS) if self.program is not None else None
        back = readback_path(text, self.fmt, self.path, moves, str(self.out),
                             parameters=params)
        return moves, roundtrip_error(back, moves), _verify(back, self.program)

    def refit(self, seg_tol, moves, roundtrip, cert):
        """Tighten the fits whose read-back gouges, at most
        :data:`~ccopt.tolerances.EXPORT_REFIT_ROUNDS` times.

        A fit is tightened only where the read-back fails and the computed
        path itself does not; every round that is kept was read back and
        verified, and the file is written from the last one. Returns the
        kept ``(seg_tol, moves, roundtrip, cert)``.
        """
        if cert is None or cert.ok:
            return seg_tol, moves, roundtrip, cert
        # No fitted move gouges (a path of lines and arcs only, say): nothing to
        # tighten, so the computed path need not be verified to know it.
        if _tighter_fits(cert, moves, seg_tol, self.tol) == seg_tol:
            return seg_tol, moves, roundtrip, cert
        if not _verify(self.path, self.program).ok:
            return seg_tol, moves, roundtrip, cert
        for _ in range(EXPORT_REFIT_ROUNDS):
            tighter = _tighter_fits(cert, moves, seg_tol, self.tol)
            if tighter == seg_tol:
                break
            try:
                moves_t, rt_t, cert_t = self.attempt(tighter)
            except ValueError:      # the tighter fit needs too many pieces
                break
            seg_tol, moves, roundtrip, cert = tighter, moves_t, rt_t, cert_t
            if cert.ok:
                break
        return seg_tol, moves, roundtrip, cert


def _fit_summary(res: ExportResult, path: ToolPath, moves: list,
                 seg_tol: dict[int, float]) -> str:
    """Record the fitted moves in ``res``; their one-line description."""
    fitted = [bound for src, geom, bound in moves
              if src >= 0 and type(geom) is not type(path.segments[src].geom)]
    res.fit_error = max(fitted, default=0.0)
    res.fitted_moves = len(fitted)
    fit = (f"spirals and blend curves as {res.fitted_moves} arcs/lines certified within "
           f"{res.fit_error:.3g}" if res.fitted_moves else "no spirals or blend curves to fit")
    if seg_tol:
        fit += (f"; fitted within {min(seg_tol.values()):.3g} on {len(seg_tol)} segment(s) "
                f"running at the clearance limit")
        res.notes.append(f"fit tightened on segments {sorted(seg_tol)}: the read-back at "
                         f"the default fit came inside the clearance")
    return fit


def _verdict(res: ExportResult, path: ToolPath, fit: str, cert) -> list[str]:
    """Header lines saying how the file was checked; records the verdict in ``res``."""
    lines = [f"read back with ccopt: within {res.roundtrip_error:.3g} {path.units} of the "
             f"computed path (tolerance {res.tolerance:g}; {fit})"]
    if cert is not None:
        res.verified = bool(cert.ok)
        res.verdict = cert
        # no clearance figure when the path has no compensated move to check
        clearance = ("no compensated move to check" if cert.min_clearance is None else
                     f"minimum clearance {cert.min_clearance:.6g} for radius {path.radius:g}")
        lines.append(f"verified against the programmed contour: "
                     f"{'OK' if cert.ok else 'FAILED'}, {clearance}")
    elif res.nothing_to_verify:
        lines.append(res.nothing_to_verify)
    else:
        lines.append("not verified: no programmed contour given")
    return lines


def _export_program(res: ExportResult, path: ToolPath, out: Path, program: Program | None,
                    title: str) -> None:
    """G-code or PMAC: checked by read-back (and verification) before it is written."""
    header = [f"ccopt {__version__} export: style {path.style}, cutter radius {path.radius:g} "
              f"{path.units}, tool-centre path (no compensation words)"]
    if title:
        header.insert(0, title)
    if res.format == "gcode" and program is not None and program.dialect == "gcode":
        header.append("kept from the program: tool, spindle, coolant and other machine words, "
                      "its work coordinates and G54-G59.3, its program end; canned cycles and "
                      "subroutines written as their moves, threads as G33 K")
    job = _ProgramExport(path, res.format, res.tolerance, out, program, header)
    seg_tol: dict[int, float] = {}
    moves, roundtrip, cert = job.attempt(seg_tol)
    if roundtrip > res.tolerance:
        raise ProgramError(f"read-back deviates {roundtrip:.3g} from the computed path, more "
                           f"than the tolerance {res.tolerance:g}; nothing written", str(out))
    seg_tol, moves, res.roundtrip_error, cert = job.refit(seg_tol, moves, roundtrip, cert)
    fit = _fit_summary(res, path, moves, seg_tol)
    text = job.write(header + _verdict(res, path, fit, cert), seg_tol)[0]
    _write_checked(res, out, text, program)


def _export_json(res: ExportResult, path: ToolPath, out: Path, program: Program | None) -> None:
    """The tool path and, given the program, its certificate."""
    cert = _verify(path, program)
    if cert is not None:
        res.verified = bool(cert.ok)
        res.verdict = cert
    doc = {"toolpath": path.to_json(), "certificate": res.certificate}
    _write_checked(res, out, json.dumps(doc) + "\n", program)


def export(path: ToolPath, out: str | os.PathLike, *, program: Program | None = None,
           tol: float | None = None, fmt: str | None = None, title: str = "") -> ExportResult:
    """Write ``path`` to ``out`` in the format its suffix names (or ``fmt``).

    Program formats are read back and checked first (see module docstring);
    ``program`` is the programmed contour to verify the read-back against.
    ``tol`` is the export tolerance in program units (default
    :data:`~ccopt.export.arcfit.DEFAULT_TOL` for the path's units).
    Raises :class:`ProgramError` (nothing written) when the read-back does not
    reproduce the path within ``tol``. A program or JSON export whose
    verification fails is written to ``NAME.failed.EXT`` when ``out`` exists
    (``res.file`` then names it, ``res.kept_existing`` the file left alone).
    :class:`ProgramError`, nothing written, when ``out`` is one of the files
    ``program`` or ``path``'s moves were read from (the same file once links
    are resolved).
    """
    refuse_overwriting_inputs([out], inputs_of(program, path))      # named as the caller gave it
    out = Path(out)
    fmt = fmt or FORMATS.get(out.suffix.lower())
    if fmt is None:
        raise ProgramError(f"unknown export format {out.suffix!r}; use one of "
                           f"{', '.join(sorted(FORMATS))}", str(out))
    tol = DEFAULT_TOL[path.units] if tol is None else float(tol)
    if not tol > 0:
        raise ProgramError("export tolerance must be > 0", str(out))
    res = ExportResult(str(out), fmt, tol)
    if program is not None:
        res.nothing_to_verify = program.nothing_to_verify()
    if fmt in ("gcode", "pmac"):
        _export_program(res, path, out, program, title)
    elif fmt == "svg":
        contour = programmed_path(program) if program is not None else None
        write_text_atomic(out, write_svg(path, contour, title))
    else:
        _export_json(res, path, out, program)
    return res


__all__ = ["DEFAULT_TOL", "ExportResult", "FORMATS", "export", "failed_name", "readback_path",
           "refuse_foreign_files", "roundtrip_error", "write_gcode", "write_pmac", "write_svg",
           "written_by_ccopt"]

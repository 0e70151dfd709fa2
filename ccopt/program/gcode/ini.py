"""A LinuxCNC configuration's INI file, for what it tells the G-code reader.

A program written for a LinuxCNC machine is read with that machine's
settings; ``--ini FILE`` (:func:`read_ini`) takes them from its INI file:

* ``[EMCIO] TOOL_TABLE``: the tool table;
* ``[TRAJ] LINEAR_UNITS``: the machine's length unit, the unit of the tool
  table's diameters (``mm``/``metric``, or ``inch``/``in``/``imperial``;
  without it inches, as LinuxCNC's stand-alone interpreter assumes:
  ``src/emc/sai/driver.cc``);
* ``[RS274NGC] SUBROUTINE_PATH``: the folders ``o<name> call`` searches, ``:``
  separated; ``PARAMETER_FILE``: the parameter file in force at the start
  (none while it does not exist, as LinuxCNC starts);
* ``[RS274NGC] DISABLE_FANUC_STYLE_SUB``: ``M98``/``M99`` subprograms refused
  (LinuxCNC's message); ``DISABLE_G92_PERSISTENCE``: the parameter file's
  ``G92`` offset (``#5210``-``#5219``) not restored at the start (both
  booleans: 1/0, TRUE/FALSE, YES/NO, ON/OFF in any case; off by default);
* every ``NAME = VALUE`` for ``#<_ini[SECTION]NAME>`` in the program, unless
  ``[RS274NGC] INI_VARS = 0`` (LinuxCNC's default is 1).

Relative file and folder names are relative to the INI file's folder, as
LinuxCNC takes them. Lines are ``[SECTION]``, ``NAME = VALUE`` or comments
(``#`` or ``;`` first); section and name compare without regard to case
(``#<_ini[vars]toolchange_x>`` reads ``[VARS] TOOLCHANGE_X``: the G-code
reader lowercases parameter names); the first of two equal names counts, as
LinuxCNC's ``IniFile::Find`` returns the first. Anything else is an error
located at its line.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ccopt.errors import ProgramError
from ccopt.program.gcode.coordinates import G92_PARAMETERS

_SECTION = re.compile(r"\[\s*([^\]]*?)\s*\]\s*$")
_ENTRY = re.compile(r"([^=]*?)\s*=\s*(.*?)\s*$")
#: LinuxCNC's boolean INI values (``IniFile::findBoolV``), in lower case.
_BOOLEANS = {"1": True, "true": True, "yes": True, "on": True,
             "0": False, "false": False, "no": False, "off": False}
#: ``[TRAJ] LINEAR_UNITS`` values and the unit each means.
LINEAR_UNITS = {"mm": "mm", "metric": "mm", "inch": "inch", "in": "inch", "imperial": "inch"}


@dataclass(frozen=True)
class LinuxCncIni:
    """The ``NAME = VALUE`` entries of an INI file by ``(SECTION, NAME)`` (upper
    case), their lines, and the settings the reader takes from them."""

    file: str
    values: dict[tuple[str, str], str] = field(default_factory=dict)
    lines: dict[tuple[str, str], int] = field(default_factory=dict)

    @property
    def folder(self) -> Path:
        return Path(self.file).resolve().parent

    def get(self, section: str, name: str) -> str | None:
        return self.values.get((section.upper(), name.upper()))

    def _path(self, section: str, name: str) -> Path | None:
        value = self.get(section, name)
        return None if not value else self.folder / value

    @property
    def tool_table(self) -> Path | None:
        """``[EMCIO] TOOL_TABLE``, or None."""
        return self._path("EMCIO", "TOOL_TABLE")

    @property
    def var_file(self) -> Path | None:
        """``[RS274NGC] PARAMETER_FILE``, or None, also when the file does not exist
        yet: LinuxCNC then starts from its default parameters and writes the
        file later (``Interp::restore_parameters``, rs274ngc_pre.cc)."""
        path = self._path("RS274NGC", "PARAMETER_FILE")
        return path if path is not None and path.exists() else None

    @property
    def sub_path(self) -> tuple[str, ...]:
        """``[RS274NGC] SUBROUTINE_PATH``'s folders, in order."""
        value = self.get("RS274NGC", "SUBROUTINE_PATH") or ""
        return tuple(str(self.folder / p) for p in value.split(":") if p.strip())

    @property
    def table_units(self) -> str:
        """The machine's length unit (module docstring): ``"mm"`` or ``"inch"``."""
        value = self.get("TRAJ", "LINEAR_UNITS")
        if value is None:
            return "inch"
        unit = LINEAR_UNITS.get(value.strip().lower())
        if unit is None:
            raise ProgramError(f"[TRAJ] LINEAR_UNITS = {value}: ccopt knows "
                               + ", ".join(LINEAR_UNITS), self.file,
                               self.lines[("TRAJ", "LINEAR_UNITS")])
        return unit

    def flag(self, section: str, name: str) -> bool:
        """``[SECTION] NAME`` as a boolean (False when absent); a located
        :class:`~ccopt.errors.ProgramError` when it is not one."""
        value = self.get(section, name)
        if value is None:
            return False
        flag = _BOOLEANS.get(value.strip().lower())
        if flag is None:
            raise ProgramError(f"[{section.upper()}] {name.upper()} = {value}: a yes/no "
                               "setting (1 or 0, TRUE or FALSE, YES or NO, ON or OFF)",
                               self.file, self.lines[(section.upper(), name.upper())])
        return flag

    @property
    def fanuc_subs_disabled(self) -> bool:
        """``[RS274NGC] DISABLE_FANUC_STYLE_SUB``: M98/M99 subprograms refused."""
        return self.flag("RS274NGC", "DISABLE_FANUC_STYLE_SUB")

    @property
    def g92_persistence_disabled(self) -> bool:
        """``[RS274NGC] DISABLE_G92_PERSISTENCE``: the G92 offset starts cleared."""
        return self.flag("RS274NGC", "DISABLE_G92_PERSISTENCE")

    def start_parameters(self, parameters: dict[int, float] | None) -> dict[int, float] | None:
        """The numbered parameters a program starts with, from the parameter
        file's ``parameters``: under ``DISABLE_G92_PERSISTENCE`` the G92 ones
        cleared, as LinuxCNC's init clears them (rs274ngc_pre.cc)."""
        if not parameters or not self.g92_persistence_disabled:
            return parameters
        first, last = G92_PARAMETERS
        return {k: (0.0 if first <= k <= last else v) for k, v in parameters.items()}

    @property
    def ini_vars(self) -> bool:
        """Whether the program may read ``#<_ini[SECTION]NAME>`` (``[RS274NGC] INI_VARS``)."""
        value = self.get("RS274NGC", "INI_VARS")
        return value is None or value.strip() not in ("0",)

    def number(self, section: str, name: str) -> float | None:
        """``[SECTION] NAME`` as a number, or None when the file has no such entry
        (or ``INI_VARS = 0``); a :class:`ValueError` naming the entry when its
        value is not a number."""
        if not self.ini_vars:
            return None
        value = self.get(section, name)
        if value is None:
            return None
        try:
            return float(value)
        except ValueError:
            raise ValueError(f"[{section.upper()}] {name.upper()} = {value} in {self.file} "
                             "is not a number") from None


def read_ini(path: str | os.PathLike) -> LinuxCncIni:
    """The INI file at ``path`` (module docstring); a located
    :class:`~ccopt.errors.ProgramError` when it cannot be read or a line is
    none of a section, an entry and a comment."""
    file = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise ProgramError(f"cannot read INI file: {exc.strerror or exc}", file) from None
    values: dict[tuple[str, str], str] = {}
    lines: dict[tuple[str, str], int] = {}
    section = None
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line[0] in "#;":
            continue
        m = _SECTION.match(line)
        if m:
            section = m.group(1).upper()
            continue
        m = _ENTRY.match(line)
        if m is None or not m.group(1):
            raise ProgramError("not a [SECTION], a NAME = VALUE line or a comment", file,
                               number, 1)
        if section is None:
            raise ProgramError(f"{m.group(1)} = ... before any [SECTION]", file, number, 1)
        key = (section, m.group(1).upper())
        if key not in values:            # the first counts, as LinuxCNC's IniFile::Find
            values[key] = m.group(2)
            lines[key] = number
    return LinuxCncIni(file, values, lines)

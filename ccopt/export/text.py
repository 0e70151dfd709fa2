"""Text that ccopt writes into its files, made safe for each format.

A case title, a source note, a program name or an error message comes from
a user's files and may hold anything: a line break followed by commands
(``x\\nI130=0\\nUNDEFINE ALL`` in a PMAC header), a comment delimiter
(``)(M30`` in G-code), markup (``</svg><script>``) or a spreadsheet formula
(``=cmd|' /C calc'!A0`` in a CSV cell). Every writer passes such text
through the one function here for its format, so that what it writes is
inert text where the format expects text, and the file's commands are the
path's alone.

* :func:`one_line` (all formats): line breaks, tabs and every other control
  or format character (Unicode categories Cc, Cf, Zl, Zp: ``\\r``, ``\\x85``,
  U+2028 and the bidirectional overrides too, all of which some reader
  treats as a line end or reorders) become one space.
* :func:`gcode_comment`, :func:`pmac_comment`: plain printable ASCII (a
  controller reads nothing else), the format's comment delimiters replaced,
  and a comment that a controller or ccopt would act on (LinuxCNC's
  ``(MSG,``, ``(LOGOPEN,``, ``(PROBEOPEN``, ccopt's own ``ccopt:`` markers,
  any ``WORD,`` or ``WORD:`` opening) turned into a plain note.
* :func:`xml_text` (SVG, and :func:`html_text`): escaped, quotes included.
* :func:`html_href`: a relative link that no scheme (``javascript:``) can hijack.
* :func:`csv_cell`: one line, and a cell that a spreadsheet would run as a
  formula (first character ``=``, ``+``, ``-``, ``@``, tab or carriage
  return, or their full-width forms) gets a leading ``'``, as the OWASP
  guidance on CSV injection says.
* :func:`plot_text`: one line with matplotlib's mathtext switched off (``$``
  escaped), so a title can neither break a figure nor fail to render.
"""
from __future__ import annotations

import html
import re
import unicodedata
from urllib.parse import quote

#: Unicode categories that are never written: controls, format characters
#: (bidirectional overrides, zero-width joiners), line and paragraph separators.
_UNPRINTABLE = frozenset({"Cc", "Cf", "Zl", "Zp", "Cs", "Co", "Cn"})

#: First characters that make a spreadsheet read a cell as a formula
#: (OWASP, "CSV Injection"), with their full-width forms.
_FORMULA_START = frozenset("=+-@\t\r\uff1d\uff0b\uff0d\uff20")

#: Comments a controller executes (LinuxCNC: MSG, DEBUG, PRINT, LOG*,
#: PROBE*, ABORT, PY) or that ccopt reads as a marker (``ccopt: air``):
#: a comment that opens with a word and ``,`` or ``:`` (``(MSG,``,
#: ``(ccopt: part)``), or with one of the words that need no punctuation.
_ACTIVE_COMMENT = re.compile(r"^\s*([A-Za-z_]+\s*[,:=]|(LOGCLOSE|PROBEOPEN|PROBECLOSE)\b)",
                             re.IGNORECASE)


def one_line(text: object) -> str:
    """``str(text)`` on one line: every control, format or separator
    character replaced by a space, surrounding blanks removed."""
    s = str(text)
    if s.isprintable():
        return s.strip()
    return "".join(" " if unicodedata.category(ch) in _UNPRINTABLE else ch for ch in s).strip()


def _ascii(text: object) -> str:
    """One line of printable ASCII: accents dropped (``é`` -> ``e``), any
    other non-ASCII character written ``?``."""
    s = unicodedata.normalize("NFKD", one_line(text))
    s = "".join(ch for ch in s if not unicodedata.combining(ch))
    return "".join(ch if " " <= ch <= "~" else "?" for ch in s)


def _inert(note: str) -> str:
    """``note`` prefixed with ``'`` when a controller or ccopt would act on it
    as a comment (see :data:`_ACTIVE_COMMENT`)."""
    return f"'{note}" if _ACTIVE_COMMENT.match(note) else note


def gcode_comment(text: object) -> str:
    """A whole G-code comment ``(...)`` holding ``text`` as a note.

    ``(`` and ``)`` become ``[`` and ``]`` (a comment cannot nest or be
    closed early), ``;`` becomes ``,`` (the end-of-line comment of some
    controllers).
    """
    note = _ascii(text).replace("(", "[").replace(")", "]").replace(";", ",")
    return f"({_inert(note)})"


def pmac_comment(text: object) -> str:
    """A whole PMAC comment line ``; ...`` holding ``text`` as a note.

    A PMAC comment runs to the end of the line, so one line is what keeps
    it a comment; besides, ``;`` becomes ``,``, ``\\`` (a line continuation
    to the Executive's C-style preprocessor) ``/``, and ``{``/``}`` (the
    Executive's macro braces) ``[``/``]``.
    """
    note = _ascii(text).replace(";", ",").replace("\\", "/")
    note = note.replace("{", "[").replace("}", "]")
    return f"; {_inert(note)}"


def with_header(text: str, header: list[str] | None, fmt: str) -> str:
    """A written program ``text`` with ``header``'s notes as comment lines,
    where the writers put them: G-code after the opening ``%``, PMAC first
    (``fmt``: ``"gcode"`` or ``"pmac"``)."""
    if not header:
        return text
    if fmt == "gcode":
        first, rest = text.split("\n", 1)
        return "\n".join([first, *map(gcode_comment, header), rest])
    return "\n".join([*map(pmac_comment, header), text])


def xml_text(text: object) -> str:
    """Text or attribute value for SVG/XML: one line, ``& < > " '`` escaped.

    Control characters are removed first because XML 1.0 forbids them (a
    single ``\\x01`` makes the whole drawing unreadable).
    """
    return html.escape(one_line(text), quote=True)


def html_text(text: object) -> str:
    """Text or attribute value for HTML (the same rules as :func:`xml_text`)."""
    return xml_text(text)


def html_href(path: object) -> str:
    """An ``href`` value for a file beside the page: percent-encoded, so a
    name like ``javascript:x`` stays a relative file name (``:`` is ``%3A``)."""
    return html.escape(quote(one_line(path), safe="/._-~"), quote=True)


def csv_cell(value: object) -> object:
    """A CSV cell: text on one line, and a cell a spreadsheet would evaluate
    as a formula prefixed with ``'``; numbers and missing values unchanged."""
    if not isinstance(value, str):
        return value
    s = value if value.isprintable() else one_line(value)
    return f"'{s}" if s[:1] in _FORMULA_START else s


def plot_text(text: object) -> str:
    """A matplotlib title or label: one line, ``$`` escaped so mathtext is
    never parsed (a stray ``$\\frac`` would make the figure fail)."""
    return one_line(text).replace("$", r"\$")


__all__ = ["csv_cell", "gcode_comment", "html_href", "html_text", "one_line", "plot_text",
           "pmac_comment", "xml_text"]

"""Making a :class:`~ccopt.program.model.Block` quickly: a PMAC move's, and a
copy with some fields changed (the G-code reader's every move).

A long PMAC program makes one block per line. ``Block`` and its ``Source``
are frozen dataclasses with slots, whose generated ``__init__`` stores each
field through ``object.__setattr__`` (the way round their own ``__setattr__``,
which refuses): about 2.5 us of the 9 us a plain line took to read (bench/io.py,
100,000 lines). :func:`new_block` stores them through the slots' descriptors,
as directly, in half that time. The objects are the same: a ``Block`` and a
``Source`` whose every field is set, equal and hashed alike; the fields a PMAC
move does not write (``turns``, ``dwell``, ``cycle``, ``words``, ``frame``,
``axes``, ``per_revolution``) take their declared defaults, whatever fields
``Block`` gains later, so long as they have a plain default (checked on
import).
"""
from __future__ import annotations

from dataclasses import MISSING, fields

from ccopt.program.model import Block, Modal, Motion, Source, Vec3

#: The fields a PMAC move gives, in the order :func:`new_block` takes them.
_GIVEN = ("source", "motion", "start", "end", "modal", "center", "feed", "move_time",
          "mcodes", "surface")
_SET = {f.name: getattr(Block, f.name).__set__ for f in fields(Block)}
#: (setter, default) of every other field.
_DEFAULTS = tuple((_SET[f.name], f.default) for f in fields(Block) if f.name not in _GIVEN)
# what new_block relies on in the model, checked once
if any(default is MISSING for _, default in _DEFAULTS) or hasattr(Block, "__post_init__"):
    raise TypeError("Block has a field without a plain default, "  # pragma: no cover
                    "or a __post_init__, which new_block does not know")
if [f.name for f in fields(Source)] != ["file", "line", "col"]:
    raise TypeError("Source has other fields than file, line, col")  # pragma: no cover
(_set_source, _set_motion, _set_start, _set_end, _set_modal, _set_center, _set_feed,
 _set_move_time, _set_mcodes, _set_surface) = (_SET[name] for name in _GIVEN)
#: The setters of Source's file, line and col (shared with pmac/straight.py).
SOURCE_SETTERS = tuple(getattr(Source, name).__set__ for name in ("file", "line", "col"))
_set_file, _set_line, _set_col = SOURCE_SETTERS
#: Each field's setter, and (setter, default) of the fields a PMAC move does
#: not give, for makers of many blocks at once (pmac/straight.py).
FIELD_SETTERS = _SET
DEFAULT_SETTERS = _DEFAULTS
_new = object.__new__
#: (name, setter) of every field of Block.
_ALL = tuple((f.name, _SET[f.name]) for f in fields(Block))


def new_block(file: str, line: int, col: int, motion: Motion, start: Vec3, end: Vec3,
              modal: Modal, center: Vec3 | None, feed: float | None, move_time: float | None,
              mcodes: tuple[int, ...], surface: str | None) -> Block:
    """``Block(source=Source(file, line, col), motion=motion, ...,
    surface=surface)``, the other fields at their defaults; the arguments are
    the fields of the same names (lengths in program units, ``feed`` units per
    second, ``move_time`` s)."""
    source = _new(Source)
    _set_file(source, file)
    _set_line(source, line)
    _set_col(source, col)
    block = _new(Block)
    _set_source(block, source)
    _set_motion(block, motion)
    _set_start(block, start)
    _set_end(block, end)
    _set_modal(block, modal)
    _set_center(block, center)
    _set_feed(block, feed)
    _set_move_time(block, move_time)
    _set_mcodes(block, mcodes)
    _set_surface(block, surface)
    for setter, default in _DEFAULTS:
        setter(block, default)
    return block


def replace_block(block: Block, **changes) -> Block:
    """``dataclasses.replace(block, **changes)``, without ``Block.__init__``
    (the same object: every field set, from ``changes`` or ``block``; Block
    has no ``__post_init__``, checked on import). Unknown names raise
    ``TypeError`` as ``replace`` does."""
    unknown = changes.keys() - _SET.keys()
    if unknown:
        raise TypeError(f"Block has no field {sorted(unknown)[0]!r}")
    out = _new(Block)
    for name, setter in _ALL:
        setter(out, changes[name] if name in changes else getattr(block, name))
    return out

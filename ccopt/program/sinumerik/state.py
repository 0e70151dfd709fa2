"""What a SINUMERIK program run keeps beyond the G-code core's state."""
from __future__ import annotations

from dataclasses import dataclass, field

from ccopt.program.gcode.state import GCodeState
from ccopt.program.model import SiemensModes
from ccopt.program.sinumerik.flow import Structure
from ccopt.program.sinumerik.values import Variables


@dataclass
class SinumerikRun:
    """One run: the core's :class:`GCodeState` (positions, plane, units,
    feed, blocks), the variables, the structures, and the SINUMERIK modes.

    ``tool``/``edge``: the active ``T`` and ``D`` (``None`` until programmed);
    ``offn``: ``OFFN`` added to the radius; ``motion``: ``"CIP"`` or ``"CT"``
    while one of them is the modal motion, else ``None`` (the core's G0-G3);
    ``sar_*``: the modal SAR settings (``G140``-``G143``, ``G340``/``G341``,
    ``DISR``, ``DISCL``, ``FAD``).
    """

    state: GCodeState
    structure: Structure
    variables: Variables = field(default_factory=Variables)
    modes: SiemensModes = field(default_factory=SiemensModes)
    tool: int | None = None
    edge: int | None = None
    tool_named: bool = False   # the tool was selected by name (T="...")
    offn: float = 0.0
    motion: str | None = None
    sar_direction: str = "G140"
    sar_infeed: str = "G340"
    disr: float | None = None
    discl: float | None = None
    discl_abs: float | None = None
    fad: float | None = None
    # FOR loops: FOR line -> (variable kind, key, end value)
    for_loops: dict = field(default_factory=dict)
    ignored: dict = field(default_factory=dict)   # code -> first line it was read and ignored
    pending_sar: object = None    # a SAR block waiting for its end point (blocks.py)
    pending_line: int = 0         # its 0-based line
    frame_shift: tuple = (0.0, 0.0, 0.0)   # the programmable frame (frames.py)
    frame_turn: float = 0.0                # its turn about Z, degrees
    pole: tuple | None = None     # the polar pole (u, v), work coordinates (polar.py)
    pole_plane: str = "XY"        # the plane it was set in
    ap: float | None = None       # the polar angle and radius kept from block to block
    rp: float | None = None
    rndm: float = 0.0             # RNDM: the modal rounding radius, 0 off (corners.py)
    frcm: float | None = None     # FRCM: the modal feed of chamfers and roundings
    corner: object = None         # a chamfer or rounding waiting for its next block
    not_inserted: dict = field(default_factory=dict)  # corners.NOT_INSERTED
    mcall: object = None          # the drilling cycle MCALL runs after each move (cycles.py)
    pending_angle: object = None  # a contour definition's first block and line (angle.py)
    offset: int = 0        # where the running text's lines start in state.lines
    loaded: dict = field(default_factory=dict)    # subprogram name -> (structure, offset)

"""Objects the verifier makes in bulk are the ones it makes one at a time: the
violations of :meth:`~ccopt.verify.certificate.Violation.many` are those of
``Violation(...)`` field for field, and :meth:`~ccopt.verify.segments.Packed.geoms`
gives the very objects :meth:`~ccopt.verify.segments.Packed.geom` gives, on
generated CAM programs pushed into the part (so they gouge and lose contact)."""
from __future__ import annotations

from dataclasses import fields, replace

import numpy as np
import pytest

from cam_programs import cam_program
from ccopt.cases import default_style
from ccopt.compensate import compensate
from ccopt.program import read_text
from ccopt.verify import verify
from ccopt.verify.certificate import Violation
from ccopt.verify.rows import SegmentRows


def pushed_certificate(seed: int):
    cp = cam_program(seed)
    prog = read_text(cp.pushed(0.3 * cp.radius), cp.file, cp.dialect, tool_table=cp.tool_table)
    return verify(compensate(prog, default_style(prog)[0]), prog)


@pytest.mark.parametrize("seed", range(0, 12, 3))
def test_many_violations_are_the_ones_made_one_by_one(seed):
    cert = pushed_certificate(seed)
    made = [*cert.violations, *cert.warnings]
    assert made
    columns = [[getattr(v, f.name) for v in made] for f in fields(Violation)]
    one_by_one = list(map(Violation, *columns))
    many = Violation.many(*columns)
    assert many == one_by_one
    assert [v.to_json() for v in many] == [v.to_json() for v in one_by_one]
    assert all(type(v) is Violation for v in many)
    with pytest.raises(ValueError):
        Violation.many(*columns[:-1])


@pytest.mark.parametrize("seed", range(1, 12, 3))
def test_geoms_are_the_objects_geom_makes(seed):
    ctx = pushed_certificate(seed).context
    for packed in (SegmentRows.of(ctx.toolpath).tool, ctx.contour.elements):
        idx = np.random.default_rng(seed).integers(0, len(packed), 2 * len(packed)).tolist()
        one, bulk = replace(packed, made={}), replace(packed, made={})
        got = bulk.geoms(np.asarray(idx))
        assert all(g is bulk.geom(i) for g, i in zip(got, idx))
        alone = [one.geom(i) for i in idx]
        assert got == alone
        # (a line's length is no part of its equality)
        assert [g.length for g in got] == [g.length for g in alone]

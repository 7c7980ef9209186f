"""Meshed (MAILx) decks in fracas_tools: BODIES/MODELS/BULK_BEHAV/DRV_DOF/DOF/GPV/
Vloc_Rloc/POSTPRO records read and rewritten byte for byte, LMGC90's contactor
numbering, against the mesh_* decks of ../shared/lmgc90_decks (written by LMGC90)."""

import glob
import sys
from pathlib import Path

import numpy as np
import pytest


from fracas_tools import Case, DatboxError, read_case  # noqa: E402
from fracas_tools import datbox  # noqa: E402
from fracas_tools.mailx import Element  # noqa: E402
from fracas_tools.outbox import read_dof_file, read_gpv, read_vloc_rloc  # noqa: E402
from fracas_tools.postpro_deck import PostPro, mecax_set_rows  # noqa: E402

DECKS = Path(__file__).resolve().parents[2] / ".." / "shared" / "lmgc90_decks"
needs_decks = pytest.mark.skipif(not DECKS.is_dir(), reason="../shared/lmgc90_decks not present")
OUT_FILES = sorted(glob.glob(str(DECKS / "*" / "OUTBOX" / "*.OUT.*"))) if DECKS.is_dir() else []
READERS = {"DOF": read_dof_file, "GPV": read_gpv, "Vloc_Rloc": read_vloc_rloc}


@needs_decks
@pytest.mark.parametrize("path", OUT_FILES, ids=["/".join(Path(p).parts[-3::2]) for p in OUT_FILES])
def test_outbox_files_rewritten_identically(path):
    """DOF.OUT.n, GPV.OUT.n, Vloc_Rloc.OUT.n of every deck (rigid and meshed, all
    contact types): read -> text() gives the file back byte for byte."""
    kind = Path(path).name.split(".")[0]
    assert READERS[kind](path).text() == Path(path).read_text()


def test_outbox_file_count():
    if DECKS.is_dir():
        assert len(OUT_FILES) == 11 * 6 + 5 * 3 - 3      # DOF, Vloc (none in mesh_plastic_bar), GPV


@needs_decks
@pytest.mark.parametrize("name", ["mesh_exploded_beam", "mesh_t3_pair_czm"])
def test_clalp_records_resolve_to_contactors(name):
    """Each CLALp record names a CLxxx point (LMGC90 number = point rank in the body)
    and an ALpxx polyline with a segment; at the written step, the candidate point
    (reference + DOF.OUT displacement) is the body's CLxxx point nearest to the
    contact point coo, closer than |gap| + 1e-4 m (coo is taken at the detection
    configuration, half a step earlier; other points are 3.5e-3 m or more away), and
    the normal n is the outward normal (-t_y, t_x) of the ALpxx segment walked from
    noda to nodb (the body on the right)."""
    case = read_case(DECKS / name)
    n_checked = 0
    for n in (1, 2, 3):
        v = read_vloc_rloc(DECKS / name / "OUTBOX" / f"Vloc_Rloc.OUT.{n}")
        dof = read_dof_file(DECKS / name / "OUTBOX" / f"DOF.OUT.{n}")
        for r in v.records:
            assert (r.inter, r.cdtac, r.antac) == ("CLALp", "CLxxx", "ALpxx")
            cd = case.body("MAILx", r.icdbdy)
            x = dof.get("MAILx", r.icdbdy).x
            dist = {k: np.linalg.norm(cd.tactor_point(k, x) - r.coor[:2])
                    for k, (c, _) in enumerate(cd.tactors(), start=1) if c.kind == "CLxxx"}
            assert min(dist, key=dist.get) == r.icdtac
            assert dist[r.icdtac] <= abs(r.gap) + 1e-4
            an = case.body("MAILx", r.ianbdy)
            poly, k = an.tactor(r.iantac)
            assert k is None and poly.kind == "ALpxx"
            a, b = poly.segments[r.anseg - 1]
            x = an.nodes + dof.get("MAILx", r.ianbdy).x
            t = (x[b - 1] - x[a - 1]) / np.linalg.norm(x[b - 1] - x[a - 1])
            assert np.dot([-t[1], t[0]], r.normal[:2]) > 0.999
            n_checked += 1
    assert n_checked == {"mesh_exploded_beam": 3 * 116, "mesh_t3_pair_czm": 3 * 8}[name]


@needs_decks
def test_exploded_beam_numbering():
    """Body 2 of mesh_exploded_beam: ALpxx 1, ALpxx 2, CLxxx 3 (+ line) in
    BODIES.DAT are LMGC90 contactors 1, 2, 3, 4 (case.md)."""
    b = read_case(DECKS / "mesh_exploded_beam").body("MAILx", 2)
    assert [c.kind for c in b.contactors] == ["ALpxx", "ALpxx", "CLxxx"]
    t = b.tactors()
    assert [(c.kind, k) for c, k in t] == [("ALpxx", None), ("ALpxx", None), ("CLxxx", 0), ("CLxxx", 1)]
    assert b.tactor_point(4) == pytest.approx([0.0025, 0.0075])      # node 1 -> 3 at apab 0.75
    with pytest.raises(ValueError, match="polyline"):
        b.tactor_point(1)


@needs_decks
def test_mesh_values_read():
    t3 = read_case(DECKS / "mesh_t3_pair_czm")
    assert [b.model for b in t3.bodies] == ["MAILx", "MAILx"]
    up = t3.body("MAILx", 2)
    assert up.n_nodes == 15 and len(up.elements) == 16
    assert up.elements[0] == Element("T3xxx", (1, 4, 2), "M2DT3", "STONE")
    assert len(up.tactors()) == 8 and up.contactors[0].points[1] == (4, 1, 0.75)
    assert t3.body("MAILx", 1).contactors[0].nodes == [3, 6, 9, 12, 15]
    drv = up.driven_by_node()
    assert [n for n, _ in drv] == [3, 6, 9, 12, 15]
    d2 = drv[0][1][1]
    assert (d2.dof, d2.ct, d2.rampi, d2.ramp) == (2, 0.01, 0.0, 5000.0)
    assert d2.value(1e-4) == pytest.approx(0.005)
    m = t3.materials["STONE"]
    assert (m.law, m.density, m.young, m.poisson) == ("ELAS", 2500.0, 1e10, 0.25)
    assert t3.models["M2DT3"].options == {"aniso": "iso__", "isext": "no___", "kine_": "small",
                                          "mstrg": "lump_", "mater": "elas_"}
    sets = t3.postpro.get("NEW MECAx SETS").mecax_sets()
    assert sets == [[(2, [3, 6, 9, 12, 15])], [(1, [3, 6, 9, 12, 15])], [(2, [4, 1, 7, 10, 13])]]
    bar = read_case(DECKS / "mesh_plastic_bar")
    st = bar.materials["STEEL"]
    assert (st.law, st.young, st.poisson, st.yield_stress, st.hardening) == ("ELAS_PLAS", 2e11, 0.3, 2e8, 2e9)
    assert st.option("isoh") == "linear"
    assert bar.models["M2DJ2"].element == "Q4P0x" and bar.models["M2DJ2"].options["form_"] == "UpdtL"
    assert bar.body("MAILx", 1).contactors == []
    drop = read_case(DECKS / "mesh_block_drop")
    blk = drop.body("MAILx", 1)
    assert blk.v0 == pytest.approx(np.tile([0.05, 0.0], (45, 1)))
    assert drop.body("RBDY2", 1).contactors[0].kind == "JONCx"
    assert drop.models["rigid"].element == "Rxx2D" and drop.models["rigid"].options == {}
    gpv = read_gpv(DECKS / "mesh_plastic_bar" / "OUTBOX" / "GPV.OUT.1")
    e1 = gpv.bodies[0].elements[0]
    assert (e1.kind, len(e1.rows), [len(r) for r in e1.rows[:3]]) == ("Q4xxx", 12, [4, 4, 6])
    vl = read_vloc_rloc(DECKS / "mesh_t3_pair_czm" / "OUTBOX" / "Vloc_Rloc.OUT.2")
    r = vl.records[0]
    assert (r.anseg, r.status, r.internal_names[3]) == (1, "Cstck", "beta")
    assert r.internal("beta") == pytest.approx(0.9292566) and r.rln == pytest.approx(-0.1172964e5)
    _, _, states = datbox.read_dof(DECKS / "mesh_block_drop" / "OUTBOX" / "DOF.OUT.1")
    x, v, nodes = states[("MAILx", 1)]
    assert nodes == list(range(1, 46)) and v[0] == pytest.approx([0.05, -0.981e-3])
    assert states[1][0] == pytest.approx([0.0, 0.0, 0.0])            # the RBDY2 ground


def mesh_case():
    """A case with every meshed record the writer knows: T3, Q4, T6, Q8 elements,
    CLxxx and ALpxx contactors, ELAS and ELAS_PLAS, models, driven nodes, initial
    state, a rigid body next to the meshes, post-processing sets."""
    c = Case(gravity=(0.0, -9.81))
    c.add_material("BLOCK", 2000.0, "ELAS", young=1e9, poisson=0.3)
    c.add_material("STEEL", 7800.0, "ELAS_PLAS", young=2e11, poisson=0.3, yield_stress=2e8, hardening=2e9)
    c.add_material("TDURx", 1000.0)
    c.add_model("M2DT3", "T3xxx")
    c.add_model("M2DQ8", "Q8xxx", kinematic="large", formulation="UpdtL", material="J2iso")
    c.add_model("M2DT6", "T6xxx")
    c.add_model("rigid", "Rxx2D")
    ground = c.add_jonc((0.5, -0.01), 1.0, 0.01, "TDURx", "WALLx")
    ground.fix()
    # two T3 on a unit square, nodes 1..4 counter-clockwise
    a = c.add_mesh_body([[0, 0], [1, 0], [1, 1], [0, 1]], [(1, 2, 3), (1, 3, 4)], "M2DT3", "BLOCK")
    a.add_candidates([(2, 1, 0.25), (2, 1, 0.75)], "BLEUx")
    a.add_polyline([4, 3, 2], "GLUEx")
    a.set_velocity(0.1, -0.2)
    a.groups["left"] = [1, 4]
    a.fix("left")
    a.impose_velocity([2], 2, ct=-0.01, rampi=0.0, ramp=100.0)
    # one Q8 and one T6 on a body of 10 nodes
    b = c.add_mesh_body([[0, 2], [2, 2], [2, 3], [0, 3], [1, 2], [2, 2.5], [1, 3], [0, 2.5],
                         [3, 2], [3, 3], [2.5, 2], [3, 2.5], [2.5, 2.5]])
    b.add_element("Q8xxx", (1, 2, 3, 4, 5, 6, 7, 8), "M2DQ8", "STEEL")
    b.add_element(Element("T6xxx", (2, 9, 10, 11, 12, 13), "M2DT6", "BLOCK"))
    b.add_candidates([(1, 2, 0.0), (2, 1, 1.0)], "BLEUx")
    b.impose_force([9, 10], 1, ct=5.0)
    b.x0[3] = (1e-3, -2e-3)
    c.add_law("gapc3", "GAP_SGR_CLB", fric=0.3)
    c.add_law("macz_", "MAC_CZM", dyfr=0.3, stfr=0.3, cn=1e11, ct=1e11, b=0.0, w=10.0)
    c.add_see("CLxxx", "BLEUx", "JONCx", "WALLx", "gapc3", 5e-3)       # body models from the contactors
    c.add_see("CLxxx", "BLEUx", "ALpxx", "GLUEx", "macz_", 1e-3, cdbdy="MAILx", anbdy="MAILx")
    c.postpro = PostPro()
    c.postpro.add("NEW MECAx SETS", rows=mecax_set_rows([[(1, [1, 4])], [(1, [2]), (2, [9, 10])]]))
    c.postpro.add("SOLVER INFORMATIONS")
    c.postpro.add("Dep EVOLUTION", step=10)
    c.run.set(time_step=1e-5, number_of_steps=10)
    return c


def _files(d):
    return {f.name: f.read_bytes() for f in sorted(Path(d, "DATBOX").iterdir())}


def test_mesh_case_round_trip(tmp_path):
    c = mesh_case()
    c.write(tmp_path / "a")
    r = read_case(tmp_path / "a")
    r.write(tmp_path / "b")
    a, b = _files(tmp_path / "a"), _files(tmp_path / "b")
    assert sorted(a) == ["BODIES.DAT", "BULK_BEHAV.DAT", "COMMAND.DAT", "DOF.INI", "DRV_DOF.DAT",
                         "GPV.INI", "MODELS.DAT", "POSTPRO.DAT", "TACT_BEHAV.DAT", "Vloc_Rloc.INI"]
    for name in a:
        assert a[name] == b[name], name
    # numbering within each model, as LMGC90
    assert [(x.model, x.number) for x in r.bodies] == [("RBDY2", 1), ("MAILx", 1), ("MAILx", 2)]
    m1, m2 = r.body("MAILx", 1), r.body("MAILx", 2)
    assert m1.v0 == pytest.approx(np.tile([0.1, -0.2], (4, 1)))
    assert m2.x0[3] == pytest.approx([1e-3, -2e-3]) and not np.any(m2.v0)
    assert [(d.node, d.dof, d.kind) for d in m1.driven] == [(1, 1, "vlocy"), (1, 2, "vlocy"),
                                                             (4, 1, "vlocy"), (4, 2, "vlocy"),
                                                             (2, 2, "vlocy")]
    assert m2.elements[0].kind == "Q8xxx" and m2.elements[1].nodes == (2, 9, 10, 11, 12, 13)
    assert [c.kind for c, _ in m1.tactors()] == ["CLxxx", "CLxxx", "ALpxx"]
    assert r.materials["STEEL"].hardening == 2e9
    assert r.models["M2DQ8"].options["form_"] == "UpdtL"
    assert r.postpro.get("NEW MECAx SETS").mecax_sets() == [[(1, [1, 4])], [(1, [2]), (2, [9, 10])]]
    assert r.postpro.get("Dep EVOLUTION").step == 10
    assert [(s.cdbdy, s.anbdy) for s in r.see_rules] == [("MAILx", "RBDY2"), ("MAILx", "MAILx")]
    text = (tmp_path / "a" / "DATBOX" / "BODIES.DAT").read_text().splitlines()
    assert " Q8xxx      1  nodes      1      2      3      4      5      6      7      8" in text
    assert "+CLxxx      1  color  BLEUx  noda=    2  nodb=    1  apab= 7.5000000E-01" in text
    assert "+ALpxx      2  color  GLUEx  noda=    3  nodb=    2" in text
    bulk = (tmp_path / "a" / "DATBOX" / "BULK_BEHAV.DAT").read_text().splitlines()
    assert " " * 40 + "SIG0= 2.0000000e+08  K___= 2.0000000e+09" in bulk
    assert " " * 40 + "isoh: linear       " in bulk


def test_mesh_checks():
    c = mesh_case()
    c.body("MAILx", 1).elements[0].material = "NOMAT"
    with pytest.raises(ValueError, match="NOMAT"):
        c.check()
    c = mesh_case()
    del c.models["M2DT6"]
    with pytest.raises(ValueError, match="M2DT6"):
        c.check()
    c = mesh_case()
    c.body("MAILx", 1).elements[0].material = "TDURx"
    with pytest.raises(ValueError, match="RIGID"):
        c.check()
    c = mesh_case()
    c.body("MAILx", 2).elements[1].material = "STEEL"
    with pytest.raises(ValueError, match="mater elas_' needs an ELAS"):
        c.check()
    c = mesh_case()
    c.body("MAILx", 2).elements[1].model = "M2DT3"
    with pytest.raises(ValueError, match="not for T6xxx"):
        c.check()
    c = mesh_case()
    c.body("MAILx", 1).fix([2])
    with pytest.raises(ValueError, match="driven twice"):
        c.check()
    with pytest.raises(ValueError, match="nodes"):
        Element("Q4xxx", (1, 2, 3), "M2DQ4", "BLOCK")
    with pytest.raises(ValueError, match="repeated"):
        Element("T3xxx", (1, 2, 1), "M2DT3", "BLOCK")
    with pytest.raises(ValueError, match="outside"):
        c.body("MAILx", 1).add_polyline([1, 7])
    with pytest.raises(ValueError, match="young"):
        c.add_material("BADxx", 1.0, "ELAS", poisson=0.3)
    with pytest.raises(ValueError, match="group"):
        c.body("MAILx", 2).fix("nowhere")


def test_mesh_reader_errors(tmp_path):
    d = mesh_case().write(tmp_path)
    lines = (d / "BODIES.DAT").read_text().splitlines()

    def broken(k, new):
        bad = list(lines)
        bad[k] = new
        p = tmp_path / "bad.dat"
        p.write_text("\n".join(bad) + "\n")
        with pytest.raises(DatboxError) as e:
            datbox.read_bodies(p)
        assert e.value.line == k + 1
        return str(e.value)

    k = next(i for i, l in enumerate(lines) if l.startswith(" T3xxx"))
    assert "element 'T4xxx'" in broken(k, lines[k].replace("T3xxx", "T4xxx"))
    assert "'model" in broken(k + 1, lines[k + 1].replace("behav", "bheav"))
    k = next(i for i, l in enumerate(lines) if l.startswith("+ALpxx"))
    assert "continuous" in broken(k, lines[k].replace("noda=    3", "noda=    1"))
    k = next(i for i, l in enumerate(lines) if l.startswith(" CLxxx"))
    assert "continuation line without" in broken(k, "+" + lines[k][1:].replace("CLxxx", "ALpxx"))
    k = next(i for i, l in enumerate(lines) if l.startswith(" NO2xx      2"))
    assert "numbered 1, 2" in broken(k, lines[k].replace("NO2xx      2", "NO2xx      7"))
    drv = (d / "DRV_DOF.DAT").read_text().replace(" vlocy      2  -1.0", " vlocy      3  -1.0")
    k = next(i for i, l in enumerate(drv.splitlines()) if l.startswith(" vlocy      2") and "-1.0" in l)
    bad = drv.splitlines()
    bad[k] = bad[k].replace(" vlocy      2", " vlocy      3")
    (tmp_path / "DRV_DOF.DAT").write_text("\n".join(bad) + "\n")
    with pytest.raises(DatboxError, match="dofs 1 and 2") as e:
        datbox.read_drv_dof(tmp_path / "DRV_DOF.DAT")
    assert e.value.line == k + 1


def test_plalp_record_layout(tmp_path):
    """PLALp (no LMGC90 fixture): the columns of Fracas's Fortran reader
    (modules/io/read_vloc_rloc.f90: vertex at 37, segment at 79, status at 93)."""
    from fracas_tools.outbox import ContactRecord, VlocRloc
    r = ContactRecord("PLALp", 3, "RBDY2", 12, "POLYG", 1, "gapc3", "MAILx", 2, "ALpxx", 4, "stick", 1,
                      cdver=5, anseg=7, rloc=np.array([1.0, -2.0, 0.0]), normal=np.zeros(3), coor=np.zeros(3))
    line = r.lines()[2]
    assert (line[8:13], line[36:41], line[43:48], line[78:83], line[92:97], line[97:103]) == \
        ("   12", "    5", "gapc3", "    7", "stick", "     1")
    v = VlocRloc(10, 1e-3, [r])
    p = tmp_path / "Vloc_Rloc.OUT.1"
    v.write(p)
    back = read_vloc_rloc(p)
    assert back.text() == v.text() and (back.records[0].cdver, back.records[0].anseg) == (5, 7)


def test_element_table_is_the_solvers(tmp_path):
    """fracas_tools.mailx.ELEMENTS (the one element table of the Python tools) against
    what the solver writes for one body of each kind: nodes per element, VTK cell type,
    Gauss-point states (/mesh of fracas.h5) and points printed per element (GPV.OUT)."""
    from fracas_run import run
    from fracas_tools.mailx import ELEMENTS
    from fracas_tools.results import Run
    c = Case(gravity=(0.0, -9.81))
    c.add_material("BLOCK", 2000.0, "ELAS", young=1e9, poisson=0.3)
    square = [[0, 0], [1, 0], [1, 1], [0, 1]]
    mids = [[0.5, 0], [1, 0.5], [0.5, 1], [0, 0.5]]
    shapes = {"T3xxx": (square[:3], (1, 2, 3)), "Q4xxx": (square, (1, 2, 3, 4)),
              "T6xxx": (square[:3] + [[0.5, 0], [0.5, 0.5], [0, 0.5]], (1, 2, 3, 4, 5, 6)),
              "Q8xxx": (square + mids, (1, 2, 3, 4, 5, 6, 7, 8))}
    for k, (kind, (nodes, conn)) in enumerate(shapes.items()):
        c.add_model(f"M2D{kind[:2]}", kind)
        b = c.add_mesh_body(np.array(nodes, dtype=float) + [2.0 * k, 0.0], [conn], f"M2D{kind[:2]}", "BLOCK")
        b.groups["base"] = [1, 2]
        b.fix("base")
    c.run.set(time_step=1e-4, number_of_steps=1, output_hdf5_every=1, output_dof_every=1, output_vtk_every=0)
    c.write(tmp_path / "elements")
    p = run("-q", tmp_path / "elements")
    assert p.returncode == 0, p.stderr
    with Run(tmp_path / "elements") as r:
        g = r.file["mesh"]
        nodes = np.diff(g["element_first_node"][()])
        gauss = np.diff(g["element_first_gauss_point"][()])
        vtk = g["element_vtk_type"][()]
    gpv = read_gpv(tmp_path / "elements" / "OUTBOX" / "GPV.OUT.1")
    printed = [len(e.rows) for b in gpv.bodies for e in b.elements]
    rows_per_point = [len(e.rows) // ELEMENTS[k].gauss_gpv for k, b, e in
                      zip(shapes, gpv.bodies, (b.elements[0] for b in gpv.bodies))]
    assert [(int(n), int(gp), int(t)) for n, gp, t in zip(nodes, gauss, vtk)] == \
        [(e.nodes, e.gauss, e.vtk) for e in (ELEMENTS[k] for k in shapes)]
    assert printed == [ELEMENTS[k].gauss_gpv * rows for k, rows in zip(shapes, rows_per_point)]
    assert rows_per_point == [2, 2, 2, 2]              # elastic: a stress and a strain line per point

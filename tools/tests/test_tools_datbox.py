"""fracas_tools.pre writers and fracas_tools.datbox readers: fixed columns, byte-identical
round trips, the LMGC90 decks of ../shared/lmgc90_decks, error locations."""

import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest


from fracas_tools import Case, DatboxError, read_case  # noqa: E402
from fracas_tools import datbox  # noqa: E402
from fracas_tools.fortran_io import d14, e14  # noqa: E402
from fracas_tools.pre import RunControl  # noqa: E402

# The LMGC90 decks: the path CMake was configured with (FRACAS_LMGC90_DECKS), else ../shared.
DECKS = Path(os.environ.get("FRACAS_LMGC90_DECKS",
                            Path(__file__).resolve().parents[2] / ".." / "shared" / "lmgc90_decks"))


def _deck_names():
    """Decks of rigid bodies; meshed (MAILx) decks are skipped until fracas_tools reads them."""
    if not DECKS.is_dir():
        return []
    out = []
    for p in sorted(DECKS.iterdir()):
        if not (p / "DATBOX").is_dir():
            continue
        meshed = "MAILx" in (p / "DATBOX" / "BODIES.DAT").read_text(errors="replace")
        out.append(pytest.param(p.name, marks=pytest.mark.skip(
            reason=f"{p.name}: meshed bodies (MAILx), not read by fracas_tools yet")) if meshed else p.name)
    return out


DECK_NAMES = _deck_names()
needs_decks = pytest.mark.skipif(not DECKS.is_dir(), reason=f"LMGC90 decks not found at {DECKS} "
                                                            "(set FRACAS_LMGC90_DECKS)")

DATBOX_FILES = ["BODIES.DAT", "BULK_BEHAV.DAT", "TACT_BEHAV.DAT", "DRV_DOF.DAT", "DOF.INI",
                "Vloc_Rloc.INI", "COMMAND.DAT"]


def rich_case():
    """A case using every record the writer knows."""
    c = Case(gravity=(0.0, -9.81))
    c.add_material("STONE", density=2600.0)
    c.add_material("TDURx", density=1000.0)
    c.add_material("STEEL", density=7800.0)
    d = c.add_disk((0.1, 0.2), 0.0123456789, "STONE", "BLEUx")
    d.set_velocity(0.3, -1e-7, 4.5)
    c.add_disk((0.3, 0.2), 0.02, "STONE", "BLEUx")               # at rest: not in DOF.INI
    sq = np.array([[0.0, 0.0], [0.1, 0.0], [0.1, 0.05], [0.0, 0.05]]) + [0.5, 0.5]
    p = c.add_polygon(sq, "STONE", "VERTx")
    p.rotate(math.pi / 7)
    c.add_polygon_cluster([[[0, 0], [0.2, 0], [0.2, 0.05], [0, 0.05]],
                           [[0, 0.05], [0.05, 0.05], [0.05, 0.2], [0, 0.2]]], "STONE", "VERTx")
    w = c.add_jonc((0.3, -0.01), 0.4, 0.01, "TDURx", "WALLx")
    w.fix()
    s = c.add_jonc((-0.01, 0.3), 0.3, 0.01, "TDURx", "WALLx", angle=-math.pi / 2)
    s.fix()
    drum = c.add_xksid((0.5, 0.5), 0.4, "STEEL", "DRUMx")
    drum.impose_velocity([1, 2])
    drum.impose_velocity(3, ct=1.0, amp=0.5, omega=2.0, phi=0.1, rampi=0.0, ramp=10.0)
    d.impose_evolution(1, "force", "fx.dat", data=[[0.0, 0.0], [0.5, 10.0], [1.0, -3.25]])
    d.impose_force(2, ct=-2.0)
    c.add_law("iqsdd", "IQS_CLB", fric=0.3)
    c.add_law("iqsds", "IQS_DS_CLB", dyfr=0.4, stfr=0.5)
    c.add_law("rstcw", "RST_CLB", rstn=0.3, rstt=0.0, fric=0.5)
    c.add_law("gapsg", "GAP_SGR_CLB", fric=0.2)
    c.add_law("macz1", "IQS_MAC_CZM", dyfr=0.73, stfr=0.73, cn=1e10, ct=1e11, b=0.0, w=40.0)
    c.add_see("DISKx", "BLEUx", "DISKx", "BLEUx", "iqsdd", 1e-3)
    c.add_see("DISKx", "BLEUx", "JONCx", "WALLx", "rstcw", 1e-3, global_alert=0.05)
    c.add_see("DISKx", "BLEUx", "xKSID", "DRUMx", "iqsds", 2e-3)
    c.add_see("POLYG", "VERTx", "POLYG", "VERTx", "macz1", 1e-2)
    c.add_see("POLYG", "VERTx", "JONCx", "WALLx", "gapsg", 1e-2)
    c.add_see("DISKx", "BLEUx", "POLYG", "VERTx", "iqsdd", 1e-3)
    c.run.set(time_step=1e-4, number_of_steps=1500, theta=0.55, detection_frequency=2,
              nlgs_check="QM/16", nlgs_tolerance=1.666e-4, nlgs_relaxation=0.9,
              nlgs_sweeps_per_check=20, nlgs_max_checks=100, nlgs_order="shuffled", nlgs_seed=7,
              output_dof_every=100, output_vtk_every=10, output_hdf5_every=5, progress_every=50)
    return c


def read_bytes(d):
    return {f.name: f.read_bytes() for f in sorted(Path(d, "DATBOX").iterdir())}


def test_write_read_write_is_byte_identical(tmp_path):
    c = rich_case()
    c.write(tmp_path / "a")
    c2 = read_case(tmp_path / "a")
    c2.write(tmp_path / "b")
    a, b = read_bytes(tmp_path / "a"), read_bytes(tmp_path / "b")
    assert sorted(a) == sorted(DATBOX_FILES + ["fx.dat"])
    for name in a:
        assert a[name] == b[name], name
    # and a third generation, through the CLI-free API again
    read_case(tmp_path / "b").write(tmp_path / "c")
    assert read_bytes(tmp_path / "c") == b


def test_read_back_values(tmp_path):
    c = rich_case()
    c.write(tmp_path)
    r = read_case(tmp_path)
    assert len(r.bodies) == len(c.bodies) == 7
    assert [sorted(k) for k in r.body_kinds()] == [sorted(k) for k in c.body_kinds()]
    b0 = r.bodies[0]
    assert b0.contactors[0].radius == pytest.approx(0.0123456789, rel=1e-7)
    assert b0.v0 == pytest.approx([0.3, -1e-7, 4.5], rel=1e-7)
    assert r.bodies[2].x0[2] == pytest.approx(math.pi / 7, rel=1e-7)
    assert r.bodies[5].x0[2] == pytest.approx(-math.pi / 2, rel=1e-7)
    assert len(r.bodies[3].contactors) == 2
    assert r.gravity == pytest.approx([0.0, -9.81, 0.0])
    assert r.materials["STEEL"].density == 7800.0
    assert r.laws["macz1"].params == pytest.approx(
        {"dyfr": 0.73, "stfr": 0.73, "cn": 1e10, "ct": 1e11, "b": 0.0, "w": 40.0})
    assert r.laws["rstcw"].layout == [["rstn", "rstt"], ["fric"]]
    assert r.see_rules[1].global_alert == pytest.approx(0.05)
    drv = r.bodies[6].driven
    assert [(d.kind, d.dof) for d in drv] == [("vlocy", 1), ("vlocy", 2), ("vlocy", 3)]
    assert drv[2].value(0.05) == pytest.approx((1.0 + 0.5 * math.cos(0.2)) * 0.5, rel=1e-7)
    evo = r.bodies[0].driven[0]
    assert evo.evolution == "fx.dat"
    assert evo.value([0.25, 0.75, 2.0]) == pytest.approx([5.0, 3.375, -29.75])
    assert r.run.values == c.run.values
    # polygon stored relative to its centroid, node at the centroid
    p = r.bodies[2]
    assert p.coor[:2] == pytest.approx([0.55, 0.525])
    assert p.contactors[0].vertices.mean(axis=0) == pytest.approx([0.0, 0.0], abs=1e-12)


def test_fixed_columns(tmp_path):
    c = rich_case()
    d = c.write(tmp_path)
    bodies = (d / "BODIES.DAT").read_text().splitlines()
    disk = next(l for l in bodies if l.startswith(" DISKx"))
    assert disk[1:6] == "DISKx" and disk[22:27] == "BLEUx" and disk[29:34] == "byrd="
    assert float(disk[34:48]) == pytest.approx(0.0123456789, rel=1e-7)
    node = next(l for l in bodies if l.startswith(" NO3xx"))
    assert len(node) == 92 and node[29:34] == "coo1=" and node[50:55] == "coo2=" and node[71:76] == "coo3="
    plain = next(l for l in bodies if l.startswith(" PLAIN"))
    assert plain[22:27] == "STONE" and plain[34:48].strip() and plain[55:69].strip()
    poly = next(l for l in bodies if l.startswith(" POLYG"))
    assert int(poly[39:46]) == 4
    jonc = next(l for l in bodies if l.startswith(" JONCx"))
    assert float(jonc[34:48]) == 0.4 and float(jonc[55:69]) == 0.01
    dof = (d / "DOF.INI").read_text().splitlines()
    assert "$steps      0                time= 0.0000000D+00" in dof
    num = [l for l in dof if l.startswith(" RBDY2")]
    assert [int(l[8:15]) for l in num] == [1, 3, 6]        # only bodies with a non-zero state
    drv = (d / "DRV_DOF.DAT").read_text().splitlines()
    v3 = [l for l in drv if l.startswith(" vlocy      3")][-1]       # the drum's
    vals = [float(v3[c0 - 1:c0 + 13]) for c0 in (15, 30, 45, 60, 75, 90)]
    assert vals == [1.0, 0.5, 2.0, 0.1, 0.0, 10.0]
    assert " force      1 evolution fx.dat" in drv
    tact = (d / "TACT_BEHAV.DAT").read_text().splitlines()
    mac = tact.index(" macz1  IQS_MAC_CZM                     dyfr= 7.3000000e-01  stfr= 7.3000000e-01")
    assert tact[mac + 1] == " " * 40 + "cn  = 1.0000000e+10  ct  = 1.0000000e+11"
    assert tact[mac + 2] == " " * 40 + "b   = 0.0000000e+00  w   = 4.0000000e+01"
    see = [l for l in tact if l.startswith(" RBDY2  DISKx  BLEUx  rstcw")][0]
    assert float(see[54:68]) == 1e-3
    assert float([l for l in tact if l.startswith("+")][0][54:68]) == 0.05
    bulk = (d / "BULK_BEHAV.DAT").read_text().splitlines()
    grav = [l for l in bulk if "grv1=" in l][0]
    assert [float(grav[c0 - 1:c0 + 13]) for c0 in (25, 46, 67)] == [0.0, -9.81, 0.0]


def test_large_body_numbers_in_drv_dof(tmp_path):
    c = Case()
    c.add_material("STONE", 1.0)
    b1 = c.add_disk((0, 0), 0.1, "STONE").fix()
    b2 = c.add_disk((1, 0), 0.1, "STONE").fix()
    b1.number, b2.number = 99999, 100000          # as in a deck of 100000 bodies
    text = c.drv_dof_text().splitlines()
    assert " RBDY2  99999" in text and " RBDY2   100000" in text   # LMGC90 reads I7 at 9-15
    p = tmp_path / "DRV_DOF.DAT"
    p.write_text("\n".join(text) + "\n")
    assert sorted(datbox.read_drv_dof(p)) == [99999, 100000]


def test_number_formats():
    assert e14(0.0) == " 0.0000000e+00"
    assert e14(-1.8070036e-18, "E") == "-1.8070036E-18"
    assert d14(0.0) == " 0.0000000D+00"
    assert d14(0.25) == " 0.2500000D+00"
    assert d14(-1234.5678) == "-0.1234568D+04"
    assert d14(1e-3) == " 0.1000000D-02"
    from fracas_tools.fortran_io import parse_real
    for text, x in ((" 0.1234567-100", 0.1234567e-100), ("1.5E-3", 1.5e-3), ("2.5d0", 2.5),
                    (".5", 0.5), ("7", 7.0), (" -0.1000000D+01", -1.0), ("", 0.0)):
        assert parse_real(text, 1, max(14, len(text))) == pytest.approx(x, rel=1e-15)
    for bad in ("nan", "inf", "1e999", "1.2.3", "abc"):
        with pytest.raises(DatboxError):
            parse_real(bad, 1, 14)


def test_mass_properties():
    c = Case()
    c.add_material("STONE", 2000.0)
    d = c.add_disk((0, 0), 0.1, "STONE")
    assert d.radii() == pytest.approx((0.1, 0.1 / math.sqrt(2)))
    sq = c.add_polygon([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]], "STONE")
    assert sq.radii() == pytest.approx((math.sqrt(1 / math.pi), math.sqrt(1 / 6)))
    assert sq.mass(2000.0) == pytest.approx(2000.0)
    # pylmgc90's JONCx convention (values of the disks_box deck)
    j = c.add_jonc((0, 0), 0.32, 0.01, "STONE")
    assert j.radii() == pytest.approx((6.4609338e-02, 2.2907757e-01), rel=1e-7)
    assert c.add_xksid((0, 0), 0.11, "STONE").radii() == (0.0, 0.0)
    # cluster: parallel-axis terms
    cl = c.add_polygon_cluster([[[0, 0], [1, 0], [1, 1], [0, 1]], [[1, 0], [2, 0], [2, 1], [1, 1]]], "STONE")
    assert cl.coor[:2] == pytest.approx([1.0, 0.5])
    assert cl.radii()[1] == pytest.approx(math.sqrt((4 + 1) / 12))


def test_validation_errors():
    c = Case()
    c.add_material("STONE", 1.0)
    with pytest.raises(ValueError, match="counter-clockwise"):
        c.add_polygon([[0, 0], [0, 1], [1, 1], [1, 0]], "STONE")
    with pytest.raises(ValueError, match="convex"):
        c.add_polygon([[0, 0], [2, 0], [1, 0.2], [2, 2], [0, 2]], "STONE")
    with pytest.raises(ValueError, match="5 characters"):
        c.add_material("SAND", 1.0)
    with pytest.raises(ValueError, match="exactly"):
        c.add_law("iqsxx", "IQS_CLB", mu=0.3)
    with pytest.raises(ValueError, match="missing"):
        c.add_law("macxx", "IQS_MAC_CZM", dyfr=0.1, stfr=0.1)
    with pytest.raises(ValueError, match="theta"):
        RunControl(theta=0.3)
    with pytest.raises(ValueError, match="nlgs_relaxation"):
        RunControl(nlgs_relaxation=2.0)
    with pytest.raises(ValueError, match="unknown"):
        RunControl(time_stp=1e-3)
    with pytest.raises(ValueError, match="one of"):
        RunControl(nlgs_check="L2")
    rc = RunControl(final_time=1.0)
    rc.set(number_of_steps=10)
    assert "final_time" not in rc.values
    with pytest.raises(ValueError, match="time_step"):
        rc.check()
    c.add_disk((0, 0), 0.1, "STONE")
    c.add_see("DISKx", "BLEUx", "DISKx", "BLEUx", "nolaw", 1e-3)
    with pytest.raises(ValueError, match="nolaw"):
        c.write("/nonexistent/never")
    c2 = Case()
    c2.add_disk((0, 0), 0.1, "ROCKS")
    with pytest.raises(ValueError, match="ROCKS"):
        c2.check()


def test_warnings_and_no_command(tmp_path):
    c = Case()
    c.add_material("STONE", 1.0)
    c.add_disk((0, 0), 0.1, "STONE", "REDxx")
    c.add_law("iqsdd", "IQS_CLB", fric=0.3)
    with pytest.warns(UserWarning) as rec:
        c.write(tmp_path)
    msgs = " ".join(str(w.message) for w in rec)
    assert "DISKx/REDxx" in msgs and "iqsdd" in msgs and "COMMAND.DAT not written" in msgs
    assert not (tmp_path / "DATBOX" / "COMMAND.DAT").exists()


def test_reader_errors_name_file_line_column(tmp_path):
    c = rich_case()
    d = c.write(tmp_path)
    lines = (d / "BODIES.DAT").read_text().splitlines()
    k = next(i for i, l in enumerate(lines) if l.startswith(" DISKx"))
    lines[k] = lines[k][:34] + " 1.2.3e-02    " + lines[k][48:]
    (d / "BODIES.DAT").write_text("\n".join(lines) + "\n")
    with pytest.raises(DatboxError) as e:
        datbox.read_bodies(d / "BODIES.DAT")
    assert e.value.line == k + 1 and e.value.col == 35 and "byrd" in str(e.value)
    assert str(e.value).startswith(f"{d / 'BODIES.DAT'}:{k + 1}:35:")
    # clockwise polygon: refused by the writer, and by the reader
    c2 = Case()
    c2.add_material("STONE", 1.0)
    p = c2.add_polygon([[0, 0], [1, 0], [1, 1], [0, 1]], "STONE")
    text = c2.bodies_text().splitlines()
    p.contactors[0].vertices = p.contactors[0].vertices[::-1].copy()
    with pytest.raises(ValueError, match="counter-clockwise"):
        c2.check()
    k = next(i for i, l in enumerate(text) if l.startswith(" POLYG"))
    text[k + 1:k + 5] = text[k + 1:k + 5][::-1]
    (tmp_path / "cw.dat").write_text("\n".join(text) + "\n")
    with pytest.raises(DatboxError, match="counter-clockwise") as e:
        datbox.read_bodies(tmp_path / "cw.dat")
    assert e.value.line == k + 1
    # unknown contactor
    bad = tmp_path / "bad.dat"
    bad.write_text("$bdyty\n RBDY2      1\n$blmty\n PLAIN      1  behav  STONE  avrd= 0.0000000E+00"
                   "  gyrd= 0.0000000E+00\n$nodty\n NO3xx      1                coo1= 0.0000000E+00"
                   "  coo2= 0.0000000E+00  coo3= 0.0000000E+00\n$tacty\n SPHER      1  color  BLEUx"
                   "  byrd= 1.0000000E+00\n$$$$$$\n")
    with pytest.raises(DatboxError, match="unknown contactor type") as e:
        datbox.read_bodies(bad)
    assert e.value.line == 8
    # COMMAND.DAT
    cmd = tmp_path / "COMMAND.DAT"
    cmd.write_text("# run\nTime_Step = 1.0D-3   ! dt\nfinal_time 1.0\nnlgs_check qm/16\n")
    rc = datbox.read_command(cmd)
    assert rc.values == {"time_step": 1e-3, "final_time": 1.0, "nlgs_check": "QM/16"}
    cmd.write_text("time_step 1e-3\nnumber_of_steps 10\nfinal_time 1.0\n")
    with pytest.raises(DatboxError, match="not both") as e:
        datbox.read_command(cmd)
    assert e.value.line == 3
    cmd.write_text("time_step 1e-3\n  nlgs_sweps 10\n")
    with pytest.raises(DatboxError, match="unknown COMMAND.DAT keyword") as e:
        datbox.read_command(cmd)
    assert (e.value.line, e.value.col) == (2, 3)
    # a law whose line layout contradicts LMGC90's
    tb = tmp_path / "TACT_BEHAV.DAT"
    tb.write_text("$behav \n rstcw  RST_CLB                         rstn= 3.0000000e-01\n")
    with pytest.raises(DatboxError, match="RST_CLB"):
        datbox.read_tact_behav(tb)


def test_unknown_law_round_trip(tmp_path):
    tb = tmp_path / "TACT_BEHAV.DAT"
    text = ("\n$behav \n elrep  ELASTIC_REPELL_CLB              stif= 1.0000000e+06  fric= 3.0000000e-01\n"
            "      \n      \n")
    tb.write_text(text)
    laws, rules = datbox.read_tact_behav(tb)
    assert laws["elrep"].params == {"stif": 1e6, "fric": 0.3}
    c = Case()
    c.laws = laws
    assert c.tact_behav_text() == text


# --------------------------------------------------------------------------------------
# the LMGC90 decks
# --------------------------------------------------------------------------------------

def _data_lines(path):
    """The lines LMGC90 reads: not blank, no '!' or '#' in column 1."""
    return [l for l in Path(path).read_text().splitlines() if l.strip() and not l.startswith(("!", "#"))]


def _echo_tactor_ranks(path):
    """Per body of an echo BODIES.OUT, the contactor numbers of its non-'+' lines."""
    out = []
    for line in Path(path).read_text().splitlines():
        if line.startswith("$bdyty"):
            out.append([])
        elif line[1:6] in ("CLxxx", "ALpxx", "DISKx", "JONCx", "POLYG", "xKSID") and line[0] == " ":
            out[-1].append(int(line[6:13]))
    return out


@needs_decks
@pytest.mark.parametrize("name", DECK_NAMES)
def test_lmgc90_deck_rewritten_identically(name, tmp_path):
    case = read_case(DECKS / name)
    with pytest.warns(UserWarning, match="COMMAND.DAT"):
        case.write(tmp_path, command=False)
    src = DECKS / name / "DATBOX"
    written = sorted(p.name for p in (tmp_path / "DATBOX").iterdir())
    assert written == sorted(p.name for p in src.iterdir() if p.suffix in (".DAT", ".INI")
                             or p.name in {d.evolution for b in case.bodies for d in b.driven})
    for f in ("BODIES.DAT", "TACT_BEHAV.DAT", "DRV_DOF.DAT", "DOF.INI", "Vloc_Rloc.INI",
              "GPV.INI", "POSTPRO.DAT"):
        if (src / f).exists():
            assert (tmp_path / "DATBOX" / f).read_bytes() == (src / f).read_bytes(), f
    # BULK_BEHAV.DAT, MODELS.DAT: our own comment header, the records column for column
    for f in ("BULK_BEHAV.DAT", "MODELS.DAT"):
        if (src / f).exists():
            assert _data_lines(tmp_path / "DATBOX" / f) == _data_lines(src / f), f
    for b in case.bodies:
        for d in b.driven:
            if d.evolution:
                assert (tmp_path / "DATBOX" / d.evolution).read_bytes() == (src / d.evolution).read_bytes()


@needs_decks
@pytest.mark.parametrize("name", DECK_NAMES)
def test_lmgc90_deck_numbers_match_echo(name):
    """Our reading of DATBOX equals LMGC90's own echo OUTBOX/*.OUT (D exponents, 7 digits)."""
    case = read_case(DECKS / name)
    echo = datbox.read_bodies(DECKS / name / "OUTBOX" / "BODIES.OUT")
    assert len(echo) == len(case.bodies)
    echo_ranks = _echo_tactor_ranks(DECKS / name / "OUTBOX" / "BODIES.OUT")
    # (LMGC90 echoes the bodies model by model: MAILx before RBDY2)
    echo_by_key = {(b.model, b.number): (b, r) for b, r in zip(echo, echo_ranks)}
    assert sorted(echo_by_key) == sorted((b.model, b.number) for b in case.bodies)
    for a in case.bodies:
        b, ranks = echo_by_key[(a.model, a.number)]
        if a.model == "MAILx":
            assert a.nodes == pytest.approx(b.nodes, rel=1e-6, abs=1e-12)
            assert a.elements == b.elements
            # LMGC90's echo numbers every contactor it built: each CLxxx point
            # and each ALpxx polyline, 1.. within the body; our numbering agrees
            assert ranks == list(range(1, len(a.tactors()) + 1))
            assert len(b.tactors()) == len(a.tactors())
            for (ca, ka), (cb, kb) in zip(a.tactors(), b.tactors()):
                assert (ca.kind, ca.color) == (cb.kind, cb.color)
                if ka is None:
                    assert ca.nodes == cb.nodes
                else:
                    assert ca.points[ka] == pytest.approx(cb.points[kb])
            continue
        assert a.material == b.material
        assert a.coor == pytest.approx(b.coor, rel=1e-6, abs=1e-12)
        assert (a.avrd, a.gyrd) == pytest.approx((b.avrd, b.gyrd), rel=1e-6)
        assert [c.kind for c in a.contactors] == [c.kind for c in b.contactors]
        for ca, cb in zip(a.contactors, b.contactors):
            if ca.kind == "POLYG":
                # LMGC90 re-centres the vertices it read: differences ~1e-10 m
                assert ca.vertices == pytest.approx(cb.vertices, rel=1e-6, abs=1e-9)
    drv = datbox.read_drv_dof(DECKS / name / "OUTBOX" / "DRV_DOF.OUT", DECKS / name / "OUTBOX")
    assert sum(len(lst) for lst in drv.values()) == sum(len(b.driven) for b in case.bodies)
    for key, lst in drv.items():
        mine = case.body(*key).driven if isinstance(key, tuple) else case.body("RBDY2", key).driven
        assert [(d.node, d.kind, d.dof, d.evolution) for d in mine] == \
            [(d.node, d.kind, d.dof, d.evolution) for d in lst]
        for dm, de in zip(mine, lst):
            assert dm.value(np.linspace(0, 2, 9)) == pytest.approx(de.value(np.linspace(0, 2, 9)))
    g, mats = datbox.read_bulk_behav(DECKS / name / "OUTBOX" / "BULK_BEHAV.OUT")
    assert g == pytest.approx(case.gravity)
    assert {k: m.density for k, m in mats.items()} == {k: m.density for k, m in case.materials.items()}
    for k, m in mats.items():
        for p in ("young", "poisson", "yield_stress", "hardening"):
            assert getattr(m, p) == pytest.approx(getattr(case.materials[k], p), rel=1e-6), (k, p)
    if case.models:
        models = datbox.read_models(DECKS / name / "OUTBOX" / "MODELS.OUT")
        for k, m in models.items():      # LMGC90 echoes the deformable models only
            assert (m.element, m.physics, m.options) == \
                (case.models[k].element, case.models[k].physics, case.models[k].options)
    laws, rules = datbox.read_tact_behav(DECKS / name / "OUTBOX" / "TACT_BEHAV.OUT")
    assert list(laws) == list(case.laws)
    for k, law in laws.items():
        assert law.law == case.laws[k].law
        assert law.params == pytest.approx(case.laws[k].params)
    # (LMGC90 echoes the see rules in its own order)
    echo = sorted((r.cdtac, r.cdcol, r.behav, r.antac, r.ancol, r.alert) for r in rules)
    mine = sorted((r.cdtac, r.cdcol, r.behav, r.antac, r.ancol, r.alert) for r in case.see_rules)
    assert [e[:5] for e in echo] == [m[:5] for m in mine]
    assert [e[5] for e in echo] == pytest.approx([m[5] for m in mine], rel=1e-6)


@needs_decks
@pytest.mark.parametrize("name", DECK_NAMES)
def test_lmgc90_mass_properties_recomputed(name):
    """avrd/gyrd computed from the contactors agree with pylmgc90's (0 for xKSID)."""
    for b in read_case(DECKS / name).bodies:
        if b.model == "MAILx":
            continue
        av, gy = b.avrd, b.gyrd
        b.avrd = b.gyrd = None
        av2, gy2 = b.radii()
        if av == 0.0:
            assert (av2, gy2) == (0.0, 0.0)
        else:
            assert (av2, gy2) == pytest.approx((av, gy), rel=2e-7)


@needs_decks
def test_lmgc90_dof_out_files():
    step, time, states = datbox.read_dof(DECKS / "disks_box" / "OUTBOX" / "DOF.OUT.2")
    assert step == 250 and time == pytest.approx(0.25)
    assert len(states) == 154
    x, v = states[1]
    assert x == pytest.approx([0.3996011e-01, -0.1595946e-18, -0.2552629e01])
    ini = read_case(DECKS / "disks_box")
    assert ini.bodies[152].x0[2] == pytest.approx(-math.pi / 2, rel=1e-7)
    assert ini.bodies[0].v0 == pytest.approx([2.7027822e-01, 0.0, 4.4864945e+00])

"""Run control from the settings an LMGC90 user knows.

An LMGC90 deck has no COMMAND.DAT: the time step, theta, the number of steps and the
NLGS settings live in the Python script that drives pylmgc90.chipy (``dt``, ``theta``,
``nb_steps``, ``norm``, ``tol``, ``relax``, ``gs_it1``, ``gs_it2``, ``freq_detect``,
``freq_write``, ``freq_display`` in LMGC90's examples). :func:`run_control` turns those
settings into a :class:`fracas_tools.pre.RunControl`; :func:`read_run_script` reads
them from such a script (top-level assignments of plain values only: the script is
parsed, never run); ``fracas-tools command`` writes the COMMAND.DAT.

LMGC90 name       COMMAND.DAT keyword        meaning
dt                time_step                  time step
theta             theta                      theta of the Moreau-Jean scheme
nb_steps          number_of_steps            steps to run
freq_detect       detection_frequency        rough detection every n steps
norm              nlgs_check                 'Quad ', 'Maxm ', 'QM/16' (blanks ignored)
tol               nlgs_tolerance             NLGS tolerance
relax             nlgs_relaxation            relaxation
gs_it1            nlgs_sweeps_per_check      Gauss-Seidel sweeps between two checks
gs_it2            nlgs_max_checks            checks before giving up
freq_write        output_dof_every           DOF.OUT.n / Vloc_Rloc.OUT.n every n steps
freq_display      output_vtk_every           DISPLAY files every n steps

LMGC90's solver type (``stype``: 'Stored_Delassus_Loops', 'Exchange_Local_Global')
is not a setting of Fracas: its one NLGS gives the same iterates.
"""
import ast
from pathlib import Path

from .pre import RunControl

#: LMGC90 script variable -> COMMAND.DAT keyword
LMGC90_NAMES = {
    "dt": "time_step",
    "theta": "theta",
    "nb_steps": "number_of_steps",
    "freq_detect": "detection_frequency",
    "norm": "nlgs_check",
    "tol": "nlgs_tolerance",
    "relax": "nlgs_relaxation",
    "gs_it1": "nlgs_sweeps_per_check",
    "gs_it2": "nlgs_max_checks",
    "freq_write": "output_dof_every",
    "freq_display": "output_vtk_every",
    "mhyp": "plane",
}

#: LMGC90's modelling hypothesis (SetDimension(2, mhyp)) -> COMMAND.DAT 'plane'
MHYP_PLANE = {1: "strain", 2: "stress", 3: "axisym"}


def run_control(**lmgc90):
    """RunControl from LMGC90 settings (names as in LMGC90_NAMES; None values are
    left out). dt and nb_steps are required. Cohesive damage follows LMGC90's update
    (cohesive_damage lmgc90), so that the run reproduces LMGC90's outputs."""
    rc = RunControl(cohesive_damage="lmgc90")
    for name, value in lmgc90.items():
        if value is None:
            continue
        if name not in LMGC90_NAMES:
            raise ValueError(f"unknown LMGC90 setting {name!r}; known: {', '.join(LMGC90_NAMES)}")
        if name == "norm":
            value = str(value).strip()
        if name == "mhyp":
            if value not in MHYP_PLANE:
                raise ValueError(f"SetDimension's modelling hypothesis {value!r} is not one Fracas runs "
                                 "(1 plane strain, 2 plane stress, 3 axisymmetry)")
            value = MHYP_PLANE[value]
        rc.set(**{LMGC90_NAMES[name]: value})
    rc.check()
    return rc


#: chipy calls that set up physics Fracas does not have (the deck does not record it).
SCRIPT_PHYSICS = {
    "SetPeriodicCondition": "periodic boundaries",
    "mp_solver_SolveThermoProblem": "thermal solver (multiphysics)",
    "RBDY2_GetThermalValue": "thermal solver (multiphysics)",
    "RBDY2_UpdateWSvsT": "thermal solver (multiphysics)",
    "mp_solver_SolveElectro1G": "electrical solver (multiphysics)",
    "RBDY2_GetElectricalPotential": "electrical solver (multiphysics)",
    "ReadMpBehaviours": "multiphysics behaviours (MP_DEM.DAT)",
    "RBDY2_MP_LoadBehaviours": "multiphysics behaviours (MP_DEM.DAT)",
    "DISKx_SetXdilation": "growing radii (dilation)", "DISKx_SetVdilation": "growing radii (dilation)",
    "POLYG_SetXdilation": "growing radii (dilation)", "POLYG_SetVdilation": "growing radii (dilation)",
    "xKSID_SetXdilation": "growing radii (dilation)", "xKSID_SetVdilation": "growing radii (dilation)",
    "PLPLx_ShrinkPolygFaces": "shrunk polygon faces",
    "RBDY2_SetBodiesInvisible": "freezing (hiding) bodies",
    "RBDY2_SetSourcePoint": "injecting bodies (source point)",
    "RBDY2_MembraneBiaxialLoading": "biaxial membrane loading", "RBDY2_BiaxialLoading": "biaxial loading",
    "mecaMAILx_SetCoroAllBodies": "corotational meshed bodies",
    "mecaMAILx_SetRigidAllBodies": "meshed bodies made rigid", "mecaMAILx_BuildRigidBodies": "meshed bodies made rigid",
    "setInternalArray": "contact internal variables set by the script (e.g. pre-damage)",
    "tact_behav_SetCZMwithInitialFriction": "cohesive laws with initial friction",
    "tact_behav_SetPressureParameters": "pressure in opening cracks",
    "Integrator_InitQS": "quasi-static integrator", "Integrator_InitCrankNickolson": "Crank-Nicolson integrator",
    "NewtonRaphson_ComputeTimeStep": "adaptive time step (Newton-Raphson driver)",
    "CLALp_SetNonSymmetricDetection": "non-symmetric CLALp detection",
    "CLALp_SetNonSymetricDetection": "non-symmetric CLALp detection",
    "SetDomainBoundary": "bodies removed outside a domain", "RBDY2_SetYminBoundary": "bodies removed below a height",
    "mecaMAILx_SetScalarFieldByNode": "nodal fields set by the script (e.g. temperature)",
    "mecaMAILx_ComputeRayleighDamping": "Rayleigh damping",
    "bulk_behav_SetGravity": "gravity set by the script",
    "PTPT2_LoadNetwork": "PTPT2 point-to-point network",
}
#: chipy calls of thermal meshed bodies (any therMAILx_ call)
SCRIPT_PHYSICS_PREFIX = {"therMAILx_": "thermal meshed bodies (therMAILx)"}
#: positional arguments of chipy.ExSolver
EXSOLVER_ARGS = ("stype", "norm", "tol", "relax", "gs_it1", "gs_it2")


class ScriptReading(dict):
    """The LMGC90 settings read from a script (a dict: name -> value), with
    ``not_understood`` (what the script says about the run that was not read) and
    ``physics`` (calls that set up physics Fracas does not have), each a list of
    strings naming the script line."""

    def __init__(self):
        super().__init__()
        self.not_understood = []
        self.physics = []


def _value(node, env):
    """Value of a constant expression of the script (numbers, strings, the names
    assigned before, + - * / // % **, int, float, round, abs, min, max); raises
    ValueError otherwise."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float, str)):
        return node.value
    if isinstance(node, ast.Name) and node.id in env:
        return env[node.id]
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        v = _value(node.operand, env)
        return -v if isinstance(node.op, ast.USub) else v
    if isinstance(node, ast.BinOp):
        a, b = _value(node.left, env), _value(node.right, env)
        ops = {ast.Add: lambda: a + b, ast.Sub: lambda: a - b, ast.Mult: lambda: a * b, ast.Div: lambda: a / b,
               ast.FloorDiv: lambda: a // b, ast.Mod: lambda: a % b, ast.Pow: lambda: a ** b}
        if type(node.op) in ops:
            return ops[type(node.op)]()
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and not node.keywords and \
            node.func.id in ("int", "float", "round", "abs", "min", "max"):
        return {"int": int, "float": float, "round": round, "abs": abs, "min": min, "max": max}[node.func.id](
            *[_value(x, env) for x in node.args])
    raise ValueError(ast.dump(node)[:60])


def _call_name(call):
    f = call.func
    return f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else ""


def _time_test(test):
    """test is 'TimeEvolution_GetTime() < x' (or <=)."""
    return isinstance(test, ast.Compare) and len(test.ops) == 1 and isinstance(test.ops[0], (ast.Lt, ast.LtE)) \
        and isinstance(test.left, ast.Call) and _call_name(test.left) == "TimeEvolution_GetTime"


def _calls(node, name):
    return [c for c in ast.walk(node) if isinstance(c, ast.Call) and _call_name(c) == name]


def read_run_script(path):
    """The LMGC90 settings of a pylmgc90 script, parsed, never run: top-level
    assignments of constant expressions (``dt = 1.e-3``, ``gs_it1, gs_it2 = 50, 400``,
    ``nb_steps = int(t_final / dt)``), the arguments of ``ExSolver`` (which win over
    variables of the same meaning), ``TimeEvolution_SetTimeStep``, ``Integrator_InitTheta``,
    ``WriteOut``, ``SetDimension``'s modelling hypothesis (``mhyp``), the length of the
    ``range`` of the time loop (the loop that calls
    ``IncrementStep``: it is what LMGC90 runs) or the steps of dt a loop
    ``while TimeEvolution_GetTime() < t_final`` makes, ``nlgs_SetWithQuickScramble`` (key
    ``quickscramble``). Returns a :class:`ScriptReading`; what could not be read and the
    physics the script sets up outside the deck are listed in it, never guessed."""
    src = Path(path).read_text()
    tree = ast.parse(src, filename=str(path))
    out, env = ScriptReading(), {}

    def where(node):
        return f"{path}:{node.lineno}: {ast.get_source_segment(src, node) or ''}".strip()

    def take(name, node, value_node):
        try:
            env[name] = _value(value_node, env)
            if name in LMGC90_NAMES:
                out[name] = env[name]
        except (ValueError, ZeroDivisionError, TypeError):
            env.pop(name, None)
            if name in LMGC90_NAMES:
                out.not_understood.append(f"{where(node)}: the value of {name} is not a constant expression")

    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1:
            t, v = node.targets[0], node.value
            if isinstance(t, ast.Name):
                take(t.id, node, v)
            elif isinstance(t, ast.Tuple) and isinstance(v, ast.Tuple) and len(t.elts) == len(v.elts):
                for tt, vv in zip(t.elts, v.elts):
                    if isinstance(tt, ast.Name):
                        take(tt.id, node, vv)

    def from_call(fname, key, arg=0):
        calls = _calls(tree, fname)
        vals = set()
        for c in calls:
            if len(c.args) > arg:
                try:
                    vals.add(_value(c.args[arg], env))
                except (ValueError, ZeroDivisionError, TypeError):
                    out.not_understood.append(f"{where(c)}: argument {arg + 1} ({key}) not read")
        if len(vals) == 1:
            v = vals.pop()
            if key in out and out[key] != v:
                out.not_understood.append(f"{where(calls[0])}: {key} = {v!r} here, {out[key]!r} assigned: "
                                          "the call's value is used")
            out[key] = v
        elif len(vals) > 1:
            out.not_understood.append(f"{path}: {fname} is called with several values of {key} "
                                      f"({sorted(vals, key=str)}): {key} not read")
            out.pop(key, None)

    from_call("TimeEvolution_SetTimeStep", "dt")
    from_call("Integrator_InitTheta", "theta")
    from_call("WriteOut", "freq_write")
    from_call("SetDimension", "mhyp", 1)
    for k, name in enumerate(EXSOLVER_ARGS):
        if name != "stype":
            from_call("ExSolver", name, k)
            from_call("nlgs_ExSolver", name, k)
    if _calls(tree, "nlgs_SetWithQuickScramble") or _calls(tree, "SetWithQuickScramble"):
        out["quickscramble"] = True

    # The time loop: a for loop over a range that calls IncrementStep.
    loops = [n for n in ast.walk(tree) if isinstance(n, (ast.For, ast.While)) and _calls(n, "IncrementStep")]
    for loop in loops:
        it = loop.iter if isinstance(loop, ast.For) else None
        if isinstance(it, ast.Call) and _call_name(it) == "range" and not it.keywords:
            try:
                n = len(range(*[int(_value(a, env)) for a in it.args]))
            except (ValueError, ZeroDivisionError, TypeError):
                out.not_understood.append(f"{where(it)}: the length of the time loop is not read")
                continue
            if "nb_steps" in out and out["nb_steps"] != n:
                out.not_understood.append(f"{where(it)}: the time loop runs {n} steps, nb_steps = "
                                          f"{out['nb_steps']}: {n} is used")
            out["nb_steps"] = n
        elif isinstance(loop, ast.While) and _time_test(loop.test) and "dt" in out:
            # while TimeEvolution_GetTime() < t_final: LMGC90 adds dt to the time
            # each step (floating point), from 0 (a fresh deck)
            try:
                t_final = _value(loop.test.comparators[0], env)
            except (ValueError, ZeroDivisionError, TypeError):
                out.not_understood.append(f"{where(loop.test)}: the final time of the time loop is not read")
                continue
            t, n, dt = 0.0, 0, float(out["dt"])
            while (t < t_final if isinstance(loop.test.ops[0], ast.Lt) else t <= t_final) and n < 10**9:
                t, n = t + dt, n + 1
            out["nb_steps"] = n
            if _calls(tree, "NewtonRaphson_ComputeTimeStep"):
                out.not_understood.append(f"{where(loop.test)}: {n} steps of dt = {dt:g} up to {t_final:g}, "
                                          "but the script may change the time step (NewtonRaphson_ComputeTimeStep)")
        else:
            head = loop.iter if isinstance(loop, ast.For) else loop.test
            out.not_understood.append(f"{where(head)}: the number of steps of this time loop is not read")
    if len(loops) > 1:
        out.not_understood.append(f"{path}: {len(loops)} time loops (calls of IncrementStep in {len(loops)} loops)")

    for c in ast.walk(tree):
        if isinstance(c, ast.Call):
            name = _call_name(c)
            what = SCRIPT_PHYSICS.get(name) or next((w for p, w in SCRIPT_PHYSICS_PREFIX.items()
                                                     if name.startswith(p)), None)
            if what:
                out.physics.append(f"{what} ({name}, {path}:{c.lineno})")
    return out


#: Commands of LMGC90's old command language (its own DATBOX/COMMAND.DAT); fracas
#: reads its run control from DATBOX/FRACAS.DAT when COMMAND.DAT is in that language.
LMGC90_COMMANDS = ("READ BODIES", "READ BEHAVIOURS", "COMPUTE MASS", "COMPUTE FREE VELOCITY", "UPDATE DOF",
                   "WRITE LAST")


def is_lmgc90_command_file(path):
    """PATH exists and is in LMGC90's old command language (as fracas detects it)."""
    p = Path(path)
    if not p.is_file():
        return False
    lines = p.read_text(errors="replace").splitlines()[:200]
    return any(ln.lstrip().startswith(c) for ln in lines for c in LMGC90_COMMANDS)


def default_command_path(case_dir):
    """DATBOX/COMMAND.DAT, or DATBOX/FRACAS.DAT when COMMAND.DAT is LMGC90's own."""
    dat = Path(case_dir) / "DATBOX"
    return dat / ("FRACAS.DAT" if is_lmgc90_command_file(dat / "COMMAND.DAT") else "COMMAND.DAT")


def write_command(case_dir, rc, overwrite=False, path=None, notes=()):
    """Write rc as CASE_DIR/DATBOX/COMMAND.DAT (FRACAS.DAT beside LMGC90's own
    COMMAND.DAT; or path); refuse to replace an
    existing file unless overwrite. Returns the path."""
    out = Path(path) if path else default_command_path(case_dir)
    if out.exists() and not overwrite:
        raise ValueError(f"{out} exists (pass --overwrite to replace it)")
    if not out.parent.is_dir():
        raise FileNotFoundError(f"{out.parent} is not a folder (is {case_dir} a case directory?)")
    lines = rc.lines()
    lines.insert(1, "! written by fracas-tools command from LMGC90 settings")
    for k, n in enumerate(notes):
        lines.insert(2 + k, "! " + n.replace("\n", " "))
    out.write_text("\n".join(lines) + "\n")
    return out

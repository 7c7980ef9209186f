"""Loading a script's helper that is not part of the package (a test case's gen.py, a
sibling case's parameters, the hydride campaign's modules) by its file path: the one way
the repository's scripts reach files outside fracas_tools, without putting folders on
sys.path (where one folder's gen.py would shadow another's).

    from fracas_tools.scripts import load
    gen = load(Path(__file__).resolve().parents[1] / "czm_mode_I" / "gen.py")

fracas_tools itself is found on PYTHONPATH (bin/fracas-python and ctest set it to tools/),
or installed (cmake --install, pip install ./tools).
"""

import importlib.util
import sys
from pathlib import Path

__all__ = ["load"]


def load(path, name=None):
    """The module of the Python file at path, executed once per process (kept in
    sys.modules under name, default a name unique to the path, so that loading it twice
    gives the same module)."""
    path = Path(path).resolve()
    key = name or "_fracas_script_" + "_".join(path.with_suffix("").parts[-3:]).replace("-", "_")
    if key in sys.modules:
        return sys.modules[key]
    spec = importlib.util.spec_from_file_location(key, path)
    if spec is None:
        raise ImportError(f"cannot load {path}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[key] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[key]
        raise
    return module

"""fracas_tools: pre- and post-processing for Fracas (2D NSCD, LMGC90-compatible decks).

    fracas_tools.pre         Case/Scene: build a DATBOX deck and COMMAND.DAT
    fracas_tools.datbox      read DATBOX files back into Case objects
    fracas_tools.mailx       meshed (MAILx) bodies, CLxxx/ALpxx contactors, MODELS.DAT models
    fracas_tools.outbox      DOF / GPV / Vloc_Rloc files (.INI and .OUT.n), read and written
    fracas_tools.postpro_deck  POSTPRO.DAT commands (node sets of meshes)
    fracas_tools.mesh        gmsh meshes (.geo, .msh, API) -> MAILx bodies, exploded meshes
    fracas_tools.generators  seeded generators: disk deposits, polygons, walls, masonry, arches
    fracas_tools.post        read OUTBOX/fracas.h5, micro-mechanics, plots, report
    fracas_tools.synthetic   a synthetic fracas.h5 with the documented layout (tests, demos)
    fracas_tools.results     the one fracas.h5 reader (Run, Results)
    fracas_tools.cohesive    the cohesive laws (Law, the solver's mirrored) and exploded decks' helpers
    fracas_tools.checks      Checker (one line per checked quantity); valtools, polytools,
                             fractools, valmesh, czm_closed_forms: the check scripts' helpers
    fracas_tools.scripts     load(path): a script's helper outside the package

Run ``python3 -m fracas_tools --help`` for the command line.
"""

from .fortran_io import DatboxError
from .pre import (Body, Case, ContactLaw, Disk, DrivenDof, Jonc, Material, Polygon, RunControl,
                  Scene, SeeRule, Xksid)
from .mailx import Candidates, Element, MeshBody, Model, Polyline
from .datbox import read_case

__version__ = "0.1.0"

__all__ = ["Case", "Scene", "Body", "Disk", "Xksid", "Jonc", "Polygon", "Material", "ContactLaw",
           "SeeRule", "DrivenDof", "RunControl", "DatboxError", "read_case", "MeshBody", "Element",
           "Candidates", "Polyline", "Model", "__version__"]

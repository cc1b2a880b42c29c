"""The sliding pendulum (SP) of the DAP_BC manual (Example B.1) as in-file texts, and a helper
that writes a model folder for a test."""

from __future__ import annotations

from pathlib import Path

SP = {
    "inBodies.m": """function inBodies
    include_global

    B1 = Body_struct;
    B1.m = 5.0;
    B1.J = 4.0;
    B1.r = [1.0; 0.2];

    B2 = Body_struct;
    B2.m = 2.0;
    B2.J = 0.2;
    B2.r = [1.25; -0.233];
    B2.p = pi/6;

    Bodies = [B1; B2];
""",
    "inPoints.m": """function inPoints
    include_global

P1 = Point_struct;
P1.Bindex = 0;
P1.sPlocal = [0; 0.2];

P2 = Point_struct;
P2.Bindex = 1;
P2.sPlocal = [0; 0];

P3 = Point_struct;
P3.Bindex = 2;
P3.sPlocal = [0; 0.5];

Points = [P1; P2; P3];
""",
    "inUvectors.m": """function inUvectors
    include_global

U1 = Unit_struct;
U1.Bindex = 0;
U1.ulocal = [1.0; 0];

U2 = Unit_struct;
U2.Bindex = 1;
U2.ulocal = [1.0; 0];

Uvectors = [U1; U2];
""",
    "inForces.m": """function inForces
    include_global

F1 = Force_struct;
F1.type = 'ptp'; % default
F1.iPindex = 2;
F1.jPindex = 1;
F1.k = 20;
F1.L0 = 0.6;

F2 = Force_struct;
F2.type = 'weight';

Forces = [F1; F2];
""",
    "inJoints.m": """function inJoints
    include_global

J1 = Joint_struct;
J1.type = 'tran';
J1.iPindex = 2;
J1.jPindex = 1;
J1.iUindex = 2;
J1.jUindex = 1;

J2 = Joint_struct;
J2.type = 'rev';
J2.iPindex = 2;
J2.jPindex = 3;

Joints = [J1; J2];
""",
    "inFuncs.m": """function inFuncs
    include_global
    Functs = [];
""",
    "inAnimate.m": """function inAnimate
    include_global
    Points_anim = [];
    Bodies(1).shape = 'rect';
    Bodies(1).W = 0.4;
Bodies(1).H = 0.2;
Bodies(2).shape = 'line';
Bodies(2).H = 1.0;
xmin = -0.5; xmax = 2.0;
ymin = -1.0; ymax = 0.5;
""",
}


def write_folder(root: Path, files: dict[str, str | None], base: dict[str, str] = SP) -> Path:
    """Write ``base`` with ``files`` laid over it (None removes a file) into ``root/model``."""
    folder = root / "model"
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in {**base, **files}.items():
        if text is not None:
            (folder / name).write_text(text)
    return folder

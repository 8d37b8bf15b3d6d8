#!/usr/bin/env python3
"""Reference values of task-space (operational-space) dynamics, for tests/data/rtb_task_space.json.

For every Robotics Toolbox 1.5.0 DH model with dynamics (the descriptions of
scripts/rtb_models.py), at 5 seeded states (q, qd), Khatib's task-space dynamics of the tool:

    Lambda = (J D^-1 J^T)^-1,  Jbar^T = Lambda J D^-1,  p = Jbar^T g,  mu = Jbar^T C qd - Lambda Jd qd

from the Toolbox's own inertia(q), jacob0(q), jacob0_dot(q, qd), coriolis(q, qd) and gravload(q)
(no friction, no motor inertia). The task is the tool's twist [v; w] (`tool`, 6 rows) for arms
of six or more joints, and its position (`tool_position`, the 3 linear rows) for smaller ones.

Checks (the script fails loudly if one does not hold):
  - jacob0_dot(q, qd) agrees with central finite differences of jacob0 along qd;
  - for six joints, Lambda, mu and p equal the Toolbox's own inertia_x, coriolis_x @ (J qd) and
    gravload_x given the inverse of the geometric Jacobian (Ji = J^-1, Jd = jacob0_dot);
  - for every arm, under the torques J^T F for a seeded F, the Toolbox's forward dynamics
    accel(q, qd, tau) gives the task acceleration J qdd + Jd qd = Lambda^-1 (F - mu - p).
Models whose gravload disagrees with their potential energy (see rtb_models.py: P8), whose D is
singular without motor inertia, or whose arm cannot hold the task anywhere, are left out. Samples where J D^-1 J^T has a condition number above 1e6 (near a singularity) are
redrawn.

    pip install roboticstoolbox-python==1.5.0
    python3 scripts/rtb_task_space.py     # writes tests/data/rtb_task_space.json
"""
import json
import sys
import warnings
from pathlib import Path

import numpy as np
import roboticstoolbox as rtb

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rtb_models import NAMES, close, description, gravity_torques, has_dynamics  # noqa: E402

warnings.filterwarnings("ignore")
OUT = Path(__file__).resolve().parent.parent / "tests" / "data" / "rtb_task_space.json"
SAMPLES = 5
SEED = 20261202


def main():
    rng = np.random.default_rng(SEED)
    out = {
        "generator": {"script": "scripts/rtb_task_space.py", "roboticstoolbox": rtb.__version__,
                      "seed": SEED},
        "conventions": {
            "toml": "the dhgen description of the Toolbox model (scripts/rtb_models.py)",
            "task": "tool: the tool's twist [v; w], world axes (6 rows of jacob0); "
                    "tool_position: its 3 linear rows",
            "Lambda": "(J D^-1 J^T)^-1, rows", "mu": "Jbar^T C qd - Lambda Jd qd",
            "p": "Jbar^T g", "JbarT": "Lambda J D^-1, rows",
            "friction_included": False, "motor_inertia_included": False,
        },
        "robots": [],
    }
    worst = 0.0
    for name in NAMES:
        r = getattr(rtb.models.DH, name)()
        if not has_dynamics(r) or any(L.isflip for L in r.links):
            continue
        nf = r.nofriction(True, True)
        for L in nf.links:
            L.Jm = 0.0
        task = "tool" if r.n >= 6 else "tool_position"
        rows = 6 if task == "tool" else 3
        robot = {"name": name, "dof": r.n, "task": task, "toml": description(r, name.lower()),
                 "samples": []}
        skip, why = False, ""
        while len(robot["samples"]) < SAMPLES:
            q = np.array([rng.uniform(*L.qlim) if L.qlim is not None and np.all(np.isfinite(L.qlim))
                          else rng.uniform(-1.5, 1.5) for L in r.links])
            qd = rng.uniform(-1, 1, r.n)
            g = nf.gravload(q)
            if np.abs(g - gravity_torques(r, q)).max() > 1e-6 * max(1.0, np.abs(g).max()):
                skip, why = True, "gravload"  # the Toolbox's gravload is wrong for this model (P8)
                break
            D = nf.inertia(q)
            J = r.jacob0(q)[:rows]
            Jd = r.jacob0_dot(q, qd)[:rows]
            h = 1e-6
            Jd_fd = (r.jacob0(q + h * qd) - r.jacob0(q - h * qd))[:rows] / (2 * h)
            close(Jd, Jd_fd, 1e-6, f"{name}: jacob0_dot vs finite differences")
            Cqd = nf.coriolis(q, qd) @ qd
            if np.linalg.cond(D) > 1e12:
                skip, why = True, "D singular"  # D singular without motor inertia (a massless wrist)
                break
            Di = np.linalg.inv(D)
            mobility = J @ Di @ J.T
            if np.linalg.cond(mobility) > 1e6:
                if r.n < rows or rows == 3 and np.linalg.matrix_rank(J) < 3:
                    skip, why = True, "rank"  # never of full rank: no task of this kind
                    break
                continue
            Lam = np.linalg.inv(mobility)
            Lam = (Lam + Lam.T) / 2
            JbarT = Lam @ J @ Di
            p = JbarT @ g
            mu = JbarT @ Cqd - Lam @ Jd @ qd
            if task == "tool" and r.n == 6:
                Ji = np.linalg.inv(J)
                close(Lam, nf.inertia_x(q, Ji=Ji), 1e-8, f"{name}: inertia_x")
                cx = nf.coriolis_x(q, qd, J=J, Ji=Ji, Jd=Jd) @ (J @ qd)
                close(mu, cx, 1e-8, f"{name}: coriolis_x")
                close(p, nf.gravload_x(q, Ji=Ji), 1e-8, f"{name}: gravload_x")
            F = rng.uniform(-20, 20, rows)
            qdd = nf.accel(q, qd, J.T @ F)
            a = J @ qdd + Jd @ qd
            worst = max(worst, close(a, mobility @ (F - mu - p), 1e-7,
                                     f"{name}: accel vs the task-space equation"))
            robot["samples"].append({"q": q.tolist(), "qd": qd.tolist(), "Lambda": Lam.tolist(),
                                     "mu": mu.tolist(), "p": p.tolist(),
                                     "JbarT": JbarT.tolist()})
        if skip:
            print(f"{name}: left out ({why})")
            continue
        out["robots"].append(robot)
        print(f"{name}: {r.n} joints, {task}")
    OUT.write_text(json.dumps(out) + "\n")
    print(f"worst task-space equation residual {worst:.2e}; wrote {OUT}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Reference derivatives of the dynamics from Pinocchio, for tests/integration/derivatives.rs.

Builds each robot of tests/data/{puma560,panda}.json (the DH tables with inertial parameters
that Robotics Toolbox and Pinocchio were checked on) as a Pinocchio model, checks it against the
file's own inverse dynamics, and writes tests/data/derivatives_<robot>.json with, for the file's
first 10 samples (q, qd, qdd):
  tau = rnea(q, qd, qdd),
  dtau_dq, dtau_dqd = computeRNEADerivatives(q, qd, qdd),
  ddq_dq, ddq_dqd, minv = computeABADerivatives(q, qd, tau),
matrices as lists of rows, entry [k][m] = d(out_k)/d(in_m).

    pip install pin        # Pinocchio 3.x
    python3 scripts/pinocchio_derivatives.py
    python3 scripts/pinocchio_derivatives.py --save-models DIR   # DIR/<robot>.bin, for the
                                                # C++ benchmarks (scripts/pinocchio_bench.sh,
                                                # scripts/cppadcg_counts.sh)
"""
import json
import sys
from pathlib import Path

import numpy as np
import pinocchio as pin

DATA = Path(__file__).resolve().parent.parent / "tests" / "data"


def rot(axis, angle):
    c, s = np.cos(angle), np.sin(angle)
    if axis == "x":
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def se3(r=np.eye(3), p=np.zeros(3)):
    return pin.SE3(np.array(r, dtype=float), np.array(p, dtype=float))


def tz(d):
    return se3(p=[0, 0, d])


def tx(a):
    return se3(p=[a, 0, 0])


def rz(t):
    return se3(r=rot("z", t))


def rx(t):
    return se3(r=rot("x", t))


def model_of(robot):
    """The Pinocchio model of a DH table: joint i about (along) the z axis of its DH frame."""
    model = pin.Model()
    model.gravity.linear = np.array(robot["gravity"], dtype=float)
    links = robot["links"]
    standard = robot["convention"] == "standard"
    parent = 0
    # The constant transform from joint i's frame to the next joint's frame (standard), and
    # from link frame i to the body's inertia frame.
    previous_tail = se3()
    for i, link in enumerate(links):
        revolute = link["joint"] == "revolute"
        off = link["offset"]
        if standard:
            # A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha); joint i about z_{i-1}.
            placement = previous_tail
            # Link frame i in joint i's (moving) frame.
            if revolute:
                tail = rz(off) * tz(link["d"]) * tx(link["a"]) * rx(link["alpha"])
            else:
                tail = rz(link["theta"]) * tz(off) * tx(link["a"]) * rx(link["alpha"])
            body_frame = tail
            previous_tail = tail
        else:
            # A_i = Rx(alpha) Tx(a) Rz(theta) Tz(d); joint i about z_i, link frame i = joint frame.
            if revolute:
                placement = previous_tail * rx(link["alpha"]) * tx(link["a"]) * rz(off) * tz(link["d"])
            else:
                placement = previous_tail * rx(link["alpha"]) * tx(link["a"]) * rz(link["theta"]) * tz(off)
            body_frame = se3()
            previous_tail = se3()
        joint = pin.JointModelRZ() if revolute else pin.JointModelPZ()
        parent = model.addJoint(parent, joint, placement, f"joint{i + 1}")
        ixx, iyy, izz, ixy, iyz, ixz = link["inertia"]
        inertia_com = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)
        local = pin.Inertia(link["mass"], np.array(link["com"], dtype=float), inertia_com)
        model.appendBodyToJoint(parent, body_frame.act(local), pin.SE3.Identity())
    return model


def rows(m):
    return [list(map(float, r)) for r in np.asarray(m)]


def main():
    if "--save-models" in sys.argv:
        out = Path(sys.argv[sys.argv.index("--save-models") + 1])
        for name in ["puma560", "panda"]:
            robot = json.loads((DATA / f"{name}.json").read_text())
            model_of(robot).saveToBinary(str(out / f"{name}.bin"))
        return
    for name in ["puma560", "panda"]:
        robot = json.loads((DATA / f"{name}.json").read_text())
        model = model_of(robot)
        data = model.createData()
        out = {
            "source": f"Pinocchio {pin.__version__} (scripts/pinocchio_derivatives.py), from tests/data/{name}.json",
            "conventions": {
                "matrices": "lists of rows; entry [k][m] = d(out_k)/d(in_m)",
                "tau": "rnea(q, qd, qdd) with the file's gravity; no friction, no motor inertia",
                "dtau_dq, dtau_dqd": "computeRNEADerivatives(q, qd, qdd)",
                "ddq_dq, ddq_dqd, minv": "computeABADerivatives(q, qd, tau) at tau = rnea(q, qd, qdd)",
                "kinetic_energy": "computeKineticEnergy(q, qd): 1/2 qd' D qd",
                "potential_energy": "computePotentialEnergy(q): -sum_k m_k gravity . c_k, centres "
                "of mass in the base frame",
            },
            "samples": [],
        }
        worst = 0.0
        for sample in robot["samples"][:10]:
            q, v, a = (np.array(sample[k], dtype=float) for k in ("q", "qd", "qdd"))
            tau = pin.rnea(model, data, q, v, a).copy()
            worst = max(worst, float(np.max(np.abs(tau - np.array(sample["tau"])))))
            dq, dv, _ = pin.computeRNEADerivatives(model, data, q, v, a)
            dq, dv = dq.copy(), dv.copy()
            pin.computeABADerivatives(model, data, q, v, tau)
            minv = np.triu(data.Minv) + np.triu(data.Minv, 1).T
            kinetic = float(pin.computeKineticEnergy(model, data, q, v))
            potential = float(pin.computePotentialEnergy(model, data, q))
            out["samples"].append(
                {
                    "q": q.tolist(),
                    "qd": v.tolist(),
                    "qdd": a.tolist(),
                    "tau": tau.tolist(),
                    "dtau_dq": rows(dq),
                    "dtau_dqd": rows(dv),
                    "ddq_dq": rows(data.ddq_dq),
                    "ddq_dqd": rows(data.ddq_dv),
                    "minv": rows(minv),
                    "kinetic_energy": kinetic,
                    "potential_energy": potential,
                }
            )
        if worst > 1e-9:
            sys.exit(f"{name}: the Pinocchio model disagrees with the file's tau by {worst:.1e}")
        print(f"{name}: Pinocchio tau = file tau to {worst:.1e}")
        (DATA / f"derivatives_{name}.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()

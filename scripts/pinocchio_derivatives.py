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


def model_of(robot, with_tool=False):
    """The Pinocchio model of a DH table: joint i about (along) the z axis of its DH frame; with
    `with_tool`, also the frame "tool" (a model of its own, so that the other quantities are
    computed as without it, bit for bit)."""
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
    if with_tool:
        # The tool frame: link frame n (the last joint's frame, then its DH tail in a standard
        # table), then the file's tool transform.
        tool = se3()
        if robot.get("tool") is not None:
            t = np.array(robot["tool"], dtype=float)
            tool = se3(t[:3, :3], t[:3, 3])
        model.addFrame(pin.Frame("tool", parent, previous_tail * tool, pin.FrameType.OP_FRAME))
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
        tooled = model_of(robot, with_tool=True)
        tooled_data = tooled.createData()
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
                "held_qdd, held_force": "forwardDynamics(q, qd, tau, J, gamma): the accelerations "
                "and the constraint force lambda_c (M qdd + b = tau + J^T lambda_c) with the tool "
                "frame held still, J its Jacobian in world axes [v; w] (getFrameJacobian, "
                "LOCAL_WORLD_ALIGNED; equal to the file's J0) and gamma = Jd qd its classical "
                "acceleration at qdd = 0",
            },
            "samples": [],
        }
        worst = worst_j = worst_held = 0.0
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
            # The tool held still: its Jacobian (checked against the file's J0) and drift.
            m, d = tooled, tooled_data
            tool = m.getFrameId("tool")
            world = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
            J = pin.computeFrameJacobian(m, d, q, tool, world).copy()
            worst_j = max(worst_j, float(np.max(np.abs(J - np.array(sample["J0"])))))
            pin.forwardKinematics(m, d, q, v, np.zeros(m.nv))
            gamma = pin.getFrameClassicalAcceleration(m, d, tool, world).vector.copy()
            held = pin.forwardDynamics(m, d, q, v, tau, J, gamma).copy()
            force = d.lambda_c.copy()
            worst_held = max(worst_held, float(np.max(np.abs(J @ held + gamma))))
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
                    "held_qdd": held.tolist(),
                    "held_force": force.tolist(),
                }
            )
        if worst > 1e-9:
            sys.exit(f"{name}: the Pinocchio model disagrees with the file's tau by {worst:.1e}")
        if worst_j > 1e-12:
            sys.exit(f"{name}: the tool frame's Jacobian disagrees with the file's J0 by {worst_j:.1e}")
        if worst_held > 1e-9:
            sys.exit(f"{name}: the held tool accelerates by {worst_held:.1e}")
        print(f"{name}: Pinocchio tau = file tau to {worst:.1e}, tool Jacobian = J0 to "
              f"{worst_j:.1e}, held tool's acceleration {worst_held:.1e}")
        (DATA / f"derivatives_{name}.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()

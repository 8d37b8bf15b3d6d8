#!/usr/bin/env python3
"""Reference velocity kinematics of the tool from Pinocchio, for tests/data/pinocchio_kinematics.json.

Builds the PUMA 560 and the Panda of tests/data/{puma560,panda}.json with their tool frame (the
models of scripts/pinocchio_derivatives.py) and writes, at the files' first 10 samples (q, qd):
  Jb     computeFrameJacobian(q, tool, LOCAL): the body Jacobian, rows [v; w] in tool axes;
  dvb_dq getFrameVelocityDerivatives(tool, LOCAL) after computeForwardKinematicsDerivatives(q,
         qd, 0): d(Jb qd)/dq, the body velocity's derivative;
  dv_dq  the same for the tool's velocity in world axes, v = R vb, w = R wb (dhgen's
         `tool_velocity_partial`): R dvb/dq_k + w_k x (R vb), both halves, w_k the world axis of
         joint k (0 for a prismatic joint), since dR/dq_k = [w_k x] R;
  H0     the kinematic Hessian, H0[k] = dJ0/dq_k (6 x n): column i of H0[k] is column k of dv_dq
         at qd = e_i (joint i alone moving at unit speed);
  Jb_dot_qd getFrameJacobianTimeVariation(tool, LOCAL) @ qd after
         computeJointJacobiansTimeVariation(q, qd): the rate of the body velocity at zero joint
         acceleration (dhgen's `body_jdot_qdot`).
Pinocchio's LOCAL_WORLD_ALIGNED velocity derivative is not used: it is not the partial derivative
of the world-axes velocity at fixed qd (it differs from the finite differences below by 1.4 on
the PUMA 560).

Checks (the script fails loudly if one does not hold): Jb against R^T J0 of the file; dv_dq and
every column of H0 against central finite differences of J0(q) qd; Jb_dot_qd against
getFrameAcceleration(tool, LOCAL) at zero joint acceleration and against central finite
differences of Jb(q + t qd) qd in t.

    pip install pin        # Pinocchio 3.x or 4.x
    python3 scripts/pinocchio_kinematics.py
"""
import json
import sys
from pathlib import Path

import numpy as np
import pinocchio as pin

sys.path.insert(0, str(Path(__file__).resolve().parent))
from pinocchio_derivatives import DATA, model_of, rows  # noqa: E402

LOCAL = pin.ReferenceFrame.LOCAL
WORLD = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def fail(msg):
    sys.exit("FAILED: " + msg)


def main():
    out = {
        "source": f"Pinocchio {pin.__version__} (scripts/pinocchio_kinematics.py), from "
                  "tests/data/{puma560,panda}.json",
        "conventions": {
            "matrices": "lists of rows; entry [k][m] = d(out_k)/d(in_m)",
            "Jb": "computeFrameJacobian(q, tool, LOCAL): rows [v; w], tool axes",
            "dvb_dq": "getFrameVelocityDerivatives(tool, LOCAL)[0] at (q, qd)",
            "dv_dq": "d(J0 qd)/dq, world axes at the tool origin, from dvb_dq (see the script)",
            "H0": "H0[k] = dJ0/dq_k, rows [v; w], from dv_dq at qd = e_i",
            "Jb_dot_qd": "getFrameJacobianTimeVariation(tool, LOCAL) @ qd at (q, qd)",
        },
        "robots": {},
    }
    worst_fd, h = 0.0, 1e-6
    for name in ["puma560", "panda"]:
        robot = json.loads((DATA / f"{name}.json").read_text())
        model = model_of(robot, with_tool=True)
        data = model.createData()
        tool, n = model.getFrameId("tool"), model.nv

        def jacobian(q, frame):
            return pin.computeFrameJacobian(model, data, q, tool, frame).copy()

        def world_partial(q, qd):
            """d(J0 qd)/dq from Pinocchio's LOCAL derivative, and that derivative."""
            pin.computeForwardKinematicsDerivatives(model, data, q, qd, np.zeros(n))
            dvb, _ = pin.getFrameVelocityDerivatives(model, data, tool, LOCAL)
            pin.framesForwardKinematics(model, data, q)
            r = data.oMf[tool].rotation
            j0 = jacobian(q, WORLD)
            vb = jacobian(q, LOCAL) @ qd
            v, w = r @ vb[:3], r @ vb[3:]
            out = np.zeros((6, n))
            for k in range(n):
                wk = j0[3:, k]
                out[:3, k] = r @ dvb[:3, k] + np.cross(wk, v)
                out[3:, k] = r @ dvb[3:, k] + np.cross(wk, w)
            return out, dvb.copy()

        samples = []
        for sample in robot["samples"][:10]:
            q, qd = (np.array(sample[k], dtype=float) for k in ("q", "qd"))
            j0 = np.array(sample["J0"], dtype=float)
            pin.framesForwardKinematics(model, data, q)
            r = data.oMf[tool].rotation
            jb = jacobian(q, LOCAL)
            e = np.abs(jb - np.vstack([r.T @ j0[:3], r.T @ j0[3:]])).max()
            if e > 1e-12:
                fail(f"{name}: Jb differs from R^T J0 by {e:.1e}")
            dv_dq, dvb_dq = world_partial(q, qd)
            steps = [np.eye(n)[k] * h for k in range(n)]
            fd = np.column_stack([(jacobian(q + s, WORLD) - jacobian(q - s, WORLD)) @ qd / (2 * h)
                                  for s in steps])
            e = np.abs(dv_dq - fd).max()
            if e > 1e-8:
                fail(f"{name}: dv_dq differs from finite differences by {e:.1e}")
            worst_fd = max(worst_fd, e)
            units = [world_partial(q, np.eye(n)[i])[0] for i in range(n)]
            hessian = [np.column_stack([units[i][:, k] for i in range(n)]) for k in range(n)]
            for k, s in enumerate(steps):
                fd = (jacobian(q + s, WORLD) - jacobian(q - s, WORLD)) / (2 * h)
                e = np.abs(hessian[k] - fd).max()
                if e > 1e-8:
                    fail(f"{name}: H0[{k}] differs from finite differences by {e:.1e}")
                worst_fd = max(worst_fd, e)
            pin.computeJointJacobiansTimeVariation(model, data, q, qd)
            pin.updateFramePlacements(model, data)
            jb_dot_qd = pin.getFrameJacobianTimeVariation(model, data, tool, LOCAL) @ qd
            pin.forwardKinematics(model, data, q, qd, np.zeros(n))
            acc = pin.getFrameAcceleration(model, data, tool, LOCAL).vector
            e = np.abs(acc - jb_dot_qd).max()
            if e > 1e-12 * max(1.0, np.abs(acc).max()):
                fail(f"{name}: Jb_dot_qd differs from the LOCAL frame acceleration by {e:.1e}")
            fd = (jacobian(q + h * qd, LOCAL) - jacobian(q - h * qd, LOCAL)) @ qd / (2 * h)
            e = np.abs(jb_dot_qd - fd).max()
            if e > 1e-8:
                fail(f"{name}: Jb_dot_qd differs from finite differences by {e:.1e}")
            worst_fd = max(worst_fd, e)
            samples.append({"q": q.tolist(), "qd": qd.tolist(), "Jb": rows(jb),
                            "dvb_dq": rows(dvb_dq), "dv_dq": rows(dv_dq),
                            "H0": [rows(m) for m in hessian],
                            "Jb_dot_qd": jb_dot_qd.tolist()})
        out["robots"][name] = samples
        print(f"{name}: {len(samples)} samples")
    (DATA / "pinocchio_kinematics.json").write_text(json.dumps(out) + "\n")
    print(f"worst finite-difference residual {worst_fd:.1e}; wrote "
          f"{DATA / 'pinocchio_kinematics.json'}")


if __name__ == "__main__":
    main()

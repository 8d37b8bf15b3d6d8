#!/usr/bin/env python3
"""Do Pinocchio and Robotics Toolbox read dhgen's URDF export as the same robot?

For each catalogue robot with reference values in tests/data/<robot>.json (Robotics Toolbox's
DH models, cross-checked with Pinocchio), writes `dhgen convert robots/<robot>.toml --to urdf`,
loads that URDF with Pinocchio 4.1.0 (`buildModelFromUrdf`) and with Robotics Toolbox 1.5.0
(`ERobot.URDF`), and compares their pose of the tool link, D, g and tau at the file's 20 samples
with the reference. The URDF carries no motor inertia and no friction; the references have
neither.

    pip install pin roboticstoolbox-python
    cargo build -p dhgen-cli
    python3 scripts/check_urdf_export.py

Prints the worst relative error per robot and quantity and exits non-zero above 1e-9.
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pinocchio as pin

ROOT = Path(__file__).resolve().parent.parent
DHGEN = ROOT / "target" / "debug" / "dhgen"
ROBOTS = ["planar_elbow", "puma560", "stanford", "panda"]


def rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))))


def main():
    worst_all = 0.0
    try:
        import roboticstoolbox as rtb
    except ImportError:
        rtb = None
        print("roboticstoolbox not installed: Pinocchio only")
    with tempfile.TemporaryDirectory() as tmp:
        for name in ROBOTS:
            ref = json.loads((ROOT / "tests" / "data" / f"{name}.json").read_text())
            urdf = Path(tmp) / f"{name}.urdf"
            subprocess.run(
                [str(DHGEN), "convert", str(ROOT / "robots" / f"{name}.toml"), "--to", "urdf",
                 "-o", str(urdf)],
                check=True,
            )
            model = pin.buildModelFromUrdf(str(urdf))
            model.gravity.linear = np.array(ref["gravity"], float)
            data = model.createData()
            tip = model.frames[len(model.frames) - 1].name
            fid = model.getFrameId(tip)
            worst = {}
            for s in ref["samples"]:
                q, qd, qdd = (np.array(s[k], float) for k in ("q", "qd", "qdd"))
                pin.forwardKinematics(model, data, q)
                pin.updateFramePlacements(model, data)
                t = data.oMf[fid].homogeneous
                d = pin.crba(model, data, q)
                d = np.triu(d) + np.triu(d, 1).T
                g = pin.computeGeneralizedGravity(model, data, q)
                tau = pin.rnea(model, data, q, qd, qdd)
                for k, got in (("T", t), ("D", d), ("g", g), ("tau", tau)):
                    worst[f"pinocchio {k}"] = max(worst.get(f"pinocchio {k}", 0.0), rel(got, s[k]))
            if rtb is not None:
                robot = rtb.ERobot.URDF(str(urdf))
                robot.gravity = np.array(ref["gravity"], float)
                for s in ref["samples"]:
                    q, qd, qdd = (np.array(s[k], float) for k in ("q", "qd", "qdd"))
                    t = robot.fkine(q, end=robot.links[-1].name).A
                    tau = robot.rne(q, qd, qdd)
                    d = robot.inertia(q)
                    for k, got in (("T", t), ("D", d), ("tau", tau)):
                        key = f"robotics toolbox {k}"
                        worst[key] = max(worst.get(key, 0.0), rel(got, s[k]))
            for k, w in sorted(worst.items()):
                print(f"{name:13} {k:22} worst relative error {w:.1e}")
                worst_all = max(worst_all, w)
    if worst_all > 1e-9:
        print(f"FAILED: {worst_all:.1e} > 1e-9")
        sys.exit(1)
    print(f"all within 1e-9 (worst {worst_all:.1e})")


if __name__ == "__main__":
    main()

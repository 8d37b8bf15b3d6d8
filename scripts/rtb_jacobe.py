#!/usr/bin/env python3
"""Reference body Jacobians (the tool frame's Jacobian in tool axes), for tests/data/rtb_jacobe.json.

For every robot of tests/data/rtb_models.json (the Robotics Toolbox 1.5.0 DH models, written by
scripts/rtb_models.py), at the q of each of its samples: the Toolbox's jacobe(q), rows [v; w],
both resolved in the end-effector frame (tool applied; independent of the base).

Checks (the script fails loudly if one does not hold):
  - the samples' J0 in rtb_models.json is still what this Toolbox gives (same models);
  - jacobe(q) @ qd equals central finite differences of fkine along qd, in tool axes:
    [R^T p_dot; vee(R^T R_dot)].

    pip install roboticstoolbox-python==1.5.0
    python3 scripts/rtb_jacobe.py     # writes tests/data/rtb_jacobe.json
"""
import json
import sys
import warnings
from pathlib import Path

import numpy as np
import roboticstoolbox as rtb

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rtb_models import close  # noqa: E402

warnings.filterwarnings("ignore")
DATA = Path(__file__).resolve().parent.parent / "tests" / "data"


def main():
    models = json.loads((DATA / "rtb_models.json").read_text())
    out = {
        "generator": {"script": "scripts/rtb_jacobe.py", "roboticstoolbox": rtb.__version__,
                      "states": "the q of each sample of rtb_models.json, in order"},
        "conventions": {"Je": "jacobe(q): rows [v; w] of the end-effector frame, end-effector "
                              "axes, rows of the 6 x n matrix"},
        "robots": [],
    }
    worst = 0.0
    for robot in models["robots"]:
        name = robot["name"]
        r = getattr(rtb.models.DH, name)()
        samples = []
        for s in robot["samples"]:
            q, qd = np.array(s["q"]), np.array(s["qd"])
            close(r.jacob0(q), np.array(s["J0"]), 1e-12, f"{name}: J0 of rtb_models.json")
            je = r.jacobe(q)
            h = 1e-6
            plus, minus, at = r.fkine(q + h * qd).A, r.fkine(q - h * qd).A, r.fkine(q).A
            rt = at[:3, :3].T
            v = rt @ (plus[:3, 3] - minus[:3, 3]) / (2 * h)
            w = rt @ (plus[:3, :3] - minus[:3, :3]) / (2 * h)
            fd = np.concatenate([v, [w[2, 1], w[0, 2], w[1, 0]]])
            worst = max(worst, close(je @ qd, fd, 1e-7, f"{name}: jacobe vs finite differences"))
            samples.append({"Je": je.tolist()})
        out["robots"].append({"name": name, "samples": samples})
        print(f"{name}: {r.n} joints")
    (DATA / "rtb_jacobe.json").write_text(json.dumps(out) + "\n")
    print(f"worst finite-difference residual {worst:.2e}; wrote {DATA / 'rtb_jacobe.json'}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Reference kinematic Hessians and manipulability gradients, for tests/data/rtb_hessian.json.

For every robot of tests/data/rtb_models.json (the Robotics Toolbox 1.5.0 DH models, written by
scripts/rtb_models.py), at the q of its samples:
  - H0: hessian0(q), the world-axes Jacobian's derivatives, H0[k] = dJ0/dq_k (6 x n), at the
    first HESSIAN_SAMPLES samples (the data would be large at all of them);
  - for axes "all", "trans" and "rot": manipulability(q, axes) and jacobm(q, axes), the
    gradient of Yoshikawa's manipulability, at every sample where the selected rows' J J^T is
    well conditioned (condition number below 1e8: jacobm inverts it; below, it is null).

Checks (the script fails loudly if one does not hold):
  - the samples' J0 in rtb_models.json is still what this Toolbox gives (same models);
  - hessian0 agrees with central finite differences of jacob0, column by column;
  - every jacobm recorded agrees with central finite differences of manipulability.

    pip install roboticstoolbox-python==1.5.0
    python3 scripts/rtb_hessian.py     # writes tests/data/rtb_hessian.json
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
HESSIAN_SAMPLES = 2
AXES = {"all": slice(0, 6), "trans": slice(0, 3), "rot": slice(3, 6)}


def main():
    models = json.loads((DATA / "rtb_models.json").read_text())
    out = {
        "generator": {"script": "scripts/rtb_hessian.py", "roboticstoolbox": rtb.__version__,
                      "states": "the q of each sample of rtb_models.json, in order"},
        "conventions": {"H0": "hessian0(q): H0[k] = dJ0/dq_k, rows [v; w] of the 6 x n matrix",
                        "m": "manipulability(q, axes=...) for axes all, trans, rot",
                        "Jm": "jacobm(q, axes=...), n entries; null where the rows' J J^T is "
                              "ill conditioned"},
        "robots": [],
    }
    worst_h, worst_m, h = 0.0, 0.0, 1e-6
    for robot in models["robots"]:
        name = robot["name"]
        r = getattr(rtb.models.DH, name)()
        samples = []
        for index, s in enumerate(robot["samples"]):
            q = np.array(s["q"])
            j = r.jacob0(q)
            close(j, np.array(s["J0"]), 1e-12, f"{name}: J0 of rtb_models.json")
            sample = {"m": {}, "Jm": {}}
            steps = [np.eye(r.n)[k] * h for k in range(r.n)]
            if index < HESSIAN_SAMPLES:
                hessian = r.hessian0(q)
                for k, e in enumerate(steps):
                    fd = (r.jacob0(q + e) - r.jacob0(q - e)) / (2 * h)
                    worst_h = max(worst_h, close(hessian[k], fd, 1e-8,
                                                 f"{name}: hessian0[{k}] vs finite differences"))
                sample["H0"] = hessian.tolist()
            for axes, rows in AXES.items():
                sample["m"][axes] = float(r.manipulability(q, axes=axes))
                ja = j[rows, :]
                if np.linalg.cond(ja @ ja.T) > 1e8:
                    sample["Jm"][axes] = None
                    continue
                jm = r.jacobm(q, axes=axes).flatten()
                fd = np.array([(r.manipulability(q + e, axes=axes)
                                - r.manipulability(q - e, axes=axes)) / (2 * h) for e in steps])
                worst_m = max(worst_m, close(jm, fd, 1e-7, f"{name}: jacobm({axes}) vs finite "
                                                           "differences"))
                sample["Jm"][axes] = jm.tolist()
            samples.append(sample)
        out["robots"].append({"name": name, "samples": samples})
        print(f"{name}: {r.n} joints")
    (DATA / "rtb_hessian.json").write_text(json.dumps(out) + "\n")
    print(f"worst finite-difference residuals: hessian0 {worst_h:.2e}, jacobm {worst_m:.2e}; "
          f"wrote {DATA / 'rtb_hessian.json'}")


if __name__ == "__main__":
    main()

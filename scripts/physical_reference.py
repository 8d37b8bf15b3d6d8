#!/usr/bin/env python3
"""Reference optima for BaseParameters::expand_physical, from an independent conic solver.

For each robot below, a copy 15 % heavier (masses and inertias about the centre of mass x1.15,
centres of mass x0.95: tests/integration/regressor.rs's `heavier_copy`) gives base parameters
pi_b. The problem expand_physical documents is then solved here with cvxpy and Clarabel (an
interior-point solver for semidefinite programs, nothing of dhgen's): over all inertial
parameters pi,

    minimize    sum over the dependent parameters j of ((pi_j - ref_j) / scale_j)^2
    subject to  pi[independent] + beta pi[dependent] = pi_b        (the same base parameters)
                every link physical: its pseudo-inertia [[Sigma, h], [h^T, m]] >= 0
                (Sigma = tr(I)/2 1 - I about the link frame's origin, h = m c), or, for a link
                whose description breaks the triangle inequality, [[I, S(h)], [S(h)^T, m 1]] >= 0

with ref the description's own parameters and scale the mean link mass M for a mass, M L for a
first moment and M L^2 for an inertia (L^2 = sum tr(I_o)/2 / sum m). The parameters pi of the
description and of the heavier copy are computed here from the TOML files (mass, centre of mass,
inertia about it); `dhgen params --json` gives the regrouping (which parameters are dependent,
and beta) and its pi, which must agree with this script's to 1e-12.

Writes tests/data/physical_reference.json: per robot, the optimum's objective and pi.

    pip install cvxpy          # with Clarabel, its default conic solver
    cargo build --release -p dhgen-cli
    python3 scripts/physical_reference.py
"""
import json
import subprocess
import tomllib
from pathlib import Path

import cvxpy as cp
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
ROBOTS = ["robots/puma560.toml", "robots/panda.toml"]
# Per link: m, mx, my, mz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz (inertia about the link frame's origin).
INERTIA = [[4, 5, 7], [5, 6, 8], [7, 8, 9]]


def dhgen(*args):
    binary = ROOT / "target" / "release" / "dhgen"
    command = [str(binary)] if binary.exists() else ["cargo", "run", "--release", "-q", "-p", "dhgen-cli", "--"]
    return subprocess.run(command + list(args), check=True, capture_output=True, text=True, cwd=ROOT).stdout


def link_parameters(link, heavier):
    m = float(link["mass"])
    c = np.array(link["com"], dtype=float)
    t = link["inertia"]
    ic = np.array(
        [
            [t.get("xx", 0.0), t.get("xy", 0.0), t.get("xz", 0.0)],
            [t.get("xy", 0.0), t.get("yy", 0.0), t.get("yz", 0.0)],
            [t.get("xz", 0.0), t.get("yz", 0.0), t.get("zz", 0.0)],
        ],
        dtype=float,
    )
    if heavier:
        m, c, ic = 1.15 * m, 0.95 * c, 1.15 * ic
    io = ic + m * (c @ c * np.eye(3) - np.outer(c, c))
    return [m, *(m * c), io[0, 0], io[0, 1], io[1, 1], io[0, 2], io[1, 2], io[2, 2]], ic, m


def triangle(ic, m):
    """validate::obeys_triangle_inequality: the principal moments e0 <= e1 <= e2 about the
    centre of mass with e0 + e1 >= e2 (to rounding)."""
    e = np.linalg.eigvalsh(ic)
    return e[0] + e[1] >= e[2] - 1e-12 * max(1.0, abs(e[2]))


def solve(path):
    description = tomllib.loads((ROOT / path).read_text())
    links = description["links"]
    n = len(links)
    data = json.loads(dhgen("params", "--json", path))
    reference, copy, triangles = [], [], []
    for link in links:
        p, ic, m = link_parameters(link, False)
        reference += p
        copy += link_parameters(link, True)[0]
        triangles.append(bool(triangle(ic, m)))
    reference, copy = np.array(reference), np.array(copy)
    assert len(data["values"]) == 10 * n, "joint-side terms are not modelled here"
    assert np.allclose(reference, data["values"], rtol=0, atol=1e-12), "pi differs from dhgen's"
    base = data["base"]
    ind, dep = np.array(base["independent"]), np.array(base["dependent"])
    beta = np.array(base["beta"]).reshape(len(ind), len(dep))
    pi_b = copy[ind] + beta @ copy[dep]

    masses = reference[0::10]
    big_m = masses.sum() / n
    second = sum(0.5 * (reference[10 * i + 4] + reference[10 * i + 6] + reference[10 * i + 9]) for i in range(n))
    big_l = np.sqrt(second / masses.sum())
    scale = np.array([[big_m, *[big_m * big_l] * 3, *[big_m * big_l**2] * 6][k % 10] for k in range(10 * n)])

    x = cp.Variable(10 * n)
    constraints = [x[ind] + beta @ x[dep] == pi_b]
    for i in range(n):
        p = x[10 * i : 10 * i + 10]
        own = masses[i] if masses[i] > 0 else big_m
        m = p[0] / own
        h = [p[1 + a] / (own * big_l) for a in range(3)]
        inertia = [[p[INERTIA[a][b]] / (own * big_l**2) for b in range(3)] for a in range(3)]
        if triangles[i]:
            half = 0.5 * (inertia[0][0] + inertia[1][1] + inertia[2][2])
            sigma = [[(half if a == b else 0) - inertia[a][b] for b in range(3)] for a in range(3)]
            rows = [sigma[a] + [h[a]] for a in range(3)] + [h + [m]]
        else:
            s = [[0, -h[2], h[1]], [h[2], 0, -h[0]], [-h[1], h[0], 0]]
            rows = [inertia[a] + s[a] for a in range(3)]
            rows += [[s[b][a] for b in range(3)] + [m if a == b else 0 for b in range(3)] for a in range(3)]
        matrix = cp.bmat([[entry if isinstance(entry, cp.Expression) else cp.Constant(entry) for entry in row] for row in rows])
        constraints.append(0.5 * (matrix + matrix.T) >> 0)
    objective = cp.sum_squares(cp.multiply(1.0 / scale[dep], x[dep] - reference[dep]))
    problem = cp.Problem(cp.Minimize(objective), constraints)
    problem.solve(
        solver=cp.CLARABEL,
        tol_gap_abs=1e-11,
        tol_gap_rel=1e-11,
        tol_feas=1e-11,
        max_iter=500,
    )
    assert problem.status == cp.OPTIMAL, problem.status
    pi = np.array(x.value)
    distance = float(np.sum(((pi[dep] - reference[dep]) / scale[dep]) ** 2))
    copy_distance = float(np.sum(((copy[dep] - reference[dep]) / scale[dep]) ** 2))
    worst_base = float(np.max(np.abs(pi[ind] + beta @ pi[dep] - pi_b)))
    print(f"{path}: objective {distance:.10e} (the copy's {copy_distance:.4e}), base parameters to {worst_base:.1e}, "
          f"triangle {triangles}")
    return {
        "robot": path,
        "objective": distance,
        "copy_objective": copy_distance,
        "parameters": pi.tolist(),
    }


def main():
    out = {
        "generator": "scripts/physical_reference.py",
        "solver": f"cvxpy {cp.__version__}, Clarabel",
        "robots": [solve(path) for path in ROBOTS],
    }
    target = ROOT / "tests" / "data" / "physical_reference.json"
    target.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {target}")


if __name__ == "__main__":
    main()

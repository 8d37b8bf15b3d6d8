#!/usr/bin/env python3
"""Reference values for every DH model of Robotics Toolbox for Python, for tests/data/rtb_models.json.

Robotics Toolbox 1.5.0 ships 24 robots as DH tables (`roboticstoolbox.models.DH`): industrial
arms, 7-joint arms, snakes of 10 joints, a PUMA on a two-axis gantry. Each is written here as a
dhgen description (TOML: the table, base and tool as xyz + URDF rpy, gravity, and the link masses,
centres of mass and inertias where the model has them), with 5 seeded samples of (q, qd, qdd) and
the Toolbox's T (fkine), J0 (jacob0), and where the model has dynamics D (inertia), g (gravload),
Cqd (coriolis @ qd) and tau (rne), all without friction and motor inertia (nofriction, Jm = 0).

Checks (the script fails loudly if one does not hold):
  - J0 agrees with central finite differences of fkine (position rows, and the rotation rows
    through the skew part of dR R^T);
  - g agrees with central finite differences of the potential energy of every link (its mass at
    its centre, placed by fkine_all), and so does -sum_i m_i Jv(c_i)^T gravity, the centres'
    Jacobians built from the frames of fkine_all;
  - rne = D qdd + Cqd + g.
Where the Toolbox's own gravload disagrees with its potential energy (P8: the PUMA on a gantry
with a rotated base), g is the centres' Jacobians' (exact, where the energy's finite differences
are good to 1e-9), tau = D qdd + Cqd + g, and the robot's `gravity_from` says so.

A model with flipped joints (the Toolbox's `flip`: theta = -q + offset; Jaco and Mico) is written
in the description's `urdf` convention, the flipped joint's axis -z (`flipped`: true). Models
whose data the format must refuse are listed in `rejected` with the field (dhgen must reject
their description with an error naming it).

    pip install roboticstoolbox-python==1.5.0
    python3 scripts/rtb_models.py     # writes tests/data/rtb_models.json
"""
import json
import sys
import warnings
from pathlib import Path

import numpy as np
import roboticstoolbox as rtb
from spatialmath import SE3

warnings.filterwarnings("ignore")
OUT = Path(__file__).resolve().parent.parent / "tests" / "data" / "rtb_models.json"
SAMPLES = 5
SEED = 20261201
NAMES = ['AL5D', 'Ball', 'Baxter', 'Cobra600', 'Coil', 'Hyper', 'Hyper3d', 'IRB140', 'Jaco',
         'KR5', 'LWR4', 'Mico', 'Orion5', 'P8', 'Panda', 'Planar2', 'Planar3', 'Puma560',
         'Sawyer', 'Stanford', 'TwoLink', 'UR10', 'UR3', 'UR5']


def fail(msg):
    print("FAILED: " + msg, file=sys.stderr)
    sys.exit(1)


def close(a, b, tol, what):
    """The largest difference of a from b relative to max(1, |b|); fails above tol."""
    scale = max(1.0, np.abs(b).max())
    e = np.abs(np.asarray(a) - np.asarray(b)).max()
    if e > tol * scale:
        fail(f"{what}: {e} (scale {scale})")
    return e


def num(x):
    return repr(float(x))


def has_dynamics(r):
    return any(L.m is not None and L.m > 0 for L in r.links)


def description(r, name):
    """The dhgen description of a Toolbox DH robot."""
    lines = [f'name = "{name}"',
             f'convention = "{"modified" if r.mdh else "standard"}"',
             "gravity = [%s]" % ", ".join(num(x) for x in r.gravity),
             # Some published inertias break the triangle inequality (the Stanford arm's link 5).
             "allow_nonphysical_inertia = true"]
    for key, T in (("base", r.base), ("tool", r.tool)):
        if not np.array_equal(T.A, np.eye(4)):
            # URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll); spatialmath's order "zyx" is that.
            lines.append(f"{key} = {{ xyz = [{', '.join(num(x) for x in T.t)}], "
                         f"rpy = [{', '.join(num(x) for x in T.rpy(order='zyx'))}] }}")
    dyn = has_dynamics(r)
    for L in r.links:
        lines.append("")
        lines.append("[[links]]")
        lines.append(f'joint = "{"prismatic" if L.isprismatic else "revolute"}"')
        lines.append(f"a = {num(L.a)}")
        lines.append(f"alpha = {num(L.alpha)}")
        # The Toolbox's offset is added to q: theta for a revolute joint, d for a prismatic one.
        if L.isprismatic:
            lines.append(f"d = {num(L.offset)}")
            lines.append(f"theta = {num(L.theta)}")
        else:
            lines.append(f"d = {num(L.d)}")
            lines.append(f"theta = {num(L.offset)}")
        if L.qlim is not None and np.all(np.isfinite(L.qlim)):
            lines.append(f"limits = [{num(L.qlim[0])}, {num(L.qlim[1])}]")
        if dyn:
            inertia = np.array(L.I, dtype=float)
            lines.append(f"mass = {num(L.m)}")
            lines.append(f"com = [{', '.join(num(x) for x in L.r)}]")
            lines.append("inertia = { " + ", ".join(
                f"{k} = {num(inertia[i, j])}" for k, (i, j) in
                [("xx", (0, 0)), ("yy", (1, 1)), ("zz", (2, 2)), ("xy", (0, 1)), ("yz", (1, 2)),
                 ("xz", (0, 2))]) + " }")
    return "\n".join(lines) + "\n"


def gravity_torques(r, q):
    """g = -sum_i m_i Jv(c_i)^T gravity, the gradient of the potential energy, with each centre's
    Jacobian built from the frames of fkine_all (joint j turns or slides along z of frame j - 1
    in a standard table, of frame j in a modified one): exact, where finite differences of the
    energy are good to about 1e-9."""
    grav = np.array(r.gravity, dtype=float)
    frames = [T.A for T in r.fkine_all(q)]  # the base first, then each link's frame
    g = np.zeros(r.n)
    for i, L in enumerate(r.links):
        T = frames[i + 1]
        c = T[:3, :3] @ np.array(L.r, dtype=float) + T[:3, 3]
        for j in range(i + 1):
            A = frames[j + 1] if r.mdh else frames[j]
            z, o = A[:3, 2], A[:3, 3]
            v = z if r.links[j].isprismatic else np.cross(z, c - o)
            g[j] -= L.m * grav @ v
    return g


def se3_fields(T):
    """A pose as the description's `{ xyz, rpy }` (URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll))."""
    T = SE3(T, check=False) if not isinstance(T, SE3) else T
    return (f"{{ xyz = [{', '.join(num(x) for x in T.t)}], "
            f"rpy = [{', '.join(num(x) for x in T.rpy(order='zyx'))}] }}")


def urdf_description(r, name):
    """A standard table with flipped joints in the description's `urdf` convention: row i's
    origin is the fixed part of the previous DH transform followed by the joint's offset, its
    axis z or, flipped, -z; the last row's fixed part moves into the tool (kinematics only)."""
    if r.mdh or has_dynamics(r):
        fail(f"{name}: flipped joints in a modified table or with dynamics are not handled")
    lines = [f'name = "{name}"', 'convention = "urdf"',
             "gravity = [%s]" % ", ".join(num(x) for x in r.gravity)]
    if not np.array_equal(r.base.A, np.eye(4)):
        lines.append(f"base = {se3_fields(r.base)}")
    before = SE3()
    for L in r.links:
        if L.isprismatic:
            origin = before * SE3.Rz(L.theta) * SE3.Tz(L.offset)
            after = SE3.Tx(L.a) * SE3.Rx(L.alpha)
        else:
            origin = before * SE3.Rz(L.offset)
            after = SE3.Tz(L.d) * SE3.Tx(L.a) * SE3.Rx(L.alpha)
        lines += ["", "[[links]]", f'joint = "{"prismatic" if L.isprismatic else "revolute"}"',
                  f"origin = {se3_fields(origin)}",
                  f"axis = [0.0, 0.0, {'-1.0' if L.isflip else '1.0'}]"]
        if L.qlim is not None and np.all(np.isfinite(L.qlim)):
            lines.append(f"limits = [{num(L.qlim[0])}, {num(L.qlim[1])}]")
        before = after
    tool = before * r.tool
    if not np.array_equal(tool.A, np.eye(4)):
        lines.insert(3, f"tool = {se3_fields(tool)}")
    return "\n".join(lines) + "\n"


def potential(r, q):
    g = np.array(r.gravity, dtype=float)
    frames = r.fkine_all(q)  # the base first, then each link's frame
    u = 0.0
    for i, L in enumerate(r.links):
        T = frames[i + 1].A
        u -= L.m * g @ (T[:3, :3] @ np.array(L.r, dtype=float) + T[:3, 3])
    return u


def jacobian_fd(r, q, h=1e-7):
    cols = []
    R = r.fkine(q).A[:3, :3]
    for e in np.eye(r.n):
        a, b = r.fkine(q + h * e).A, r.fkine(q - h * e).A
        v = (a[:3, 3] - b[:3, 3]) / (2 * h)
        W = (a[:3, :3] - b[:3, :3]) / (2 * h) @ R.T
        cols.append(np.concatenate([v, [W[2, 1], W[0, 2], W[1, 0]]]))
    return np.array(cols).T


def main():
    rng = np.random.default_rng(SEED)
    out = {
        "generator": {"script": "scripts/rtb_models.py", "roboticstoolbox": rtb.__version__,
                      "seed": SEED},
        "conventions": {
            "toml": "the dhgen description (docs/robot-description.md) of the Toolbox model",
            "T": "fkine(q), 4x4, rows", "J0": "jacob0(q), 6xn, rows [v; w] in the world frame",
            "D": "inertia(q)", "g": "gravload(q) (see gravity_from)",
            "Cqd": "coriolis(q, qd) @ qd", "tau": "rne(q, qd, qdd) = D qdd + Cqd + g",
            "friction_included": False, "motor_inertia_included": False,
        },
        "robots": [], "rejected": [],
    }
    for name in NAMES:
        r = getattr(rtb.models.DH, name)()
        # A flipped joint (theta = -q + offset) has no field in a DH row: such a robot is
        # written in the urdf convention, its joint's axis -z.
        flipped = any(L.isflip for L in r.links)
        toml = (urdf_description if flipped else description)(r, name.lower())
        bad = [(j + 1, L.r) for j, L in enumerate(r.links)
               if has_dynamics(r) and np.abs(np.array(L.r, dtype=float)).max() > 1e3]
        if bad:
            out["rejected"].append({"name": name, "toml": toml, "field": "com",
                                    "link": bad[0][0],
                                    "why": f"link {bad[0][0]}'s centre of mass "
                                           f"{[float(x) for x in bad[0][1]]} m is beyond any "
                                           "robot (millimetres written as metres?)"})
            continue
        robot = {"name": name, "dof": r.n, "toml": toml, "flipped": flipped, "gravity_from": None,
                 "samples": []}
        dyn = has_dynamics(r)
        nf = r.nofriction(True, True)
        for L in nf.links:
            L.Jm = 0.0
        for _ in range(SAMPLES):
            q = np.array([rng.uniform(*L.qlim) if L.qlim is not None and np.all(np.isfinite(L.qlim))
                          else rng.uniform(-1.5, 1.5) for L in r.links])
            qd, qdd = rng.uniform(-1, 1, r.n), rng.uniform(-1, 1, r.n)
            J = r.jacob0(q)
            e = np.abs(J - jacobian_fd(r, q)).max()
            if e > 1e-6:
                fail(f"{name}: jacob0 vs finite differences of fkine: {e}")
            s = {"q": q.tolist(), "qd": qd.tolist(), "qdd": qdd.tolist(),
                 "T": r.fkine(q).A.tolist(), "J0": J.tolist()}
            if dyn:
                D = nf.inertia(q)
                Cqd = nf.coriolis(q, qd) @ qd
                g = nf.gravload(q)
                h = 1e-6
                g_energy = np.array([(potential(r, q + h * e) - potential(r, q - h * e)) / (2 * h)
                                     for e in np.eye(r.n)])
                g_jacobians = gravity_torques(r, q)
                scale = max(1.0, np.abs(g_energy).max())
                if np.abs(g_jacobians - g_energy).max() > 1e-6 * scale:
                    fail(f"{name}: the centres' Jacobians vs the potential energy")
                if np.abs(g - g_energy).max() > 1e-6 * scale:
                    robot["gravity_from"] = "jacobians"
                    g = g_jacobians
                tau = D @ qdd + Cqd + g
                if robot["gravity_from"] is None:
                    e = np.abs(tau - nf.rne(q, qd, qdd)).max()
                    if e > 1e-9 * max(1.0, np.abs(tau).max()):
                        fail(f"{name}: rne vs D qdd + Cqd + g: {e}")
                s.update({"D": D.tolist(), "g": g.tolist(), "Cqd": Cqd.tolist(),
                          "tau": tau.tolist()})
            robot["samples"].append(s)
        if robot["gravity_from"]:
            robot["note"] = ("the Toolbox's gravload and rne disagree with the gradient of the "
                             "potential energy for this model; g is -sum m_i Jv(c_i)^T gravity "
                             "from fkine_all's frames (which agrees with the energy) and tau = "
                             "D qdd + Cqd + g")
        out["robots"].append(robot)
        print(f"{name}: {r.n} joints, {'dynamics' if dyn else 'kinematics'}"
              + (", g from the centres' Jacobians" if robot["gravity_from"] else ""))
    OUT.write_text(json.dumps(out) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()

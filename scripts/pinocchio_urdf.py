#!/usr/bin/env python3
"""Reference values for the URDF input, from Pinocchio, for tests/data/urdf_<name>.json.

For each robot of ROBOTS below, reads tests/data/urdf/<file> and writes tests/data/urdf_<name>.json
with 20 samples (10 for the larger files) of (q, qd, qdd) and Pinocchio's T, J0, D, Cqd, C, g, tau and fd_qdd.

The robot is the serial chain of URDF joints from the root link to the `tip` link:
  - the revolute / continuous / prismatic joints on that path are the robot's joints q, in path
    order (root to tip); fixed joints are merged;
  - every other movable joint (not on the path) is locked at q = 0: its subtree is rigidly
    attached and its inertia counted (pin.buildReducedModel at pin.neutral);
  - gravity [0, 0, -9.81] in the root link's frame.

Checks (the script fails loudly if one does not hold):
  - the reduced model's joints are exactly the chain's joints, in order; armature is zero;
  - T agrees with an independent numpy forward kinematics of the URDF (origin xyz/rpy, axis);
  - J0 agrees with central finite differences of T;
  - g agrees with finite differences of the potential energy, and 1/2 qd' D qd with the kinetic
    energy, both from the independent forward kinematics of EVERY link (locked subtrees included)
    and the URDF's <inertial> elements;
  - tau = D qdd + Cqd + g; aba(q, qd, tau) = qdd; C qd = Cqd; Ddot - 2C skew-symmetric
    (Ddot by central finite differences of crba along qd); C equals the Christoffel-symbol
    matrix built from central finite differences of crba.

    python3 scripts/pinocchio_urdf.py            # write tests/data/urdf_*.json of ROBOTS
    python3 scripts/pinocchio_urdf.py --random   # (re)write the made-up robots of RANDOM_ROBOTS:
                                                 # tests/data/urdf/random_<k>.urdf (seeded,
                                                 # byte-for-byte reproducible) and
                                                 # tests/data/urdf_random_<k>.json
    python3 scripts/pinocchio_urdf.py --summary  # print each URDF's joint structure
    python3 scripts/pinocchio_urdf.py --copy     # (re)copy the URDFs from an installed
                                                 # example-robot-data (pip install --no-deps
                                                 # example-robot-data==6.0.0), byte for byte
"""
import hashlib
import json
import math
import shutil
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data"
URDF_DIR = DATA / "urdf"
SCRIPT = "scripts/pinocchio_urdf.py"

PACKAGE = "example-robot-data"
PACKAGE_VERSION = "6.0.0"
# Path of the robots inside the installed wheel (site-packages/cmeel.prefix/...).
PACKAGE_PREFIX = "cmeel.prefix/share/example-robot-data/robots"

SAMPLES = 20
GRAVITY = [0.0, 0.0, -9.81]

ROBOTS = [
    {
        "name": "panda",
        "urdf": "panda.urdf",
        "source_path": "robots/panda_description/urdf/panda.urdf",
        "licence": "Apache-2.0 (robots/panda_description/LICENSE; upstream "
        "frankaemika/franka_ros franka_description)",
        "tip": "panda_hand",
        "seed": 1101,
    },
    {
        "name": "ur5",
        "urdf": "ur5.urdf",
        "source_path": "robots/ur_description/urdf/ur5_joint_limited_robot.urdf",
        "licence": "BSD (robots/ur_description/README.md; upstream "
        "ros-industrial/universal_robot ur_description)",
        "tip": "wrist_3_link",
        "seed": 1102,
    },
    {
        "name": "baxter",
        "urdf": "baxter.urdf",
        "source_path": "robots/baxter_description/urdf/baxter.urdf",
        "licence": "BSD-3-Clause, Copyright (c) 2013-2015 Rethink Robotics "
        "(robots/baxter_description/LICENSE; upstream RethinkRobotics/baxter_common)",
        "tip": "left_gripper",
        "seed": 1103,
    },
    {
        "name": "kinova",
        "urdf": "kinova.urdf",
        "source_path": "robots/kinova_description/robots/kinova.urdf",
        "licence": "BSD (robots/kinova_description/README.md; upstream "
        "Kinovarobotics/kinova-ros kinova_description)",
        "tip": "j2s6s200_end_effector",
        "seed": 1104,
    },
    {
        "name": "double_pendulum",
        "urdf": "double_pendulum_continuous.urdf",
        "source_path": "robots/double_pendulum_description/urdf/double_pendulum_continuous.urdf",
        "licence": "BSD (robots/double_pendulum_description/README.md; original work "
        "of example-robot-data's contributors)",
        "tip": "link2",
        "seed": 1105,
    },
    {
        # A tree (wheels, head, hand) whose arm starts after a prismatic torso; the base
        # carries a 1 mg antenna whose tensor is not positive semi-definite (a link no moving
        # body carries: dhgen reads past it, as Pinocchio does).
        "name": "tiago",
        "urdf": "tiago.urdf",
        "source_path": "robots/tiago_description/robots/tiago.urdf",
        "licence": "Apache-2.0 (robots/tiago_description/README.md; upstream "
        "pal-robotics/tiago_robot tiago_description)",
        "tip": "arm_7_link",
        "seed": 1106,
    },
    {
        # Spherical joints written as three revolute ones through massless virtual links
        # (no <inertial>): 13 joints from the root to the left hand.
        "name": "human",
        "urdf": "human.urdf",
        "source_path": "robots/human_description/robots/human.urdf",
        "licence": "BSD-2-Clause (robots/human_description/README.md; original work of the "
        "Gepetto team)",
        "tip": "left_hand",
        "seed": 1107,
    },
    # Four more from the wild, with fewer samples each (the files are larger than the arms'):
    {
        "name": "xarm7",
        "urdf": "xarm7.urdf",
        "source_path": "robots/xarm_description/urdf/xarm7.urdf",
        "licence": "BSD-3-Clause (robots/xarm_description/README.md; upstream "
        "xArm-Developer/xarm_ros2)",
        "tip": "link_eef",
        "seed": 1108,
        "samples": 10,
    },
    {
        # A humanoid's left arm from the pelvis: three waist joints, then seven; the legs and
        # the other arm (19 joints) locked.
        "name": "g1",
        "urdf": "g1.urdf",
        "source_path": "robots/g1_description/urdf/g1_29dof_rev_1_0.urdf",
        "licence": "BSD-3-Clause (robots/g1_description/README.md; upstream "
        "unitreerobotics/unitree_ros g1_description)",
        "tip": "left_wrist_yaw_link",
        "seed": 1109,
        "samples": 10,
    },
    {
        # One arm of a four-legged, wheeled, two-armed robot.
        "name": "centauro",
        "urdf": "centauro.urdf",
        "source_path": "robots/centauro_description/urdf/centauro.urdf",
        "licence": "Apache-2.0 (robots/centauro_description/README.md; upstream "
        "ADVRHumanoids/iit-centauro-ros-pkg)",
        "tip": "arm1_6",
        "seed": 1110,
        "samples": 10,
    },
    {
        # A five-joint arm under a hexacopter's body.
        "name": "hextilt",
        "urdf": "hextilt_flying_arm_5.urdf",
        "source_path": "robots/hextilt_description/urdf/hextilt_flying_arm_5.urdf",
        "licence": "BSD-2-Clause (robots/hextilt_description/README.md; upstream "
        "PepMS/hidro_robots)",
        "tip": "flying_arm_5__gripper",
        "seed": 1111,
        "samples": 10,
    },
]

MOVABLE = ("revolute", "continuous", "prismatic")


def fail(msg):
    print("FAILED: " + msg, file=sys.stderr)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)


# ---------------------------------------------------------------------------------------------
# An independent reading of the URDF (numpy only), used to choose the chain and to check Pinocchio.


def floats(text, default):
    if text is None:
        return list(default)
    return [float(x) for x in text.split()]


def rpy_matrix(rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = (math.cos(r), math.sin(r), math.cos(p), math.sin(p),
                              math.cos(y), math.sin(y))
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def transform(xyz, rpy):
    t = np.eye(4)
    t[:3, :3] = rpy_matrix(rpy)
    t[:3, 3] = xyz
    return t


def axis_angle(axis, angle):
    k = np.array(axis) / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


def origin_of(elem):
    o = elem.find("origin")
    if o is None:
        return [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    return floats(o.get("xyz"), [0, 0, 0]), floats(o.get("rpy"), [0, 0, 0])


class Urdf:
    def __init__(self, path):
        self.path = path
        root = ET.parse(path).getroot()
        # Only the direct children of <robot>: <transmission> also holds <joint name=...> tags.
        self.links = {l.get("name"): l for l in root.findall("link")}
        self.joints = {}
        self.joint_order = []
        self.parent_joint = {}  # child link -> joint name
        for j in root.findall("joint"):
            name = j.get("name")
            lim = j.find("limit")
            dyn = j.find("dynamics")
            xyz, rpy = origin_of(j)
            self.joints[name] = {
                "name": name,
                "type": j.get("type"),
                "parent": j.find("parent").get("link"),
                "child": j.find("child").get("link"),
                "xyz": xyz,
                "rpy": rpy,
                "rpy_text": None if j.find("origin") is None else j.find("origin").get("rpy"),
                "axis": floats(j.find("axis").get("xyz") if j.find("axis") is not None else None,
                               [1, 0, 0]),
                "axis_text": None if j.find("axis") is None else j.find("axis").get("xyz"),
                "lower": None if lim is None or lim.get("lower") is None else float(lim.get("lower")),
                "upper": None if lim is None or lim.get("upper") is None else float(lim.get("upper")),
                "has_limit": lim is not None,
                "dynamics": None if dyn is None else dict(dyn.attrib),
                "mimic": None if j.find("mimic") is None else dict(j.find("mimic").attrib),
            }
            self.joint_order.append(name)
            check(self.joints[name]["child"] not in self.parent_joint,
                  f"{path}: link {self.joints[name]['child']} has two parent joints")
            self.parent_joint[self.joints[name]["child"]] = name
        roots = [l for l in self.links if l not in self.parent_joint]
        check(len(roots) == 1, f"{path}: expected one root link, found {roots}")
        self.root = roots[0]

    def path_joints(self, tip):
        """Joint names from the root link to `tip`, root first."""
        check(tip in self.links, f"{self.path}: no link {tip}")
        out = []
        link = tip
        while link != self.root:
            j = self.parent_joint[link]
            out.append(j)
            link = self.joints[j]["parent"]
        return out[::-1]

    def joint_motion(self, j, q):
        t = np.eye(4)
        if j["type"] in ("revolute", "continuous"):
            t[:3, :3] = axis_angle(j["axis"], q)
        elif j["type"] == "prismatic":
            t[:3, 3] = np.array(j["axis"]) / np.linalg.norm(j["axis"]) * q
        elif j["type"] != "fixed":
            fail(f"{self.path}: joint type {j['type']} not handled")
        return t

    def link_poses(self, qmap):
        """World pose of every link; movable joints not in qmap are at 0."""
        poses = {self.root: np.eye(4)}
        pending = list(self.joint_order)
        while pending:
            rest = []
            for name in pending:
                j = self.joints[name]
                if j["parent"] not in poses:
                    rest.append(name)
                    continue
                poses[j["child"]] = (poses[j["parent"]] @ transform(j["xyz"], j["rpy"])
                                     @ self.joint_motion(j, qmap.get(name, 0.0)))
            check(len(rest) < len(pending), f"{self.path}: joint tree is disconnected")
            pending = rest
        return poses

    def inertials(self):
        """(link, mass, com in link frame, inertia tensor about the COM in link axes)."""
        out = []
        for name, link in self.links.items():
            inert = link.find("inertial")
            if inert is None:
                continue
            m = float(inert.find("mass").get("value"))
            xyz, rpy = origin_of(inert)
            a = inert.find("inertia").attrib
            i = np.array([
                [float(a["ixx"]), float(a["ixy"]), float(a["ixz"])],
                [float(a["ixy"]), float(a["iyy"]), float(a["iyz"])],
                [float(a["ixz"]), float(a["iyz"]), float(a["izz"])],
            ])
            r = rpy_matrix(rpy)
            out.append((name, m, np.array(xyz), r @ i @ r.T))
        return out


def rot_log(r):
    return pin.log3(r)


# ---------------------------------------------------------------------------------------------
# Pinocchio model of the chain.


def reduced_model(urdf_path, u, chain):
    full = pin.buildModelFromUrdf(str(urdf_path))
    full.gravity.linear = np.array(GRAVITY)
    chain_set = set(chain)
    movable = [n for n in u.joint_order if u.joints[n]["type"] in MOVABLE]
    full_names = [full.names[i] for i in range(1, full.njoints)]
    check(sorted(full_names) == sorted(movable),
          f"Pinocchio's joints {full_names} are not the URDF's movable joints {movable}")
    locked_names = [n for n in full_names if n not in chain_set]
    locked_ids = [full.getJointId(n) for n in locked_names]
    model = pin.buildReducedModel(full, locked_ids, pin.neutral(full))
    model.gravity.linear = np.array(GRAVITY)
    names = [model.names[i] for i in range(1, model.njoints)]
    check(names == chain, f"reduced model joints {names} != chain {chain}")
    for i in range(1, model.njoints):
        check(model.parents[i] == i - 1, f"reduced model is not a chain at joint {names[i - 1]}")
    check(np.all(model.armature == 0), "armature is not zero")
    check(np.all(model.rotorInertia == 0), "rotor inertia is not zero")
    check(model.nv == len(chain), "nv != n")
    return model, locked_names


def to_pin_q(model, u, chain, q):
    qp = np.zeros(model.nq)
    for i, name in enumerate(chain):
        jm = model.joints[i + 1]
        if u.joints[name]["type"] == "continuous":
            check(jm.nq == 2 and jm.nv == 1, f"{name}: continuous joint is not nq=2/nv=1")
            qp[jm.idx_q] = math.cos(q[i])
            qp[jm.idx_q + 1] = math.sin(q[i])
        else:
            check(jm.nq == 1 and jm.nv == 1, f"{name}: joint is not nq=nv=1")
            qp[jm.idx_q] = q[i]
        check(jm.idx_v == i, f"{name}: velocity index {jm.idx_v} != {i}")
    return qp


def sym(d):
    return np.triu(d) + np.triu(d, 1).T


def crba(model, data, qp):
    return sym(pin.crba(model, data, qp).copy())


def close(a, b, tol, what):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    err = float(np.max(np.abs(a - b))) if a.size else 0.0
    scale = max(1.0, float(np.max(np.abs(b))) if b.size else 1.0)
    check(err <= tol * scale, f"{what}: max error {err:.3e} > {tol:.1e} * {scale:.3g}")
    return err / scale


def sample_q(rng, u, chain):
    q = []
    for name in chain:
        j = u.joints[name]
        if j["type"] == "continuous":
            q.append(rng.uniform(-math.pi, math.pi))
        else:
            check(j["lower"] is not None and j["upper"] is not None and j["lower"] < j["upper"],
                  f"{name}: no usable limits")
            q.append(rng.uniform(j["lower"], j["upper"]))
    return np.array(q)


def independent_energy(u, chain, q, qd, h=1e-6):
    """Potential energy, and kinetic energy by central differences of every link's pose."""
    grav = np.array(GRAVITY)
    inert = u.inertials()

    def poses(qq):
        return u.link_poses(dict(zip(chain, qq)))

    p0, pp, pm = poses(q), poses(q + h * qd), poses(q - h * qd)
    pot, kin = 0.0, 0.0
    for name, m, c, ic in inert:
        t0 = p0[name]
        com = t0[:3, :3] @ c + t0[:3, 3]
        pot -= m * grav @ com
        v = ((pp[name][:3, :3] @ c + pp[name][:3, 3]) - (pm[name][:3, :3] @ c + pm[name][:3, 3])) / (2 * h)
        w = rot_log(pp[name][:3, :3] @ pm[name][:3, :3].T) / (2 * h)
        iw = t0[:3, :3] @ ic @ t0[:3, :3].T
        kin += 0.5 * m * v @ v + 0.5 * w @ iw @ w
    return pot, kin


def independent_gravity(u, chain, q, h=1e-6):
    g = np.zeros(len(q))
    for i in range(len(q)):
        e = np.zeros(len(q))
        e[i] = h
        g[i] = (independent_energy(u, chain, q + e, np.zeros(len(q)))[0]
                - independent_energy(u, chain, q - e, np.zeros(len(q)))[0]) / (2 * h)
    return g


def lists(a):
    return np.asarray(a, dtype=float).tolist()


CONVENTIONS = {
    "fields": "name: robot name; source: where the URDF comes from (package, version, path inside "
    "it, licence, sha256 of the file in tests/data/urdf, modified = false: the copy is byte for "
    "byte the package's file); urdf: file name in tests/data/urdf; tip: the chain's last link; "
    "base: the chain's first link when not the URDF root (null: the root link); root_link: the "
    "URDF's root link; n: number of joints; joint_names / joint_types / joint_axes: the chain's "
    "joints in order, with their URDF type and <axis> xyz; qlim: URDF [lower, upper] (null for "
    "continuous joints); locked_joints: the movable joints off the chain, locked at 0; "
    "friction_included: false, tau has no damping/friction; joint_dynamics: see below; sampling: "
    "how the samples were drawn; generator: the script, the library versions and the worst "
    "relative error of each consistency check; samples: list of {q, qd, qdd, T, J0, D, Cqd, C, g, "
    "tau, fd_qdd, K, V, com, Jcom}.",
    "robot": "The serial chain of URDF joints from the root link (or `base` when not null) to the "
    "link `tip`. The revolute, continuous and prismatic joints on that path are the robot's joints "
    "q, in path order (root first), named in `joint_names`; fixed joints are merged into their "
    "parent link. Every other movable joint of the file (`locked_joints`, not on the path) is "
    "locked at q = 0: its subtree is rigidly attached to its parent link and its mass and inertia "
    "are counted. Pinocchio: buildModelFromUrdf, then buildReducedModel(model, locked, "
    "neutral(model)); mimic tags are ignored (every locked joint is at 0).",
    "urdf_kinematics": "A joint's child link frame = parent link frame * Trans(origin xyz) * "
    "Rot(origin rpy) * motion(q); Rot(rpy) = Rz(yaw) Ry(pitch) Rx(roll) (fixed axes X, Y, Z); "
    "motion(q) is a rotation by q about the unit `axis` (joint frame coordinates) for revolute "
    "and continuous joints, a translation q * axis for prismatic ones, identity for fixed ones. "
    "A missing <origin> is identity, a missing <axis> is 1 0 0.",
    "joint_variable": "q[i] is the URDF joint value: the angle in rad (revolute, continuous) or the "
    "displacement in m (prismatic) of motion(q) above; q = 0 is the URDF's zero configuration. "
    "(Pinocchio stores a continuous joint as (cos q, sin q); converted.)",
    "sampling": "q uniform in each joint's URDF [lower, upper], uniform in [-pi, pi] for a "
    "continuous joint; qd and qdd uniform in [-2, 2]; numpy default_rng(seed).",
    "gravity": "gravitational acceleration in the root link's frame (Pinocchio model.gravity).",
    "T": "4x4 homogeneous pose of the `tip` link frame in the root link frame = Pinocchio "
    "data.oMf of the tip's BODY frame.",
    "J0": "6xn geometric Jacobian of the tip link frame origin, in root-frame axes, rows "
    "[vx,vy,vz,wx,wy,wz] = Pinocchio getFrameJacobian(tip, LOCAL_WORLD_ALIGNED). Column j of a "
    "revolute joint: [a x (p_tip - p_j); a]; prismatic: [a; 0], a = joint axis in root axes.",
    "dynamics_equation": "tau = D(q) qdd + C(q,qd) qd + g(q); no friction, no damping, no motor "
    "/rotor inertia (armature) - see `friction_included` and `joint_dynamics`.",
    "D": "n x n joint-space inertia matrix = Pinocchio crba(q), symmetrised.",
    "Cqd": "n-vector of Coriolis+centrifugal torques = rnea(q, qd, 0) - g(q) (equals C @ qd).",
    "C": "n x n Christoffel-form Coriolis matrix C[i][j] = sum_k Gamma[i][j][k] qd[k], Gamma[i][j][k] "
    "= 1/2 (dD_ij/dq_k + dD_ik/dq_j - dD_jk/dq_i), computed as 1/2 d(Cqd)/d(qd) = 1/2 dtau_dv of "
    "Pinocchio's computeRNEADerivatives(q, qd, 0). C qd = Cqd and Ddot - 2C skew-symmetric are "
    "checked.",
    "g": "n-vector of gravity torques = computeGeneralizedGravity(q) = rnea(q, 0, 0); the torque "
    "needed to hold the arm static.",
    "tau": "n-vector inverse dynamics = rnea(q, qd, qdd) with `gravity`.",
    "qdd": "the input joint acceleration.",
    "fd_qdd": "aba(q, qd, tau): forward dynamics of `tau`, equal to qdd (to 1e-10, checked).",
    "K": "kinetic energy 1/2 qd' D qd = computeKineticEnergy(q, qd) (checked against each link's "
    "energy from finite differences of its pose).",
    "com": "centre of mass of the bodies the joints move, root link frame = centerOfMass(q) "
    "(checked: V = -M gravity . com, M = computeTotalMass).",
    "Jcom": "3xn Jacobian of `com` = jacobianCenterOfMass(q) (checked: g = -M Jcom' gravity).",
    "V": "potential energy = computePotentialEnergy(q) = -sum_k m_k gravity . c_k over the bodies the "
    "joints move (centres of mass c_k in the root link frame; links fixed to the root link, which "
    "no joint moves, are not counted). Its change between two samples is checked against every "
    "link's weight times its height.",
    "joint_dynamics": "per chain joint, the damping and friction attributes of its URDF "
    "<dynamics> tag (null when absent); NOT included in tau.",
    "units": "SI (m, rad, kg, kg m^2, N, N m).",
    "layout": "all matrices are row-major nested lists (list of rows).",
}


def generate(robot):
    path = URDF_DIR / robot["urdf"]
    u = Urdf(path)
    tip = robot["tip"]
    path_joints = u.path_joints(tip)
    for name in path_joints:
        check(u.joints[name]["type"] in MOVABLE + ("fixed",),
              f"{name}: joint type {u.joints[name]['type']} on the chain")
    chain = [n for n in path_joints if u.joints[n]["type"] in MOVABLE]
    n = len(chain)
    model, locked = reduced_model(path, u, chain)
    data = model.createData()
    fid = model.getFrameId(tip, pin.FrameType.BODY)
    check(fid < len(model.frames) and model.frames[fid].name == tip, f"no BODY frame {tip}")
    check(model.frames[fid].parentJoint == n, "the tip frame is not on the chain's last joint")

    rng = np.random.default_rng(robot["seed"])
    samples = []
    worst = {}

    def note(k, v):
        worst[k] = max(worst.get(k, 0.0), v)

    for _ in range(robot.get("samples", SAMPLES)):
        q = sample_q(rng, u, chain)
        qd = rng.uniform(-2, 2, n)
        qdd = rng.uniform(-2, 2, n)
        qp = to_pin_q(model, u, chain, q)
        zero = np.zeros(n)

        pin.forwardKinematics(model, data, qp)
        pin.updateFramePlacements(model, data)
        pin.computeJointJacobians(model, data, qp)
        t = data.oMf[fid].homogeneous.copy()
        j0 = pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED).copy()

        d = crba(model, data, qp)
        g = pin.computeGeneralizedGravity(model, data, qp).copy()
        tau = pin.rnea(model, data, qp, qd, qdd).copy()
        cqd = pin.rnea(model, data, qp, qd, zero).copy() - g
        _, dtau_dv, _ = pin.computeRNEADerivatives(model, data, qp, qd, zero)
        c = 0.5 * np.array(dtau_dv)
        fd = pin.aba(model, data, qp, qd, tau).copy()
        kinetic = float(pin.computeKineticEnergy(model, data, qp, qd))
        potential = float(pin.computePotentialEnergy(model, data, qp))
        com = pin.centerOfMass(model, data, qp).copy()
        jcom = pin.jacobianCenterOfMass(model, data, qp).copy()
        total = pin.computeTotalMass(model)

        # Consistency checks.
        note("T vs numpy FK", close(t, u.link_poses(dict(zip(chain, q)))[tip], 1e-12, "T vs numpy FK"))
        h = 1e-6
        for k in range(n):
            e = np.zeros(n)
            e[k] = h
            tp = u.link_poses(dict(zip(chain, q + e)))[tip]
            tm = u.link_poses(dict(zip(chain, q - e)))[tip]
            col = np.concatenate([(tp[:3, 3] - tm[:3, 3]) / (2 * h),
                                  rot_log(tp[:3, :3] @ tm[:3, :3].T) / (2 * h)])
            note("J0 vs FD", close(j0[:, k], col, 1e-7, f"J0 column {k} vs finite differences"))
        note("g vs rnea(q,0,0)", close(g, pin.rnea(model, data, qp, zero, zero), 1e-12, "g vs rnea(q,0,0)"))
        note("g vs FD potential", close(g, independent_gravity(u, chain, q), 1e-6, "g vs dV/dq"))
        pot, kin = independent_energy(u, chain, q, qd)
        note("KE", close(0.5 * qd @ d @ qd, kin, 1e-7, "1/2 qd'D qd vs kinetic energy"))
        note("K", close(kinetic, kin, 1e-7, "computeKineticEnergy vs kinetic energy"))
        note("V = -M g.com", close(potential, -total * np.array(GRAVITY) @ com, 1e-12,
                                   "V vs the centre of mass"))
        note("g = -M Jcom' g", close(g, -total * jcom.T @ np.array(GRAVITY), 1e-12,
                                     "g vs the Jacobian of the centre of mass"))
        if samples:
            # Links fixed to the root add the same constant to `pot` at every q.
            first = samples[0]
            note("V", close(potential - first["V"], pot - first_pot, 1e-12,
                            "change of computePotentialEnergy vs of the links' weight x height"))
        else:
            first_pot = pot
        note("tau = D qdd + Cqd + g", close(tau, d @ qdd + cqd + g, 1e-12, "tau = D qdd + Cqd + g"))
        note("aba", close(fd, qdd, 1e-10, "aba(q, qd, tau) vs qdd"))
        note("C qd", close(c @ qd, cqd, 1e-12, "C qd vs Cqd"))
        hh = 1e-6
        ddot = (crba(model, data, pin.integrate(model, qp, qd * hh))
                - crba(model, data, pin.integrate(model, qp, -qd * hh))) / (2 * hh)
        n_skew = ddot - 2 * c
        dd = []
        for k in range(n):
            e = np.zeros(n)
            e[k] = hh
            dd.append((crba(model, data, pin.integrate(model, qp, e))
                       - crba(model, data, pin.integrate(model, qp, -e))) / (2 * hh))
        c_fd = np.array([[sum(0.5 * (dd[k][i, j] + dd[j][i, k] - dd[i][j, k]) * qd[k]
                              for k in range(n)) for j in range(n)] for i in range(n)])
        note("C vs Christoffel of FD D", close(c, c_fd, 1e-6, "C vs Christoffel symbols of D"))
        note("Ddot - 2C skew", close(n_skew + n_skew.T, np.zeros((n, n)), 1e-6, "Ddot - 2C skew"))

        samples.append({
            "q": lists(q), "qd": lists(qd), "qdd": lists(qdd),
            "T": lists(t), "J0": lists(j0), "D": lists(d), "Cqd": lists(cqd), "C": lists(c),
            "g": lists(g), "tau": lists(tau), "fd_qdd": lists(fd), "K": kinetic, "V": potential,
            "com": lists(com), "Jcom": lists(jcom),
        })

    raw = path.read_bytes()
    joint_dynamics = []
    for name in chain:
        dyn = u.joints[name]["dynamics"]
        joint_dynamics.append({
            "name": name,
            "damping": None if dyn is None or "damping" not in dyn else float(dyn["damping"]),
            "friction": None if dyn is None or "friction" not in dyn else float(dyn["friction"]),
        })
    if robot.get("generated"):
        source = {
            "package": None,
            "version": None,
            "path": f"tests/data/urdf/{robot['urdf']}",
            "installed_as": None,
            "licence": "generated by this project (scripts/pinocchio_urdf.py --random), same "
            "licence as the project",
            "sha256": hashlib.sha256(raw).hexdigest(),
            "modified": False,
            "generated_by": f"{SCRIPT} --random",
            "urdf_seed": robot["urdf_seed"],
            "features": robot["features"],
        }
    else:
        source = {
            "package": PACKAGE,
            "version": PACKAGE_VERSION,
            "path": robot["source_path"],
            "installed_as": f"site-packages/{PACKAGE_PREFIX}/{robot['source_path'][len('robots/'):]}",
            "licence": robot["licence"],
            "sha256": hashlib.sha256(raw).hexdigest(),
            "modified": False,
        }
    out = {
        "name": robot["name"],
        "source": source,
        "urdf": robot["urdf"],
        "tip": tip,
        "base": None,
        "root_link": u.root,
        "n": n,
        "joint_names": chain,
        "joint_types": [u.joints[j]["type"] for j in chain],
        "joint_axes": [u.joints[j]["axis"] for j in chain],
        "qlim": [None if u.joints[j]["type"] == "continuous"
                 else [u.joints[j]["lower"], u.joints[j]["upper"]] for j in chain],
        "locked_joints": locked,
        "gravity": GRAVITY,
        "friction_included": False,
        "joint_dynamics": joint_dynamics,
        "sampling": {"seed": robot["seed"], "samples": robot.get("samples", SAMPLES),
                     "q": "uniform in [lower, upper]; uniform in [-pi, pi] for continuous joints",
                     "qd": [-2.0, 2.0], "qdd": [-2.0, 2.0]},
        "conventions": RANDOM_CONVENTIONS if robot.get("generated") else CONVENTIONS,
        "generator": {"script": SCRIPT, "pinocchio": pin.__version__, "numpy": np.__version__,
                      "checks_worst_relative_error": worst},
        "samples": samples,
    }
    dest = DATA / f"urdf_{robot['name']}.json"
    dest.write_text(json.dumps(out, indent=1) + "\n")
    print(f"{dest.relative_to(ROOT)}: n={n}, tip={tip}, locked={locked}")
    for k, v in worst.items():
        print(f"    {k}: {v:.2e}")


# ---------------------------------------------------------------------------------------------


def quarter_turn_forms(text):
    """Values of an rpy string that are within 1e-3 of a nonzero multiple of pi/2."""
    out = []
    if text is None:
        return out
    for tok in text.split():
        v = float(tok)
        k = round(v / (math.pi / 2))
        if k != 0 and abs(v - k * math.pi / 2) < 1e-3:
            out.append((tok, k, v - k * math.pi / 2))
    return out


def summary(robot):
    path = URDF_DIR / robot["urdf"]
    u = Urdf(path)
    print(f"== {robot['urdf']} (root link {u.root}, {len(u.links)} links, {len(u.joints)} joints)")
    chain = set(u.path_joints(robot["tip"]))
    types = {}
    forms = {}
    for name in u.joint_order:
        j = u.joints[name]
        types[j["type"]] = types.get(j["type"], 0) + 1
        extra = []
        if j["type"] != "fixed":
            extra.append(f"axis {j['axis_text']}")
        if j["dynamics"] is not None:
            extra.append(f"dynamics {j['dynamics']}")
        if j["mimic"] is not None:
            extra.append(f"mimic {j['mimic']}")
        if j["type"] in MOVABLE:
            extra.append(f"limit [{j['lower']}, {j['upper']}]")
        print(f"  {'*' if name in chain else ' '} {name:40s} {j['type']:10s} rpy={j['rpy_text']!s:35s} "
              + "; ".join(extra))
        for tok, k, err in quarter_turn_forms(j["rpy_text"]):
            forms.setdefault(tok, [k, err, 0])[2] += 1
    # Inertial and visual/collision origins, for completeness.
    other = {}
    for l in u.links.values():
        for o in l.iter("origin"):
            for tok, k, err in quarter_turn_forms(o.get("rpy")):
                other.setdefault(tok, [k, err, 0])[2] += 1
    print(f"  joint types: {types}")
    axes = sorted({u.joints[n]['axis_text'] for n in u.joint_order if u.joints[n]['type'] in MOVABLE})
    print(f"  movable-joint axes: {axes}")
    print("  joint-origin rpy values near k*pi/2 (text, k, value - k*pi/2, count):")
    for tok, (k, err, cnt) in sorted(forms.items(), key=lambda x: (x[1][0], x[0])):
        print(f"    {tok:>22s}  k={k:+d}  {err:+.3e}  x{cnt}")
    if other:
        print("  link (inertial/visual/collision) origin rpy values near k*pi/2:")
        for tok, (k, err, cnt) in sorted(other.items(), key=lambda x: (x[1][0], x[0])):
            print(f"    {tok:>22s}  k={k:+d}  {err:+.3e}  x{cnt}")


def copy():
    import importlib.metadata as md
    import site
    version = md.version(PACKAGE)
    check(version == PACKAGE_VERSION, f"{PACKAGE} {version} installed, expected {PACKAGE_VERSION}")
    prefix = None
    for sp in site.getsitepackages():
        if (Path(sp) / PACKAGE_PREFIX).is_dir():
            prefix = Path(sp) / PACKAGE_PREFIX
    check(prefix is not None, f"no {PACKAGE_PREFIX} in site-packages")
    URDF_DIR.mkdir(parents=True, exist_ok=True)
    for robot in ROBOTS:
        src = prefix / robot["source_path"][len("robots/"):]
        shutil.copyfile(src, URDF_DIR / robot["urdf"])
        print(f"{src} -> {(URDF_DIR / robot['urdf']).relative_to(ROOT)}")
    # The licence texts that come with the files: the package's own, and the robots' that have one.
    licences = {"LICENSE.example-robot-data": Path(md.distribution(PACKAGE).locate_file(
        f"example_robot_data-{PACKAGE_VERSION}.dist-info/licenses/LICENSE"))}
    for robot in ROBOTS:
        f = prefix / robot["source_path"][len("robots/"):].split("/")[0] / "LICENSE"
        if f.is_file():
            licences[f"LICENSE.{robot['name']}"] = f
    for name, src in licences.items():
        shutil.copyfile(src, URDF_DIR / name)
        print(f"{src} -> {(URDF_DIR / name).relative_to(ROOT)}")


# ---------------------------------------------------------------------------------------------
# Random robots ("URDFs from the wild"): made-up URDF files, written by a seeded generator
# (`--random`), exercising what the hand-picked files do not: negative and oblique non-unit axes,
# arbitrary origins, fixed joints in the middle of the chain (with and without <inertial>),
# locked movable branches and fixed branches with mass, a `world` root, a tool link as the tip,
# an exact pitch of +-pi/2 (the RPY gimbal case), elements in shuffled order.

RANDOM_CONVENTIONS = dict(CONVENTIONS)
RANDOM_CONVENTIONS["fields"] = CONVENTIONS["fields"].replace(
    "source: where the URDF comes from (package, version, path inside it, licence, sha256 of the "
    "file in tests/data/urdf, modified = false: the copy is byte for byte the package's file)",
    "source: where the URDF comes from: made up by scripts/pinocchio_urdf.py --random from "
    "`urdf_seed` (package, version, installed_as: null; path: the file; sha256 of the file in "
    "tests/data/urdf; modified = false: the file is the generator's output as written; features: "
    "what the file exercises)")
assert RANDOM_CONVENTIONS["fields"] != CONVENTIONS["fields"]

# Exact decimals of quarter turns (float(x) is the double nearest k*pi/2).
QUARTER_TURNS = ("1.5707963267948966", "-1.5707963267948966", "3.141592653589793",
                 "-3.141592653589793")

# Per robot: the chain's joint types and <axis> texts (joint_i moves link_i); mid_fixed: after
# link_i, fixed joints to links with (True) or without (False) <inertial>, the next joint hanging
# from the last of them; gimbal: joint_i's origin pitch, written exactly; locked: movable joints
# off the chain (name, child link, type, parent link, axis, with a fixed child with mass);
# fixed_branch: (link, parent link, with <inertial>); tool: a fixed child `tool` of the last
# link, with mass, as the tip; root "world": a fixed joint world -> base_link.
RANDOM_ROBOTS = [
    {
        "name": "random_1", "urdf": "random_1.urdf", "seed": 2101, "urdf_seed": 3101,
        "tip": "link_4", "root": "base_link", "base_inertial": True,
        "types": ["revolute", "continuous", "prismatic", "revolute"],
        "axes": ["0 0 -1", "0.3 -0.5 0.8", "1 0 0", "0 -1 0"],
        "mid_fixed": {2: [True]},
        "gimbal": {3: "1.5707963267948966"},
        "locked": [("branch_joint", "branch_link", "revolute", "link_1", "0 1 0", False)],
        "fixed_branch": [("sensor", "link_3", True)],
        "tool": False, "shuffle": False, "visuals": False, "dynamics_zero": False,
    },
    {
        "name": "random_2", "urdf": "random_2.urdf", "seed": 2102, "urdf_seed": 3102,
        "tip": "link_7", "root": "world", "base_inertial": True,
        "types": ["revolute", "revolute", "continuous", "prismatic", "revolute", "continuous",
                  "revolute"],
        "axes": ["0 0 1", "-1 0 0", "0 1 0", "-0.2 0.4 1.1", "0 -1 0", "1 1 0", "0 0 -1"],
        "mid_fixed": {2: [False], 5: [True, False]},
        "gimbal": {5: "-1.5707963267948966"},
        "locked": [("slider_joint", "slider_link", "prismatic", "link_2_fixed_1", "0 0 1", False),
                   ("pan_joint", "pan_link", "revolute", "base_link", "0 0 1", False)],
        "fixed_branch": [("camera", "link_6", True)],
        "tool": False, "shuffle": False, "visuals": False, "dynamics_zero": True,
    },
    {
        "name": "random_3", "urdf": "random_3.urdf", "seed": 2103, "urdf_seed": 3103,
        "tip": "tool", "root": "base_link", "base_inertial": False,
        "types": ["revolute", "continuous", "revolute", "revolute", "continuous", "revolute",
                  "revolute", "continuous", "revolute"],
        "axes": ["0 0 1", "0 1 0", "-1 0 0", "0 0 -1", "0.3 -0.5 0.8", "1 0 0", "0 -1 0",
                 "-0.7 0.1 0.25", "0 0 1"],
        "mid_fixed": {1: [True], 4: [False], 7: [True]},
        "gimbal": {},
        "locked": [("finger_joint", "finger_link", "prismatic", "link_9", "0 -1 0", False)],
        "fixed_branch": [("marker", "link_5", True), ("frame_5", "link_5", False)],
        "tool": True, "shuffle": True, "visuals": True, "dynamics_zero": False,
    },
    {
        "name": "random_4", "urdf": "random_4.urdf", "seed": 2104, "urdf_seed": 3104,
        "tip": "link_12", "root": "base_link", "base_inertial": True,
        "types": ["revolute", "prismatic", "continuous", "revolute", "revolute", "continuous",
                  "revolute", "prismatic", "revolute", "continuous", "revolute", "revolute"],
        "axes": ["0 0 1", "0 0 -1", "0 1 0", "0.3 -0.5 0.8", "-1 0 0", "0 0 1", "0 -1 0",
                 "0.5 0 -0.5", "0 1 0", "-0.4 -0.9 0.2", "1 0 0", "0 0 -1"],
        "mid_fixed": {3: [True], 8: [False]},
        "gimbal": {9: "1.5707963267948966"},
        "locked": [("wrist_cam_joint", "wrist_cam_link", "revolute", "link_6", "-1 0 0", True)],
        "fixed_branch": [("payload", "link_10", True)],
        "tool": False, "shuffle": False, "visuals": True, "dynamics_zero": False,
    },
]
for _r in RANDOM_ROBOTS:
    _r["generated"] = True


def fmt(v, digits):
    """A short decimal: v to `digits` decimals, trailing zeros dropped."""
    t = f"{v:.{digits}f}"
    if "." in t:
        t = t.rstrip("0").rstrip(".")
    return "0" if t in ("-0", "") else t


def random_rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q @ np.diag(np.sign(np.diag(r)))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


class RandomUrdf:
    """Builds one random URDF's text from a spec of RANDOM_ROBOTS."""

    def __init__(self, spec):
        self.spec = spec
        self.rng = np.random.default_rng(spec["urdf_seed"])
        self.elems = []

    def angle(self, quarter=0.12, zero=0.08):
        u = self.rng.uniform()
        if u < quarter:
            return str(self.rng.choice(QUARTER_TURNS))
        if u < quarter + zero:
            return "0"
        return fmt(self.rng.uniform(-math.pi, math.pi), 6)

    def xyz(self, size=0.4, zero=0.15):
        return " ".join("0" if self.rng.uniform() < zero else fmt(self.rng.uniform(-size, size), 4)
                        for _ in range(3))

    def rpy(self, pitch=None):
        r, p, y = self.angle(), self.angle(), self.angle()
        if pitch is not None:
            # The gimbal case: pitch exactly +-pi/2, with arbitrary roll and yaw.
            r, p, y = fmt(self.rng.uniform(-3, 3), 6), pitch, fmt(self.rng.uniform(-3, 3), 6)
        return f"{r} {p} {y}"

    def inertial(self):
        rng = self.rng
        mass = fmt(rng.uniform(0.2, 5.0), 3)
        s = float(mass) * rng.uniform(0.002, 0.02)
        a, b = s * rng.uniform(0.5, 1.5), s * rng.uniform(0.5, 1.5)
        c = rng.uniform(abs(a - b) + 0.1 * min(a, b), a + b - 0.1 * min(a, b))
        r = random_rotation(rng)
        i = r @ np.diag([a, b, c]) @ r.T
        g = lambda v: f"{v:.10g}"
        xyz = " ".join(fmt(rng.uniform(-0.15, 0.15), 4) for _ in range(3))
        rpy = " ".join(fmt(rng.uniform(-math.pi, math.pi), 4) for _ in range(3))
        return (f'    <inertial>\n      <origin xyz="{xyz}" rpy="{rpy}"/>\n'
                f'      <mass value="{mass}"/>\n'
                f'      <inertia ixx="{g(i[0, 0])}" ixy="{g(i[0, 1])}" ixz="{g(i[0, 2])}" '
                f'iyy="{g(i[1, 1])}" iyz="{g(i[1, 2])}" izz="{g(i[2, 2])}"/>\n    </inertial>\n')

    def visual(self):
        rng = self.rng
        rad, length = fmt(rng.uniform(0.02, 0.06), 3), fmt(rng.uniform(0.05, 0.3), 3)
        return (f'    <visual>\n      <origin xyz="0 0 {fmt(float(length) / 2, 4)}" '
                f'rpy="1.5707963267948966 0 0"/>\n'
                f'      <geometry>\n        <cylinder radius="{rad}" length="{length}"/>\n'
                f'      </geometry>\n      <material name="grey">\n'
                f'        <color rgba="0.6 0.6 0.6 1"/>\n      </material>\n    </visual>\n'
                f'    <collision>\n      <origin xyz="0 0 0" rpy="0 0 0"/>\n      <geometry>\n'
                f'        <box size="{rad} {rad} {length}"/>\n      </geometry>\n    </collision>\n')

    def link(self, name, inertial, visual=None):
        visual = self.spec["visuals"] if visual is None else visual
        body = (self.inertial() if inertial else "") + (self.visual() if visual else "")
        self.elems.append(f'  <link name="{name}">\n{body}  </link>\n' if body
                          else f'  <link name="{name}"/>\n')

    def joint(self, name, kind, parent, child, axis=None, pitch=None, xyz=None):
        rng = self.rng
        xyz = self.xyz() if xyz is None else xyz
        t = (f'  <joint name="{name}" type="{kind}">\n'
             f'    <origin xyz="{xyz}" rpy="{self.rpy(pitch)}"/>\n'
             f'    <parent link="{parent}"/>\n    <child link="{child}"/>\n')
        if kind != "fixed":
            t += f'    <axis xyz="{axis}"/>\n'
        if kind in ("revolute", "prismatic"):
            if kind == "revolute":
                lo, hi = fmt(rng.uniform(-3.0, -0.5), 4), fmt(rng.uniform(0.5, 3.0), 4)
            else:
                lo, hi = "0", fmt(rng.uniform(0.2, 0.5), 3)
            t += (f'    <limit lower="{lo}" upper="{hi}" effort="{fmt(rng.uniform(10, 200), 1)}" '
                  f'velocity="{fmt(rng.uniform(0.5, 4), 2)}"/>\n')
        if kind != "fixed" and self.spec["dynamics_zero"]:
            t += '    <dynamics damping="0" friction="0"/>\n'
        self.elems.append(t + "  </joint>\n")

    def build(self):
        s = self.spec
        if s["root"] == "world":
            self.link("world", False, visual=False)
            # The base transform: a nonzero origin.
            self.joint("world_joint", "fixed", "world", "base_link",
                       xyz=" ".join(fmt(self.rng.uniform(0.1, 0.4) * self.rng.choice([-1, 1]), 4)
                                    for _ in range(3)))
        self.link("base_link", s["base_inertial"])
        parent = "base_link"
        n = len(s["types"])
        for i in range(1, n + 1):
            self.joint(f"joint_{i}", s["types"][i - 1], parent, f"link_{i}", s["axes"][i - 1],
                       pitch=s["gimbal"].get(i))
            self.link(f"link_{i}", True)
            parent = f"link_{i}"
            for k, with_inertial in enumerate(s["mid_fixed"].get(i, []), 1):
                check(i < n, "mid-chain fixed joints after the last link")
                self.joint(f"fixed_{i}_{k}", "fixed", parent, f"link_{i}_fixed_{k}")
                self.link(f"link_{i}_fixed_{k}", with_inertial)
                parent = f"link_{i}_fixed_{k}"
        if s["tool"]:
            self.joint("tool_joint", "fixed", f"link_{n}", "tool")
            self.link("tool", True)
        for name, child, kind, par, axis, grandchild in s["locked"]:
            self.joint(name, kind, par, child, axis)
            self.link(child, True)
            if grandchild:
                self.joint(f"{child}_fixed", "fixed", child, f"{child}_tip")
                self.link(f"{child}_tip", True)
        for child, par, with_inertial in s["fixed_branch"]:
            self.joint(f"{child}_joint", "fixed", par, child)
            self.link(child, with_inertial)
        elems = list(self.elems)
        if s["shuffle"]:
            elems = [elems[k] for k in self.rng.permutation(len(elems))]
        head = ('<?xml version="1.0"?>\n'
                # ("--" may not appear inside an XML comment.)
                f"<!-- Made-up robot, generated by {SCRIPT} (option random, urdf_seed "
                f"{s['urdf_seed']}). Not a real robot; regenerate rather than edit. -->\n"
                f'<robot name="{s["name"]}">\n')
        return head + "".join(elems) + "</robot>\n"


def features(spec):
    n = len(spec["types"])
    out = [f"{n} joints: " + ", ".join(f"{t} ({a})" for t, a in zip(spec["types"], spec["axes"]))]
    mid = sum(len(v) for v in spec["mid_fixed"].values())
    out.append(f"{mid} fixed joint(s) mid-chain: " + "; ".join(
        f"after link_{i}: " + ", ".join("link with <inertial>" if w else "massless link" for w in v)
        for i, v in sorted(spec["mid_fixed"].items())))
    for name, child, kind, par, axis, grandchild in spec["locked"]:
        out.append(f"locked {kind} {name} (axis {axis}) off {par}, child {child} with mass"
                   + (" and a fixed child with mass" if grandchild else ""))
    for child, par, w in spec["fixed_branch"]:
        out.append(f"fixed branch {child} off {par}" + (" with mass" if w else " (massless)"))
    for i, p in spec["gimbal"].items():
        out.append(f"joint_{i} origin pitch {p} (RPY gimbal case)")
    if spec["root"] == "world":
        out.append("root link world, fixed joint world_joint to base_link with a nonzero origin")
    if spec["tool"]:
        out.append("tip = tool, a fixed child with mass of the last link (tool transform)")
    if not spec["base_inertial"]:
        out.append("base_link without <inertial>")
    if spec["shuffle"]:
        out.append("<link> and <joint> elements in shuffled order")
    if spec["visuals"]:
        out.append("<visual>/<collision> elements")
    if spec["dynamics_zero"]:
        out.append('<dynamics damping="0" friction="0"> on movable joints')
    out.append("some rpy written as exact quarter-turn decimals "
               "(1.5707963267948966, -3.141592653589793, ...)")
    return out


def near_quarter_turns(u):
    """Joint-origin rpy values: (exact nonzero quarter turns, offsets 0 < |v - k pi/2| < 1e-9)."""
    exact, tiny = [], []
    for name in u.joint_order:
        for v in u.joints[name]["rpy"]:
            k = round(v / (math.pi / 2))
            off = abs(v - k * math.pi / 2)
            if off == 0 and k != 0:
                exact.append((name, v))
            elif 0 < off < 1e-9:
                tiny.append((name, v, off))
    return exact, tiny


def check_random_urdf(spec, u):
    """What the generator promises: every moving link and locked child has a valid <inertial>."""
    inert = {name: (m, ic) for name, m, c, ic in u.inertials()}
    for name, m, ic in ((k, v[0], v[1]) for k, v in inert.items()):
        ev = np.linalg.eigvalsh(ic)
        check(0.2 <= m <= 5.0, f"{name}: mass {m}")
        check(ev[0] > 0 and ev[0] + ev[1] > ev[2] * (1 + 1e-6),
              f"{name}: inertia eigenvalues {ev} not positive / triangle")
    for i in range(1, len(spec["types"]) + 1):
        check(f"link_{i}" in inert, f"link_{i} has no <inertial>")
    for name in u.joint_order:
        check(u.joints[name]["dynamics"] in (None, {"damping": "0", "friction": "0"}),
              f"{name}: nonzero <dynamics>")


def random_robots():
    URDF_DIR.mkdir(parents=True, exist_ok=True)
    for spec in RANDOM_ROBOTS:
        spec["features"] = features(spec)
        text = RandomUrdf(spec).build()
        path = URDF_DIR / spec["urdf"]
        path.write_text(text)
        u = Urdf(path)
        check(u.root == ("world" if spec["root"] == "world" else "base_link"), "root link")
        check_random_urdf(spec, u)
        generate(spec)
        exact, tiny = near_quarter_turns(u)
        print(f"    joint-origin rpy: {len(exact)} exact quarter-turn value(s) "
              f"({sorted({v for _, v in exact})}); max nonzero offset < 1e-9 from k*pi/2: "
              + (f"{max(o for _, _, o in tiny):.3e} ({tiny})" if tiny else "none"))


def main():
    if "--copy" in sys.argv:
        copy()
        return
    if "--summary" in sys.argv:
        for robot in ROBOTS + RANDOM_ROBOTS:
            if (URDF_DIR / robot["urdf"]).is_file():
                summary(robot)
        return
    if pin.__version__ != "4.1.0":
        print(f"warning: Pinocchio {pin.__version__}; the files were made with 4.1.0", file=sys.stderr)
    if "--random" in sys.argv:
        random_robots()
        return
    for robot in ROBOTS:
        generate(robot)


if __name__ == "__main__":
    main()

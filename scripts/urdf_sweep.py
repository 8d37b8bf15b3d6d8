#!/usr/bin/env python3
"""Compare `dhgen eval` with Pinocchio on every URDF file of example-robot-data 6.0.0.

For each file the sweep asks `dhgen info` which chain it takes without --tip, then evaluates a
set of chains with `dhgen eval --json --derivatives` at seeded random states and compares T, J, D,
C, g and tau with Pinocchio's (and, since 2026-12-05, the tool's Jacobian in its own axes, Jb,
with getFrameJacobian(LOCAL) and J̇_b q̇, Jb_dot_qd, with getFrameJacobianTimeVariation(LOCAL)
times qd; the scale of J̇_b q̇'s error also |Jb| |qd|²), and the derivatives of the dynamics with Pinocchio's
computeRNEADerivatives and computeABADerivatives. The chains of a file are: the one dhgen takes by default (when it takes one),
up to 6 root-to-leaf chains (the longest, then other joint sets), one leaf whose chain holds a
<mimic> joint and one with no movable joint (both must be refused), and two --base chains on
the longest chain (the base just after its first joint, and at the link its middle joint hangs
from). With --extended: every leaf, 8 states per chain instead of 3, and --base at every link of
the longest chain. Joint values are drawn within the joint limits (continuous joints, and joints
without usable limits, in [-pi, pi], or [-0.2, 0.2] m for prismatic ones); qd and qdd in [-1, 1].

What a chain means (dhgen's URDF semantics, which scripts/pinocchio_urdf.py's reference follows):
  - the robot's joints are the revolute, continuous and prismatic joints on the path from the
    base link (the root link, or --base) to --tip, base first; fixed joints are merged;
  - every other movable joint is locked at 0, its subtree rigidly attached and its inertia
    counted, as pinocchio.buildReducedModel at pinocchio.neutral does;
  - gravity is [0, 0, -9.81] in the root link's frame, with or without --base;
  - with --base, the base link stays where the locked joints above it put it, and T and J are
    in the base link's frame: the reference is inv(oMf[base]) oMf[tip], and Pinocchio's
    LOCAL_WORLD_ALIGNED Jacobian at the tip rotated by the base's R^T;
  - tau includes the URDF's <dynamics damping friction> as damping * qd + friction * sign(qd);
    Pinocchio's rnea omits them, so they are added to its tau (D, C and g have none);
  - C is the Christoffel-symbol matrix: half of d(rnea)/d(qd) at qdd = 0;
  - Pinocchio holds a continuous joint as (cos q, sin q) (nq = 2, nv = 1), and is given q so;
  - dhgen reads the files with --snap 0, so no angle is read as an exact quarter turn and both
    sides use the same numbers.
Pinocchio's buildReducedModel fails on frame-name clashes (z1: a fixed joint and its child link
both named `gripperStator`; anymal_c: a link and a joint both named `RH_KFE`). The sweep renames
the clashing frame it never looks up: the fixed joint's, or the link's BODY frame, which it then
looks up under the new name.

The derivatives: dtau_dq and dtau_dqd at (q, qd, qdd), with the URDF's damping on the diagonal
of dtau_dqd (Coulomb friction's derivative is 0 away from qd = 0); dqdd_dq, dqdd_dqd and Minv
at the tau whose accelerations are qdd, taken from Pinocchio's ABA derivatives at its
friction-free rnea(q, qd, qdd), with -Minv * damping added to dqdd_dqd. Where the chain's D is
singular (a massless link at its end: D's smallest eigenvalue at most 1e-12 of its largest),
dhgen's forward dynamics, and so its dqdd_dq, dqdd_dqd and Minv, must be absent.

Tolerance: for each quantity, max |dhgen - Pinocchio| <= 1e-9 * its scale: max(max |Pinocchio|,
1e-6) for T, J, D and tau; for g, also a bound on gravity's torques (|gravity| * the chain's
mass * its joint placements' and largest centre of mass offset's lengths: where the axes left
are vertical, g is zero: exactly so in dhgen, which reads 1.5707963267948966, the double nearest
pi/2, as a quarter turn even under --snap 0, and to rounding in Pinocchio); for C, also |D| * |qd| (its size where its
entries cancel); for dtau_dq, also the size of the torques it is the rate of
(max |tau|, |g|, |D| * |qdd|: where gravity's rate cancels to nothing, as on a wheel, the
rounding of those terms is what is left); for dtau_dqd, also |D| * |qd| (2C's); for dqdd_dq and dqdd_dqd, also max |Minv| times the
scale of dtau_dq or dtau_dqd (the rounding of the product -Minv * dtau). For dqdd_dq, dqdd_dqd
and Minv the bound is max(1e-9, cond(D) * 1e-14) rather than 1e-9: the inverse of a matrix known
to rounding is known only to its condition number times that (iCub's neck, whose last link
weighs almost nothing, has cond(D) = 1.9e8, and both sides' Minv differ by 2.9e-8). Pinocchio's T is
itself checked against the independent numpy forward kinematics of scripts/pinocchio_urdf.py
(to 1e-10).

A refusal by dhgen is expected only when EXPECTED_REFUSALS below describes it (each entry with
its reason). The exit code is 0 when every chain passes and every refusal is expected, 1
otherwise (a failing chain, an unexpected refusal, a chain dhgen accepts although it has a mimic
joint or no movable joint, a crash, a file Pinocchio cannot read that dhgen does not refuse as
expected, an error of the reference).

    pip install pin example-robot-data==6.0.0
    cargo build --release -p dhgen-cli
    python3 scripts/urdf_sweep.py                     # 3 states per chain (~10 s)
    python3 scripts/urdf_sweep.py --extended          # more chains and states (~1 min)
    python3 scripts/urdf_sweep.py --only panda --out /tmp/sweep --seed 7

urdfdom prints "Error: No name given for the robot." on reading ur3.urdf (see EXPECTED_REFUSALS).
The results (one JSON record per file and chain) go to results.jsonl (results_extended.jsonl
with --extended) in --out, by default a new temporary directory. DHGEN=/path/to/dhgen runs
another binary than target/release/dhgen; --robots DIR reads the URDF files from DIR instead of
the installed example-robot-data.

A second corpus: the 1,095 URDF files of pybullet 3.2.7's pybullet_data (`pip download pybullet
--no-deps --only-binary=:all:`, unzip the wheel, --robots .../pybullet_data). 2026-12-01: 179
chains pass, 0 fail; the 12 problems it reports are refusals outside EXPECTED_REFUSALS, each
with its reason: 11 files Pinocchio cannot read either (an XML declaration not at the start,
xacro's `$(optenv ...)` left in, comma-separated or four-number <origin>, a `spherical` joint, no
<link>), and cube_no_rotation.urdf's reversed limits (lower > upper, Bullet's "no limits").
2026-12-02, with the derivatives: 179 chains pass (257 with --extended), 0 fail.

A third corpus: random arms, written by dhgen and exported by it as URDF, for Pinocchio to read
(general and industrial arms of 1 to 14 joints, prismatic joints among them):

    for style in general industrial; do for n in 1 2 3 5 6 7 8 9 10 12 14; do for s in 1 2; do
      f=/tmp/arms/${style}_${n}_$s; dhgen random --dof $n --style $style --seed $((n*10+s)) \
        -o $f.toml && dhgen convert $f.toml --to urdf -o $f.urdf; done; done; done
    python3 scripts/urdf_sweep.py --extended --robots /tmp/arms

2026-12-02: 352 chains pass (the 44 arms with --base at every link), 0 fail; worst 3.2e-13 (tau)
and 4.5e-12 (Minv).
"""
import argparse
import importlib.metadata
import importlib.util
import json
import math
import os
import re
import site
import subprocess
import sys
import tempfile
import time
from collections import Counter, namedtuple
from pathlib import Path

import numpy as np

try:
    import pinocchio as pin
except ImportError:
    sys.exit("Pinocchio is not installed: pip install pin example-robot-data==6.0.0")

ROOT = Path(__file__).resolve().parent.parent
ROBOTS_IN_SITE_PACKAGES = Path("cmeel.prefix/share/example-robot-data/robots")
PACKAGE_VERSION = "6.0.0"

TOL = 1e-9
FK_TOL = 1e-10
GRAVITY = np.array([0.0, 0.0, -9.81])
DERIVATIVES = ("dtau_dq", "dtau_dqd", "dqdd_dq", "dqdd_dqd", "Minv")
FORWARD = ("dqdd_dq", "dqdd_dqd", "Minv")
SINGULAR = 1e-12  # D's smallest eigenvalue over its largest, at or below which D is singular
CONDITIONED = 1e-14  # the forward derivatives' tolerance per unit of D's condition number
DYNAMICS = ("D", "C", "g", "tau") + DERIVATIVES
QUANTITIES = ("T", "J", "Jb", "Jb_dot_qd") + DYNAMICS

sys.dont_write_bytecode = True  # no __pycache__ in the repository
_spec = importlib.util.spec_from_file_location("pinocchio_urdf",
                                               ROOT / "scripts" / "pinocchio_urdf.py")
pu = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(pu)
MOVABLE = pu.MOVABLE


class ReferenceFailure(Exception):
    """A check of scripts/pinocchio_urdf.py, or of the reference here, does not hold."""


def _raise(msg):
    raise ReferenceFailure(msg)


pu.fail = _raise  # pinocchio_urdf's check() would otherwise exit the process


# ---------------------------------------------------------------------------------------------
# Refusals dhgen is expected to make. `file` limits an entry to one file (relative to the robots
# directory); `applies(ctx, match)` confirms it from the sweep's own reading of the URDF, where
# ctx.chain is the chain's movable joints, or None for `dhgen info` without --tip.

Expected = namedtuple("Expected", "file pattern applies reason")
Context = namedtuple("Context", "u chain")


def _has_movable(u):
    return any(j["type"] in MOVABLE for j in u.joints.values())


def _moved_by_chain(ctx, link):
    return bool(ctx.chain) and any(j in ctx.chain for j in ctx.u.path_joints(link))


EXPECTED_REFUSALS = [
    Expected(None, r"joint `([^`]+)` on the chain from `[^`]*` to `[^`]*` is a mimic joint",
             lambda c, m: bool(c.chain) and m[1] in c.chain
             and c.u.joints[m[1]]["mimic"] is not None,
             "a genuine <mimic> joint on the chain: dhgen reads independent joints only"),
    Expected(None, r"no movable joint between `",
             lambda c, m: c.chain == [],
             "no movable joint on the chain"),
    Expected(None, r"no movable joint below link `",
             lambda c, m: c.chain is None and c.u is not None and not _has_movable(c.u),
             "no movable joint in the file"),
    Expected(None, r"the file is a tree with \d+ ends",
             lambda c, m: c.chain is None,
             "a tree with several ends and no --tip: the end of the chain must be named"),
    Expected("romeo_description/urdf/romeo_laas_small.urdf",
             r"link `([LR]HipPitch_link)` <inertial> <inertia>: inertia tensor is not positive "
             r"semi-definite \(principal moments -0\.002[78]",
             lambda c, m: _moved_by_chain(c, m[1]),
             "a moving body with a non-positive-semi-definite inertia (principal moment "
             "-0.0027 / -0.0028): dhgen refuses unphysical inertia by design"),
    Expected("iris_description/robots/iris.urdf",
             r"joint `(iris__rotor_\d_joint)` <limit lower>: angle -1e16 rad is outside the range",
             lambda c, m: bool(c.chain) and m[1] in c.chain,
             "a rotor joint on the chain with limits of ±1e16 rad, outside the description "
             "format's angle range"),
    Expected("ur_description/urdf/ur3.urdf", r"the robot has no <link>",
             lambda c, m: True,
             "an empty xacro shell (no <link>), which Pinocchio cannot read either"),
]


def expected_refusal(rel_name, err, ctx):
    """The entry of EXPECTED_REFUSALS that explains dhgen's message `err`, or None."""
    for e in EXPECTED_REFUSALS:
        if e.file not in (None, rel_name):
            continue
        m = re.search(e.pattern, err)
        if m and e.applies(ctx, m):
            return e
    return None


# ---------------------------------------------------------------------------------------------
# Set-up: where things are.


def find_robots():
    dirs = site.getsitepackages() + [site.getusersitepackages()]
    for d in dirs:
        robots = Path(d) / ROBOTS_IN_SITE_PACKAGES
        if robots.is_dir():
            try:
                version = importlib.metadata.version("example-robot-data")
            except importlib.metadata.PackageNotFoundError:
                version = "(version unknown)"
            if version != PACKAGE_VERSION:
                print(f"warning: example-robot-data {version}; EXPECTED_REFUSALS is for "
                      f"{PACKAGE_VERSION}", file=sys.stderr)
            return robots
    sys.exit(f"example-robot-data's robots not found (looked for {ROBOTS_IN_SITE_PACKAGES} in "
             f"{', '.join(dirs)}): pip install pin example-robot-data==6.0.0, or give --robots DIR")


def find_dhgen():
    if os.environ.get("DHGEN"):
        dhgen = Path(os.environ["DHGEN"])
        if not dhgen.is_file():
            sys.exit(f"DHGEN={dhgen}: no such file")
        return dhgen
    dhgen = ROOT / "target" / "release" / "dhgen"
    if not dhgen.is_file():
        sys.exit(f"{dhgen} is missing: build it with `cargo build --release -p dhgen-cli` in "
                 f"{ROOT} (or name another binary with DHGEN=/path/to/dhgen)")
    return dhgen


# ---------------------------------------------------------------------------------------------
# The chains of a file, and the states.


def path_between(u, base, tip):
    """Joint names from link `base` down to link `tip`, base first."""
    out, link = [], tip
    while link != base:
        j = u.parent_joint[link]
        out.append(j)
        link = u.joints[j]["parent"]
    return out[::-1]


def leaves_of(u):
    parents = {u.joints[n]["parent"] for n in u.joint_order}
    return [l for l in u.links if l not in parents]


def pick_chains(u, rng, extended):
    """The (label, base or None, tip) chains of a file (see the module's docstring)."""
    max_leaves = math.inf if extended else 6
    info = []
    for leaf in leaves_of(u):
        p = u.path_joints(leaf)
        mov = [j for j in p if u.joints[j]["type"] in MOVABLE]
        info.append((leaf, p, mov, any(u.joints[j]["mimic"] is not None for j in mov)))
    good = [x for x in info if x[2] and not x[3]]
    mimic = [x for x in info if x[2] and x[3]]
    none = [x for x in info if not x[2]]
    if len(good) <= max_leaves:
        chosen = good
    else:
        longest = sorted(good, key=lambda x: (-len(x[2]), x[0]))[0]
        chosen, seen = [longest], {tuple(longest[2])}
        rest = [good[i] for i in rng.permutation(len(good))]
        for x in rest:  # other joint sets first, then other leaves
            if len(chosen) < max_leaves and tuple(x[2]) not in seen:
                chosen.append(x)
                seen.add(tuple(x[2]))
        for x in rest:
            if len(chosen) < max_leaves and x not in chosen:
                chosen.append(x)
    out = [("leaf", None, x[0]) for x in chosen]
    if mimic:
        out.append(("mimic-leaf", None, min(x[0] for x in mimic)))
    if none:
        out.append(("nomovable-leaf", None, min(x[0] for x in none)))
    if good:
        leaf, p, mov, _ = max(good, key=lambda x: (len(x[2]), x[0]))
        if len(mov) >= 2:
            after_first = u.joints[mov[0]]["child"]
            out.append(("base-after-j1", after_first, leaf))
            mid = u.joints[mov[len(mov) // 2]]["parent"]
            if mid != after_first:
                out.append(("base-mid", mid, leaf))
        if extended:
            for j in p:
                b = u.joints[j]["child"]
                if b != leaf and b not in [x[1] for x in out]:
                    out.append(("base-every", b, leaf))
    return out


def limits(u, name):
    j = u.joints[name]
    if j["type"] == "continuous" or j["lower"] is None or j["upper"] is None \
            or not j["lower"] < j["upper"]:
        return (-0.2, 0.2) if j["type"] == "prismatic" else (-math.pi, math.pi)
    return j["lower"], j["upper"]


def sample(rng, u, chain):
    q = np.array([rng.uniform(*limits(u, j)) for j in chain])
    return q, rng.uniform(-1, 1, len(chain)), rng.uniform(-1, 1, len(chain))


# ---------------------------------------------------------------------------------------------
# Pinocchio's reference.


def dedupe_frames(model):
    """Rename the clashing frames buildReducedModel trips on (see the module's docstring).
    Returns the model and {link name: its BODY frame's new name}."""
    names = [f.name for f in model.frames]
    joints = set(model.names)
    renamed = {}
    for i, f in enumerate(model.frames):
        if names.count(f.name) < 2:
            continue
        if f.name in joints and f.type == pin.FrameType.BODY:
            renamed[f.name] = f"{f.name}__link"
            f.name = renamed[f.name]
        elif f.name not in joints and f.type != pin.FrameType.BODY:
            f.name = f"{f.name}__{str(f.type).split('.')[-1]}_{i}"
        else:
            continue
        model.frames[i] = f
    return model, renamed


class Reference:
    """Pinocchio's reduced model of one chain, and its values at a state."""

    def __init__(self, full, u, chain, base, tip):
        full, renamed = dedupe_frames(full.copy())
        locked = [full.getJointId(full.names[i]) for i in range(1, full.njoints)
                  if full.names[i] not in chain]
        model = pin.buildReducedModel(full, locked, pin.neutral(full))
        names = [model.names[i] for i in range(1, model.njoints)]
        if names != chain:
            raise ReferenceFailure(f"reduced model's joints {names} != chain {chain}")
        if any(model.parents[i] != i - 1 for i in range(1, model.njoints)):
            raise ReferenceFailure("reduced model is not a chain")
        model.gravity.linear = GRAVITY
        self.model, self.data, self.u, self.chain = model, model.createData(), u, chain
        self.locked = len(locked)
        # A bound on gravity's torques: all the mass at the farthest a chain of these joint
        # placements and centres of mass can put it from an axis.
        reach = sum(np.linalg.norm(p.translation) for p in model.jointPlacements) \
            + max(np.linalg.norm(i.lever) for i in model.inertias)
        self.static = float(np.linalg.norm(GRAVITY) * pin.computeTotalMass(model) * reach)
        self.tip = self._body_frame(renamed.get(tip, tip))
        self.base = None if base is None else self._body_frame(renamed.get(base, base))
        if self.base is not None and model.frames[self.base].parentJoint != 0:
            raise ReferenceFailure(f"base link {base} moves in the reduced model")
        dyn = [u.joints[j]["dynamics"] or {} for j in chain]
        self.damping = np.array([float(d.get("damping") or 0) for d in dyn])
        self.friction = np.array([float(d.get("friction") or 0) for d in dyn])

    def _body_frame(self, name):
        if not self.model.existFrame(name, pin.FrameType.BODY):
            raise ReferenceFailure(f"no BODY frame {name}")
        return self.model.getFrameId(name, pin.FrameType.BODY)

    def values(self, q, qd, qdd):
        model, data, n = self.model, self.data, len(self.chain)
        qp = pu.to_pin_q(model, self.u, self.chain, q)
        pin.forwardKinematics(model, data, qp)
        pin.updateFramePlacements(model, data)
        pin.computeJointJacobians(model, data, qp)
        T = data.oMf[self.tip].homogeneous.copy()
        J = pin.getFrameJacobian(model, data, self.tip, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        J = np.asarray(J).reshape(6, n)  # eigenpy returns a 6x1 Jacobian as a flat (6,) array
        # The tool's Jacobian in its own axes and J̇_b q̇ (neither depends on the base).
        Jb = np.asarray(pin.getFrameJacobian(model, data, self.tip, pin.ReferenceFrame.LOCAL))
        Jb = Jb.reshape(6, n)
        pin.computeJointJacobiansTimeVariation(model, data, qp, qd)
        Jb_dot = pin.getFrameJacobianTimeVariation(model, data, self.tip, pin.ReferenceFrame.LOCAL)
        Jb_dot_qd = np.asarray(Jb_dot).reshape(6, n) @ qd
        if self.base is not None:
            Tb = data.oMf[self.base].homogeneous.copy()
            T = np.linalg.inv(Tb) @ T
            R = Tb[:3, :3].T
            J = np.vstack([R @ J[:3], R @ J[3:]])
        D = pu.sym(pin.crba(model, data, qp).copy())
        g = pin.computeGeneralizedGravity(model, data, qp).copy()
        tau = pin.rnea(model, data, qp, qd, qdd).copy() + self.damping * qd \
            + self.friction * np.sign(qd)
        _, dtau_dqd, _ = pin.computeRNEADerivatives(model, data, qp, qd, np.zeros(n))
        C = 0.5 * np.array(dtau_dqd)
        # The derivatives at the state itself, and forward dynamics' at the τ whose
        # accelerations are qdd (dhgen's τ adds friction, which both sides then take away).
        viscous = np.diag(self.damping)
        dtau_dq, dtau_dv, _ = (np.array(m) for m in
                               pin.computeRNEADerivatives(model, data, qp, qd, qdd))
        tau_pin = pin.rnea(model, data, qp, qd, qdd).copy()
        dqdd_dq, dqdd_dv, minv = (np.array(m) for m in
                                  pin.computeABADerivatives(model, data, qp, qd, tau_pin))
        minv = pu.sym(minv)
        return {"T": T, "J": J, "Jb": Jb, "Jb_dot_qd": Jb_dot_qd, "D": D, "C": C, "g": g, "tau": tau, "qd": qd, "qdd": qdd,
                "static": self.static, "dtau_dq": dtau_dq, "dtau_dqd": dtau_dv + viscous,
                "dqdd_dq": dqdd_dq, "dqdd_dqd": dqdd_dv - minv @ viscous, "Minv": minv}


def amax(a):
    a = np.asarray(a, float)
    return float(np.max(np.abs(a))) if a.size else 0.0


def rel_error(a, b, scale=0.0):
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape:
        return math.inf
    if not a.size:
        return 0.0
    return float(np.max(np.abs(a - b))) / max(amax(b), scale, 1e-6)


def scales(r):
    """The scale each quantity's error is judged against, beyond its own size (docstring)."""
    torques = max(amax(r["tau"]), amax(r["g"]), amax(r["D"]) * amax(r["qdd"]))
    dq = max(amax(r["dtau_dq"]), torques)
    dqd = max(amax(r["dtau_dqd"]), amax(r["D"]) * amax(r["qd"]))
    minv = amax(r["Minv"])
    return {"Jb_dot_qd": amax(r["Jb"]) * amax(r["qd"]) ** 2, "g": r["static"], "C": amax(r["D"]) * amax(r["qd"]), "dtau_dq": dq, "dtau_dqd": dqd,
            "dqdd_dq": minv * dq, "dqdd_dqd": minv * dqd}


def condition(D):
    """D's condition number (inf where D is singular by SINGULAR's rule)."""
    e = np.linalg.eigvalsh(np.asarray(D, float))
    return math.inf if e[0] <= SINGULAR * e[-1] else float(e[-1] / e[0])


# ---------------------------------------------------------------------------------------------
# The sweep.


class Sweep:
    def __init__(self, dhgen, robots, nstates):
        self.dhgen, self.robots, self.nstates = dhgen, robots, nstates

    def run(self, args):
        p = subprocess.run([str(self.dhgen)] + args, capture_output=True, text=True, timeout=120)
        return p.returncode, p.stdout, p.stderr.strip()

    @staticmethod
    def refusal(rec, rc, err, ctx):
        """Record dhgen's refusal in rec; returns the EXPECTED_REFUSALS entry explaining it."""
        rec["rc"], rec["err"] = rc, err[:2000]
        if rc != 1:  # 1 is dhgen's refusal; anything else is a crash or a usage error
            rec["status"] = "crash"
            return None
        e = expected_refusal(rec["file"], err, ctx)
        rec["status"] = "refused"
        rec["expected"] = e.reason if e else None
        return e

    def check_chain(self, path, u, full, label, base, tip, rng):
        rel_name = str(path.relative_to(self.robots))
        rec = {"file": rel_name, "label": label, "base": base, "tip": tip}
        chain = [j for j in path_between(u, base or u.root, tip) if u.joints[j]["type"] in MOVABLE]
        rec["chain"] = chain
        args = [str(path), "--tip", tip, "--snap", "0"] + (["--base", base] if base else [])
        rc, _, err = self.run(eval_args(args, np.zeros(max(len(chain), 1))))
        if rc != 0:
            self.refusal(rec, rc, err, Context(u, chain))
            return rec
        if not chain or any(u.joints[j]["mimic"] is not None for j in chain):
            rec["status"] = "accepted-unexpectedly"
            return rec
        ref = Reference(full, u, chain, base, tip)
        rec["locked"] = ref.locked
        worst, failed = {}, []
        for _ in range(self.nstates):
            q, qd, qdd = sample(rng, u, chain)
            state = {"q": q.tolist(), "qd": qd.tolist(), "qdd": qdd.tolist()}
            rc, out, err = self.run(eval_args(args, q, qd, qdd))
            if rc != 0:
                failed.append(dict(state, bad=[f"dhgen exited with {rc}: {err[:500]}"]))
                continue
            d = json.loads(out)
            r = ref.values(q, qd, qdd)
            poses = u.link_poses(dict(zip(chain, q)))
            T_numpy = poses[tip] if base is None else np.linalg.inv(poses[base]) @ poses[tip]
            if rel_error(r["T"], T_numpy) > FK_TOL:
                raise ReferenceFailure(f"Pinocchio's T disagrees with numpy's forward kinematics "
                                       f"by {rel_error(r['T'], T_numpy):.2e}")
            bad = []
            scale = scales(r)
            kappa = condition(r["D"]) if "D" in d else 1.0
            d_singular = kappa == math.inf
            if d_singular:
                rec["singular_D"] = rec.get("singular_D", 0) + 1
            else:
                rec["cond_D"] = max(rec.get("cond_D", 1.0), kappa)
            for k in QUANTITIES:
                if k in FORWARD and d_singular:
                    if k in d:
                        bad.append(f"{k} given although D is singular")
                    continue
                if k not in d:
                    if not (k in DYNAMICS and d.get("has_dynamics") is False):
                        bad.append(f"{k} missing")
                    continue
                e = rel_error(d[k], r[k], scale.get(k, 0.0))
                worst[k] = max(worst.get(k, 0.0), e)
                if e > (max(TOL, kappa * CONDITIONED) if k in FORWARD else TOL):
                    bad.append(f"{k} {e:.2e}")
            if bad:
                failed.append(dict(state, bad=bad))
        rec["status"] = "FAIL" if failed else "pass"
        rec["worst"] = worst
        if failed:
            rec["failed_states"] = len(failed)
            rec["first_failure"] = failed[0]
        return rec

    def sweep_file(self, path, seed, extended):
        """The file's records: `dhgen info` without --tip first, then one per chain."""
        rel_name = str(path.relative_to(self.robots))
        rng = np.random.default_rng([seed, sum(map(ord, rel_name))])
        try:
            full, u, unreadable = pin.buildModelFromUrdf(str(path)), pu.Urdf(path), None
        except Exception as e:  # Pinocchio's or the numpy reader's error
            full, u, unreadable = None, None, f"{type(e).__name__}: {e}"[:500]
        info = {"file": rel_name, "label": "default-tip(info)", "base": None, "tip": None}
        rc, out, err = self.run(["info", str(path), "--snap", "0"])
        expected = None
        if rc == 0:
            info["status"] = "ok"
            info["info"] = next((l for l in out.splitlines() if l.startswith("URDF chain")), "")
        else:
            expected = self.refusal(info, rc, err, Context(u, None))
        if unreadable:
            # Fine only when dhgen refuses the file for a reason listed for this very file.
            info["unreadable"] = unreadable
            if expected is None or expected.file != rel_name:
                info["status"] = "unreadable"
            return [info]
        records = [info]
        chains = pick_chains(u, rng, extended)
        m = re.search(r"from link `([^`]*)` to link `([^`]*)`", info.get("info", ""))
        if m and m[1] == u.root:
            chains.insert(0, ("default-tip", None, m[2]))
        for label, base, tip in chains:
            try:
                rec = self.check_chain(path, u, full, label, base, tip, rng)
            except ReferenceFailure as e:
                rec = {"file": rel_name, "label": label, "base": base, "tip": tip,
                       "status": "ref-error", "err": str(e)[:500]}
            except Exception as e:
                rec = {"file": rel_name, "label": label, "base": base, "tip": tip,
                       "status": "script-error", "err": f"{type(e).__name__}: {e}"[:500]}
            records.append(rec)
        return records


def _floats(v):
    return ",".join(repr(float(x)) for x in v)


def eval_args(args, q, qd=None, qdd=None):
    out = ["eval"] + args + ["--q=" + _floats(q)]
    if qd is not None:
        out += ["--qd=" + _floats(qd), "--qdd=" + _floats(qdd), "--derivatives"]
    return out + ["--json"]


def is_problem(rec):
    if rec["status"] in ("ok", "pass"):
        return False
    return not (rec["status"] == "refused" and rec["expected"])


def describe(rec):
    where = f"{rec['file']} {rec['label']}"
    if rec["tip"] is not None:
        where += f" base={rec['base'] or '(root)'} tip={rec['tip']}"
    detail = rec.get("first_failure") or rec.get("unreadable") or rec.get("err") or ""
    return f"{where}: {rec['status']} {json.dumps(detail) if isinstance(detail, dict) else detail}"


def summary(records):
    """The per-file table, the tally of expected refusals and the problems; True if none."""
    files = {}
    for r in records:
        row = files.setdefault(r["file"], Counter())
        if r["label"] == "default-tip(info)":
            row["default"] = r["status"] if not is_problem(r) else r["status"].upper()
            row["unreadable"] = "unreadable" in r
        elif r["status"] == "pass":
            row["pass"] += 1
        elif r["status"] == "refused":
            row["refused"] += 1
            row["unexpected"] += not r["expected"]
        else:
            row["fail"] += 1
    width = max(len(f) for f in files)
    print(f"\n{'file':{width}}  {'default':10}  pass  fail  refused")
    total = Counter()
    for f, row in sorted(files.items()):
        total.update({k: row[k] for k in ("pass", "fail", "refused", "unexpected")})
        refused = str(row["refused"])
        if row["unexpected"]:
            refused += f" ({row['unexpected']} unexpected)"
        if row["unreadable"]:
            refused += "  (Pinocchio cannot read the file)"
        print(f"{f:{width}}  {row['default']:10}  {row['pass']:4}  {row['fail']:4}  {refused}")
    print(f"{'total':{width}}  {'':10}  {total['pass']:4}  {total['fail']:4}  {total['refused']}"
          f" ({total['unexpected']} unexpected)")
    reasons = Counter(r["expected"] for r in records if r["status"] == "refused" and r["expected"])
    if reasons:
        print("\nexpected refusals (dhgen info without --tip included):")
    for reason, n in reasons.most_common():
        print(f"  {n:4}  {reason}")
    problems = [r for r in records if is_problem(r)]
    if problems:
        print(f"\n{len(problems)} problem(s):")
        for r in problems:
            print("  " + describe(r))
    return not problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", metavar="SUBSTRING", help="only the files whose path holds this")
    ap.add_argument("--seed", type=int, default=12345, help="random seed (default 12345)")
    ap.add_argument("--extended", action="store_true",
                    help="every leaf, 8 states per chain, --base at every link of the "
                    "longest chain")
    ap.add_argument("--out", type=Path, help="directory for the results (default: a new "
                    "temporary directory)")
    ap.add_argument("--robots", type=Path, help="directory of the URDF files (default: the "
                    "installed example-robot-data's)")
    args = ap.parse_args()

    dhgen = find_dhgen()
    robots = args.robots.resolve() if args.robots else find_robots()
    files = sorted(p for p in robots.rglob("*.urdf")
                   if not args.only or args.only in str(p.relative_to(robots)))
    if not files:
        sys.exit(f"no URDF file in {robots}" + (f" matching {args.only!r}" if args.only else ""))
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        out_dir = args.out
    else:
        out_dir = Path(tempfile.mkdtemp(prefix="urdf_sweep_"))
    out_path = out_dir / ("results_extended.jsonl" if args.extended else "results.jsonl")
    print(f"dhgen: {dhgen}\nrobots: {robots} ({len(files)} files)\nresults: {out_path}")

    sweep = Sweep(dhgen, robots, 8 if args.extended else 3)
    start = time.monotonic()
    records = []
    with open(out_path, "w") as out:
        for i, path in enumerate(files, 1):
            print(f"[{i}/{len(files)}] {path.relative_to(robots)}", file=sys.stderr, flush=True)
            for rec in sweep.sweep_file(path, args.seed, args.extended):
                out.write(json.dumps(rec) + "\n")
                records.append(rec)
                if is_problem(rec):
                    print("  " + describe(rec), file=sys.stderr)
    ok = summary(records)
    print(f"\n{time.monotonic() - start:.0f} s; results in {out_path}; "
          f"{'no problem' if ok else 'PROBLEMS (exit 1)'}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()

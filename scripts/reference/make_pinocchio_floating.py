#!/usr/bin/env python3
"""Reference dynamics of floating-base robots, computed by Pinocchio.

Writes dynagen/tests/data/pinocchio_floating_<robot>.json for the bundled
quadruped12 (12 joints, Unitree A1 parameters) and torso_two_arms (14
joints, a humanoid-like upper body), each with a JointModelFreeFlyer root:
pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()).  For 10 states
(random unit quaternions, joints in [-pi, pi], |qd| of 2 and of 50), it
records Pinocchio's rnea, crba, nonLinearEffects, computeGeneralizedGravity
and aba, the world pose and WORLD/LOCAL Jacobians of one frame, the centre
of mass and the centroidal momentum matrix (ccrba).

Conventions are converted to dynagen's (shared/DESIGN.md):
- q is the same: [p, quaternion (x, y, z, w), joints];
- Pinocchio's free-flyer velocity is [v, w] (the body twist in the base
  frame, linear first); dynagen's is [w, v]: velocity-side vectors, the
  rows and columns of M and the Jacobians' columns are permuted by
  PERM = [3, 4, 5, 0, 1, 2, 6, ...], and the Jacobians' and the
  centroidal matrix's rows (linear; angular) by [3, 4, 5, 0, 1, 2];
- the base rows of tau are the wrench on the base in the base frame,
  (f, m) in Pinocchio, (m, f) in dynagen.

Not run in CI.  See README.md in this folder.
"""

from importlib import metadata

import numpy as np
import pinocchio as pin

from refcommon import DATA, REPO, dump_json, file_order

SCRIPT = "scripts/reference/make_pinocchio_floating.py"
SEED = 20261125
GRAVITY = np.array([0.0, 0.0, -9.81])
ROBOTS = {"quadruped12": "FR_foot", "torso_two_arms": "right_ee", "random_tree20": "l17"}
ANG_LIN = [3, 4, 5, 0, 1, 2]


def random_tree(rng, n):
    """A random tree of n revolute and prismatic joints with non-aligned
    axes, rotated origins, fixed links and random inertias, as URDF text."""
    out = ['<?xml version="1.0"?>', f"<!-- written by {SCRIPT} (seed {SEED}) -->", '<robot name="random_tree20">']

    def inertial():
        m = float(rng.uniform(0.5, 3.0))
        a, b = (float(v) for v in rng.uniform(0.02, 0.12, 2))
        c = abs(a - b) + float(rng.uniform(0.01, 0.06))
        x, y, z = (float(v) for v in rng.uniform(-0.1, 0.1, 3))
        r, p, w = float(rng.uniform(-3, 3)), float(rng.uniform(-1.5, 1.5)), float(rng.uniform(-3, 3))
        return (f'<inertial><origin xyz="{x!r} {y!r} {z!r}" rpy="{r!r} {p!r} {w!r}"/><mass value="{m!r}"/>'
                f'<inertia ixx="{a!r}" iyy="{b!r}" izz="{c!r}" ixy="0" ixz="0" iyz="0"/></inertial>')

    out.append(f'<link name="base">{inertial()}</link>')
    links = ["base"]
    for k in range(n + 4):
        parent = links[rng.integers(len(links))]
        kind = "fixed" if k >= n else ("prismatic" if rng.uniform() < 0.2 else "revolute")
        axis = rng.normal(size=3) if rng.uniform() < 0.5 else np.eye(3)[rng.integers(3)]
        axis = [float(v) for v in axis / np.linalg.norm(axis)]
        x, y, z = (float(v) for v in rng.uniform(-0.3, 0.3, 3))
        r, p, w = (float(v) for v in rng.uniform(-1, 1, 3))
        out.append(f'<link name="l{k}">{inertial()}</link>')
        out.append(f'<joint name="j{k}" type="{kind}"><parent link="{parent}"/><child link="l{k}"/>'
                   f'<origin xyz="{x!r} {y!r} {z!r}" rpy="{r!r} {p!r} {w!r}"/>'
                   f'<axis xyz="{axis[0]!r} {axis[1]!r} {axis[2]!r}"/>'
                   f'<limit lower="-10" upper="10" effort="100" velocity="100"/></joint>')
        links.append(f"l{k}")
    out.append("</robot>")
    return "\n".join(out) + "\n"


def states(rng, n):
    out = []
    for k in range(10):
        quat = rng.normal(size=4)
        quat /= np.linalg.norm(quat)
        q = np.concatenate([rng.uniform(-2, 2, 3), quat, rng.uniform(-np.pi, np.pi, n)])
        qd = rng.uniform(-1, 1, n + 6)
        qd *= (2.0 if k < 5 else 50.0) / np.linalg.norm(qd)
        out.append(dict(q=q, qd=qd, qdd=rng.uniform(-5, 5, n + 6), tau=rng.uniform(-10, 10, n + 6)))
    return out


def run(robot, frame_name, rng):
    if robot == "random_tree20":
        rel = f"dynagen/tests/data/{robot}.urdf"
        (REPO / rel).write_text(random_tree(rng, 20))
    else:
        rel = f"dynagen/robots/{robot}.urdf"
    model = pin.buildModelFromUrdf(str(REPO / rel), pin.JointModelFreeFlyer())
    data = model.createData()
    assert np.allclose(model.gravity.linear, GRAVITY)
    assert model.nq == model.nv + 1, "a joint with nq != nv (continuous?)"
    n = model.nv - 6
    # dynagen's joint i is Pinocchio's joint pin_names.index(name_i)
    names = file_order(REPO / rel)
    pin_names = list(model.names)[2:]
    assert sorted(names) == sorted(pin_names)
    perm = ANG_LIN + [6 + pin_names.index(name) for name in names]
    inv = np.argsort(perm)  # ours[k] = pin[perm[k]]  <=>  pin = ours[inv]
    qperm = list(range(7)) + [7 + pin_names.index(name) for name in names]
    fid = model.getFrameId(frame_name)
    records = []
    for s in states(rng, n):
        q = s["q"][np.argsort(qperm)]
        qd, qdd, tau = (s[k][inv] for k in ("qd", "qdd", "tau"))  # to Pinocchio's order
        r = {k: s[k].tolist() for k in ("q", "qd", "qdd", "tau")}
        r["tau_id"] = pin.rnea(model, data, q, qd, qdd)[perm].tolist()
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        r["M"] = M[np.ix_(perm, perm)].tolist()
        r["h"] = pin.nonLinearEffects(model, data, q, qd)[perm].tolist()
        r["g"] = pin.computeGeneralizedGravity(model, data, q)[perm].tolist()
        r["qdd_fd"] = pin.aba(model, data, q, qd, tau)[perm].tolist()
        pin.framesForwardKinematics(model, data, q)
        r["frame_pose"] = data.oMf[fid].homogeneous.tolist()
        jw = pin.computeFrameJacobian(model, data, q, fid, pin.WORLD)
        jl = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL)
        r["jacobian_world"] = jw[np.ix_(ANG_LIN, perm)].tolist()
        r["jacobian_local"] = jl[np.ix_(ANG_LIN, perm)].tolist()
        r["com"] = pin.centerOfMass(model, data, q).tolist()
        ag = pin.ccrba(model, data, q, qd)
        r["centroidal_momentum_matrix"] = ag[np.ix_(ANG_LIN, perm)].tolist()
        # internal consistency: tau = M qdd + h, aba = M^-1 (tau - h)
        h = pin.nonLinearEffects(model, data, q, qd)
        assert np.allclose(M @ qdd + h, pin.rnea(model, data, q, qd, qdd), rtol=1e-10, atol=1e-9)
        assert np.allclose(np.linalg.solve(M, tau - h), pin.aba(model, data, q, qd, tau), rtol=1e-8, atol=1e-8)
        records.append(r)
    doc = {
        "source": f"{SCRIPT} (Pinocchio {metadata.version('pin')}, numpy {np.__version__}, seed {SEED})",
        "robot": rel,
        "root": "pin.JointModelFreeFlyer()",
        "gravity": GRAVITY.tolist(),
        "joint_names": names,
        "frame": frame_name,
        "total_mass": float(sum(i.mass for i in model.inertias)),
        "states": records,
    }
    dump_json(doc, DATA / f"pinocchio_floating_{robot}.json")
    print(robot, n, "joints:", len(records), "states")


def main():
    rng = np.random.default_rng(SEED)
    for robot, frame in ROBOTS.items():
        run(robot, frame, rng)


if __name__ == "__main__":
    main()

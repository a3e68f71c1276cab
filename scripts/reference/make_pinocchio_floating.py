#!/usr/bin/env python3
"""Reference dynamics of floating-base robots, computed by Pinocchio.

Writes dynagen/tests/data/pinocchio_floating_<robot>.json for the bundled
quadruped12 (12 joints, Unitree A1 parameters), torso_two_arms (14
joints, a humanoid-like upper body), a random 20-joint tree, the
legged_manipulator (18 joints: Go1 legs, a Z1 arm) and humanoid32 (32
joints, TALOS parameters), each with a JointModelFreeFlyer root:
pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()).  For 10 states
(random unit quaternions, joints in [-pi, pi], |qd| of 2 and of 50), it
records Pinocchio's rnea, crba, nonLinearEffects, computeGeneralizedGravity
and aba, the world pose and WORLD/LOCAL Jacobians of one frame, the centre
of mass and the centroidal momentum matrix (ccrba).  For the legged
manipulator also, for each contact frame (the feet and the arm's tool):
its world pose, WORLD and LOCAL Jacobians and its classical acceleration
at qdd = 0 (getFrameClassicalAcceleration, LOCAL: the bias J'qd of a
contact constraint); and a scene: armature on every joint, constant
payloads on the trunk and the arm's last link (added to Pinocchio's joint
inertias), a tip wrench at a foot (fext), with rnea, crba,
nonLinearEffects, computeGeneralizedGravity and aba under them.

Conventions are converted to dynagen's (shared/DESIGN.md):
- q is the same: [p, quaternion (x, y, z, w), joints];
- Pinocchio's free-flyer velocity is [v, w] (the body twist in the base
  frame, linear first); dynagen's is [w, v]: velocity-side vectors, the
  rows and columns of M and the Jacobians' columns are permuted by
  PERM = [3, 4, 5, 0, 1, 2, 6, ...], and the Jacobians' and the
  centroidal matrix's rows (linear; angular) by [3, 4, 5, 0, 1, 2];
- the base rows of tau are the wrench on the base in the base frame,
  (f, m) in Pinocchio, (m, f) in dynagen;
- a tip wrench is the wrench (m; f) the frame applies to its environment,
  in the frame: Pinocchio's fext on the frame's joint is minus it, moved
  to the joint's frame.

Not run in CI.  See README.md in this folder.
"""

from importlib import metadata

import numpy as np
import pinocchio as pin

from refcommon import DATA, REPO, dump_json, file_order

SCRIPT = "scripts/reference/make_pinocchio_floating.py"
SEED = 20261125
GRAVITY = np.array([0.0, 0.0, -9.81])
ROBOTS = {"quadruped12": "FR_foot", "torso_two_arms": "right_ee", "random_tree20": "l17", "legged_manipulator": "arm_ee",
          "humanoid32": "left_sole_link"}
CONTACTS = {"legged_manipulator": ["FL_foot", "FR_foot", "RL_foot", "RR_foot", "arm_ee"]}
# The legged manipulator's scene: armature (kg m^2) on each joint by kind,
# payloads (link, mass, com, inertia ixx iyy izz ixy ixz iyz about the com,
# in the link's frame), a tip wrench (m; f) at a foot, in the foot's frame.
ARMATURE = {"hip": 0.011, "thigh": 0.012, "calf": 0.027, "arm_joint": 0.004}
PAYLOADS = [("trunk", 1.5, [0.05, -0.02, 0.04], [0.004, 0.006, 0.007, 0.0005, -0.0002, 0.0001]),
            ("arm_link06", 0.4, [0.03, 0.01, -0.01], [0.0004, 0.0005, 0.0003, 0.0, 0.00002, 0.0])]
TIP = ("FL_foot", [0.3, -0.2, 0.1, 5.0, -3.0, 40.0])
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


def classical_bias(model, data, q, qd, fid):
    """The frame's classical acceleration at qdd = 0, LOCAL, (angular; linear)."""
    pin.forwardKinematics(model, data, q, qd, np.zeros(model.nv))
    acc = pin.getFrameClassicalAcceleration(model, data, fid, pin.LOCAL)
    return np.concatenate([acc.angular, acc.linear])


def contact_records(robot, model, data, q, qd, perm):
    """Pose, WORLD and LOCAL Jacobians and J'qd of every contact frame."""
    out = {}
    for name in CONTACTS[robot]:
        fid = model.getFrameId(name)
        pin.framesForwardKinematics(model, data, q)
        jw = pin.computeFrameJacobian(model, data, q, fid, pin.WORLD)
        jl = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL)
        out[name] = {
            "pose": data.oMf[fid].homogeneous.tolist(),
            "jacobian_world": jw[np.ix_(ANG_LIN, perm)].tolist(),
            "jacobian_local": jl[np.ix_(ANG_LIN, perm)].tolist(),
            "acceleration_bias": classical_bias(model, data, q, qd, fid).tolist(),
        }
    return out


def scene_model(model):
    """The model with the scene's armature and constant payloads."""
    m = model.copy()
    arm = np.zeros(m.nv)
    for jid in range(2, m.njoints):
        kind = next(k for k in ARMATURE if k in m.names[jid])
        arm[m.joints[jid].idx_v] = ARMATURE[kind]
    m.armature = arm
    for link, mass, com, inertia in PAYLOADS:
        f = m.frames[m.getFrameId(link)]
        ixx, iyy, izz, ixy, ixz, iyz = inertia
        rot = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        payload = pin.Inertia(mass, np.array(com), rot)
        m.inertias[f.parentJoint] = m.inertias[f.parentJoint] + f.placement.act(payload)
    return m


def scene_records(model, q, qd, qdd, tau, perm):
    """rnea, crba, nonLinearEffects, gravity and aba under the scene."""
    m = scene_model(model)
    d = m.createData()
    frame, wrench = TIP
    f = m.frames[m.getFrameId(frame)]
    fext = pin.StdVec_Force()
    for _ in range(m.njoints):
        fext.append(pin.Force.Zero())
    # the robot pushes on its environment with wrench; the environment on it with -wrench
    fext[f.parentJoint] = -f.placement.act(pin.Force(np.array(wrench[3:]), np.array(wrench[:3])))
    M = pin.crba(m, d, q)
    M = np.triu(M) + np.triu(M, 1).T
    h = pin.nonLinearEffects(m, d, q, qd)
    t = pin.rnea(m, d, q, qd, qdd, fext)
    a = pin.aba(m, d, q, qd, tau, fext)
    g = pin.computeGeneralizedGravity(m, d, q)
    zero = np.zeros(m.nv)
    jtf = pin.rnea(m, d, q, zero, zero, fext) - g  # J^T wrench
    assert np.allclose(M @ qdd + h + jtf, t, rtol=1e-10, atol=1e-9)
    assert np.allclose(M @ a + h + jtf, tau, rtol=1e-8, atol=1e-8)
    return {
        "tau_id": t[perm].tolist(),
        "M": M[np.ix_(perm, perm)].tolist(),
        "h": h[perm].tolist(),
        "g": g[perm].tolist(),
        "qdd_fd": a[perm].tolist(),
    }


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
        if robot in CONTACTS:
            r["contacts"] = contact_records(robot, model, data, q, qd, perm)
            r["scene"] = scene_records(model, q, qd, qdd, tau, perm)
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
    if robot in CONTACTS:
        doc["contact_frames"] = CONTACTS[robot]
        doc["scene"] = {
            "armature": {model.names[j]: ARMATURE[next(k for k in ARMATURE if k in model.names[j])]
                         for j in range(2, model.njoints)},
            "payloads": [{"link": l, "mass": m, "com": c, "inertia": i} for l, m, c, i in PAYLOADS],
            "tip_wrench": {"frame": TIP[0], "wrench": TIP[1]},
        }
    dump_json(doc, DATA / f"pinocchio_floating_{robot}.json")
    print(robot, n, "joints:", len(records), "states")


def main():
    rng = np.random.default_rng(SEED)
    for robot, frame in ROBOTS.items():
        run(robot, frame, rng)


if __name__ == "__main__":
    main()

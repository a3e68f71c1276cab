#!/usr/bin/env python3
"""Reference dynamics of the bundled robots, computed by Pinocchio.

Writes dynagen/tests/data/pinocchio_<robot>.json for each URDF in
dynagen/robots/: for a zero state and 8 random states, Pinocchio's rnea,
crba, nonLinearEffects, computeGeneralizedGravity and aba, and the pose and
space/body Jacobians of one named frame.

For the UR5 it also runs the Modern Robotics library on the book's UR5 lists
(Mlist, Glist, Slist) at the same states and records the largest difference
from Pinocchio on ur5.urdf, which must be at rounding level; the lists
themselves are stored in the JSON under "mr_lists".

For the planar 2-link arm it checks the closed-form M, C qd and g written in
the URDF's header comment.

Not run in CI.  See README.md in this folder.
"""

import sys
import xml.etree.ElementTree as ET
from importlib import metadata

import numpy as np
import pinocchio as pin
import modern_robotics as mr

from refcommon import DATA, REPO, UR5_GLIST, UR5_MLIST, UR5_SLIST, dump_json

SCRIPT = "scripts/reference/make_pinocchio_data.py"
SEED = 20240611
N_RANDOM = 8
GRAVITY = np.array([0.0, 0.0, -9.81])

# robot name -> the frame whose pose and Jacobians are recorded
ROBOTS = {
    "ur5": "ee_link",
    "panda": "panda_tcp",
    "torso_two_arms": "right_ee",
    "planar_2link": "tip",
}

# Pinocchio orders motion vectors (linear; angular); dynagen and Modern
# Robotics use (angular; linear).  Row permutation from the one to the other:
ANG_LIN = [3, 4, 5, 0, 1, 2]


def urdf_dof_order(path):
    """Movable joints depth first over the URDF tree, children in file order.

    Also returns each joint's type and limits."""
    root = ET.parse(path).getroot()
    joints = root.findall("joint")
    children = {}
    child_links = set()
    info = {}
    for j in joints:
        parent = j.find("parent").get("link")
        child = j.find("child").get("link")
        children.setdefault(parent, []).append((j.get("name"), child))
        child_links.add(child)
        lim = j.find("limit")
        info[j.get("name")] = {
            "type": j.get("type"),
            "lower": float(lim.get("lower")) if lim is not None
            and lim.get("lower") is not None else None,
            "upper": float(lim.get("upper")) if lim is not None
            and lim.get("upper") is not None else None,
        }
    roots = [l.get("name") for l in root.findall("link")
             if l.get("name") not in child_links]
    assert len(roots) == 1, roots
    order = []

    def visit(link):
        for name, child in children.get(link, []):
            if info[name]["type"] != "fixed":
                order.append(name)
            visit(child)

    visit(roots[0])
    return order, info


def draw_states(rng, names, info):
    """The zero state, then N_RANDOM random states."""
    n = len(names)
    states = [dict(q=np.zeros(n), qd=np.zeros(n), qdd=np.zeros(n),
                   tau=np.zeros(n))]
    for _ in range(N_RANDOM):
        q = np.empty(n)
        for i, name in enumerate(names):
            if info[name]["type"] == "prismatic":
                q[i] = rng.uniform(info[name]["lower"], info[name]["upper"])
            else:
                q[i] = rng.uniform(-np.pi, np.pi)
        states.append(dict(q=q, qd=rng.uniform(-2, 2, n),
                           qdd=rng.uniform(-5, 5, n),
                           tau=rng.uniform(-10, 10, n)))
    return states


def symmetrise_upper(M):
    """crba fills the upper triangle; mirror it."""
    U = np.triu(M)
    return U + np.triu(U, 1).T


def mr_ur5_checks(states, pin_results, pose_home):
    """MR library on the book's UR5 lists versus Pinocchio on ur5.urdf."""
    diffs = {"tau": 0.0, "M": 0.0, "h": 0.0, "g": 0.0, "qdd_fd": 0.0,
             "frame_pose": 0.0, "jacobian_world": 0.0, "jacobian_local": 0.0}
    M_home = np.eye(4)
    for Mi in UR5_MLIST:
        M_home = M_home @ Mi
    Blist = mr.Adjoint(mr.TransInv(M_home)) @ UR5_SLIST
    Ml, Gl, Sl = list(UR5_MLIST), list(UR5_GLIST), UR5_SLIST
    zero6 = np.zeros(6)
    for s, r in zip(states, pin_results):
        q, qd, qdd, tau = s["q"], s["qd"], s["qdd"], s["tau"]
        n = len(q)
        got = {
            "tau": mr.InverseDynamics(q, qd, qdd, GRAVITY, zero6, Ml, Gl, Sl),
            "M": mr.MassMatrix(q, Ml, Gl, Sl),
            "h": mr.InverseDynamics(q, qd, np.zeros(n), GRAVITY, zero6,
                                    Ml, Gl, Sl),
            "g": mr.GravityForces(q, GRAVITY, Ml, Gl, Sl),
            "qdd_fd": mr.ForwardDynamics(q, qd, tau, GRAVITY, zero6,
                                         Ml, Gl, Sl),
            "frame_pose": mr.FKinSpace(M_home, Sl, q),
            "jacobian_world": mr.JacobianSpace(Sl, q),
            "jacobian_local": mr.JacobianBody(Blist, q),
        }
        for k, v in got.items():
            diffs[k] = max(diffs[k], float(np.max(np.abs(v - np.array(r[k])))))
    home_diff = float(np.max(np.abs(M_home - pose_home)))
    return diffs, home_diff


def planar_closed_form(q, qd):
    """The closed forms in planar_2link.urdf's header comment."""
    m1, m2, l1, l2, g0 = 2.0, 1.5, 1.0, 0.8, 9.81
    lc1, lc2 = l1 / 2, l2 / 2
    I1, I2 = m1 * l1 ** 2 / 12, m2 * l2 ** 2 / 12
    c1, c2 = np.cos(q[0]), np.cos(q[1])
    s2 = np.sin(q[1])
    c12 = np.cos(q[0] + q[1])
    M11 = I1 + I2 + m1 * lc1 ** 2 + m2 * (l1 ** 2 + lc2 ** 2 + 2 * l1 * lc2 * c2)
    M12 = I2 + m2 * (lc2 ** 2 + l1 * lc2 * c2)
    M22 = I2 + m2 * lc2 ** 2
    h = m2 * l1 * lc2
    Cqd = np.array([-h * s2 * (2 * qd[0] * qd[1] + qd[1] ** 2),
                    h * s2 * qd[0] ** 2])
    g = np.array([-(m1 * lc1 + m2 * l1) * g0 * c1 - m2 * lc2 * g0 * c12,
                  -m2 * lc2 * g0 * c12])
    return np.array([[M11, M12], [M12, M22]]), Cqd, g


def run(robot, frame_name, rng):
    rel = f"dynagen/robots/{robot}.urdf"
    path = REPO / rel
    model = pin.buildModelFromUrdf(str(path))  # fixed base
    data = model.createData()
    assert model.nq == model.nv, "a joint with nq != nv (continuous?)"
    assert np.allclose(model.gravity.linear, GRAVITY)
    names = list(model.names)[1:]
    file_order, info = urdf_dof_order(path)
    if names != file_order:
        sys.exit(f"{robot}: Pinocchio's joint order {names} differs from the "
                 f"depth-first file order {file_order}")
    fid = model.getFrameId(frame_name)
    assert fid < model.nframes, frame_name

    states = draw_states(rng, names, info)
    results = []
    worst = {"tau_vs_M_qdd_plus_h": 0.0, "qdd_fd_vs_solve": 0.0,
             "h_minus_g_at_zero_velocity": 0.0}
    for s in states:
        q, qd, qdd, tau = s["q"], s["qd"], s["qdd"], s["tau"]
        r = {}
        r["tau"] = pin.rnea(model, data, q, qd, qdd).copy()
        r["M"] = symmetrise_upper(pin.crba(model, data, q).copy())
        r["h"] = pin.nonLinearEffects(model, data, q, qd).copy()
        r["g"] = pin.computeGeneralizedGravity(model, data, q).copy()
        r["qdd_fd"] = pin.aba(model, data, q, qd, tau).copy()
        pin.framesForwardKinematics(model, data, q)
        r["frame_pose"] = data.oMf[fid].homogeneous.copy()
        Jw = pin.computeFrameJacobian(model, data, q, fid, pin.WORLD)
        Jl = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL)
        r["jacobian_world"] = Jw[ANG_LIN, :].copy()
        r["jacobian_local"] = Jl[ANG_LIN, :].copy()
        # internal consistency of what is recorded
        worst["tau_vs_M_qdd_plus_h"] = max(
            worst["tau_vs_M_qdd_plus_h"],
            float(np.max(np.abs(r["M"] @ qdd + r["h"] - r["tau"]))))
        worst["qdd_fd_vs_solve"] = max(
            worst["qdd_fd_vs_solve"],
            float(np.max(np.abs(np.linalg.solve(r["M"], tau - r["h"])
                                - r["qdd_fd"]))))
        h0 = pin.nonLinearEffects(model, data, q, np.zeros(model.nv))
        worst["h_minus_g_at_zero_velocity"] = max(
            worst["h_minus_g_at_zero_velocity"],
            float(np.max(np.abs(h0 - r["g"]))))
        # the body Jacobian is the space one seen from the frame
        X = mr.Adjoint(mr.TransInv(r["frame_pose"]))
        assert np.allclose(X @ r["jacobian_world"], r["jacobian_local"],
                           atol=1e-12)
        results.append(r)

    doc = {
        "robot": robot,
        "source": {
            "generator": "pinocchio",
            "pinocchio_version": pin.__version__,
            "modern_robotics_version": metadata.version("modern_robotics"),
            "numpy_version": np.__version__,
            "urdf": rel,
            "script": SCRIPT,
            "load": "pinocchio.buildModelFromUrdf(urdf) (fixed base)",
            "seed": SEED,
        },
        "notes": [
            "Spatial rows are (angular; linear), as in dynagen and Modern "
            "Robotics.  Pinocchio's motion order is (linear; angular): its "
            "Jacobians' rows were reordered [3,4,5,0,1,2] before saving.",
            "jacobian_world = pinocchio WORLD frame Jacobian = the space "
            "Jacobian of Modern Robotics (twist of the frame expressed in "
            "the base frame, linear part = velocity of the body point at the "
            "base origin); jacobian_local = pinocchio LOCAL = the body "
            "Jacobian (twist in the frame itself).  LOCAL_WORLD_ALIGNED is "
            "not used.",
            "tau = rnea(q, qd, qdd) with gravity (0,0,-9.81) and no tip "
            "wrench; M = crba(q), upper triangle mirrored; h = "
            "nonLinearEffects(q, qd) = C(q,qd) qd + g(q); g = "
            "computeGeneralizedGravity(q); qdd_fd = aba(q, qd, tau_in).",
            "frame_pose is the 4x4 pose of the named frame in the base frame.",
            "States: the first is the zero state; the next are drawn with "
            "numpy.random.default_rng(seed) in joint order: q uniform in "
            "[-pi, pi] for revolute joints and in [lower, upper] for "
            "prismatic ones (revolute limits are not applied), then qd in "
            "[-2, 2], qdd in [-5, 5], tau_in in [-10, 10].",
            "joint_names is Pinocchio's joint order, checked equal to the "
            "depth-first order of the URDF tree with children in file order.",
            "Matrices are lists of rows.",
        ],
        "joint_names": names,
        "joint_types": [info[n]["type"] for n in names],
        "nq": model.nq,
        "gravity": GRAVITY.tolist(),
        "frame": frame_name,
        "consistency_checks_max_abs": worst,
        "states": [
            {
                "q": s["q"].tolist(), "qd": s["qd"].tolist(),
                "qdd": s["qdd"].tolist(), "tau_in": s["tau"].tolist(),
                **{k: np.asarray(v).tolist() for k, v in r.items()},
            }
            for s, r in zip(states, results)
        ],
    }

    if robot == "ur5":
        pin.framesForwardKinematics(model, data, np.zeros(model.nq))
        diffs, home_diff = mr_ur5_checks(states, results,
                                         data.oMf[fid].homogeneous)
        diffs["home_pose_M07"] = home_diff
        doc["mr_vs_pinocchio_max_abs_diff"] = max(diffs.values())
        doc["mr_vs_pinocchio_max_abs_diff_by_quantity"] = diffs
        doc["mr_lists"] = {
            "source": (
                "The UR5 of Lynch & Park, Modern Robotics (2017), as given "
                "with the book's chapter-8 UR5 dynamics/simulation exercise "
                "and its code library: Mlist = [M01..M67] (link frames at "
                "the centres of mass, M67 = end-effector frame ee_link), "
                "Glist = [G1..G6], Slist 6x6 (rows (omega; v), columns "
                "joints).  The MR computations above use g = (0,0,-9.81) "
                "and Ftip = 0."),
            "Mlist": UR5_MLIST.tolist(),
            "Glist": UR5_GLIST.tolist(),
            "Slist": UR5_SLIST.tolist(),
        }
        print(f"  MR vs Pinocchio (UR5): {doc['mr_vs_pinocchio_max_abs_diff']:.3e}"
              f"  {diffs}")
        if doc["mr_vs_pinocchio_max_abs_diff"] > 1e-10:
            sys.exit("ur5.urdf is not equivalent to the MR UR5 lists")

    if robot == "planar_2link":
        worst_cf = {"M": 0.0, "Cqd": 0.0, "g": 0.0}
        for s, r in zip(states, results):
            M, Cqd, g = planar_closed_form(s["q"], s["qd"])
            worst_cf["M"] = max(worst_cf["M"], float(np.max(np.abs(M - r["M"]))))
            worst_cf["g"] = max(worst_cf["g"], float(np.max(np.abs(g - r["g"]))))
            worst_cf["Cqd"] = max(worst_cf["Cqd"], float(
                np.max(np.abs(Cqd - (r["h"] - r["g"])))))
        doc["closed_form_vs_pinocchio_max_abs_diff"] = worst_cf
        print(f"  closed form vs Pinocchio: {worst_cf}")
        if max(worst_cf.values()) > 1e-12:
            sys.exit("planar_2link closed form disagrees with Pinocchio")

    out = DATA / f"pinocchio_{robot}.json"
    dump_json(doc, out)
    print(f"{robot}: {names}; consistency {worst}; wrote "
          f"{out.relative_to(REPO)}")


def main():
    rng = np.random.default_rng(SEED)
    for robot, frame in ROBOTS.items():
        run(robot, frame, rng)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Reference dynamics, computed by Pinocchio, of robots with mimic joints.

Writes to dynagen/tests/data/:

- panda_mimic.urdf: the bundled robots/panda.urdf with the <mimic> element
  franka_description gives the second finger (panda_finger_joint2 follows
  panda_finger_joint1 with URDF's default multiplier 1 and offset 0): the
  Panda as users have it;
- gripper_mimic.urdf: a two-joint arm with a gripper linkage whose revolute
  master (c_finger) has a mimic joint below it (d_tip_l, multiplier -0.75,
  offset 0.2), two on a sibling branch (e_knuckle_r, multiplier 1, offset
  -0.1, and f_tip_r below it, multiplier -1), a prismatic one (g_slide,
  0.02 m/rad, offset 0.01 m), then an independent joint (h_cam);
- pinocchio_mimic_panda.json, pinocchio_mimic_gripper.json: Pinocchio's rnea,
  crba, nonLinearEffects and computeGeneralizedGravity with its URDF parser's
  mimic option on (buildModelFromUrdf(path, mimic=True)), and
  qdd_fd = M^-1 (tau_in - h) solved here (Pinocchio's aba refuses models with
  mimic joints), at the zero state and 8 random ones.

Each file's values are checked against Pinocchio's model of the same file
without the option (every joint independent) projected by the coupling
matrix G (tau = G^T tau_full at q_full = G q + offsets, qd_full = G qd,
M = G^T M_full G, h and g likewise); the largest difference is stored.
Not run in CI.
"""

from importlib import metadata
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin

from make_file_robots_data import GRAVITY, chain_urdf, g17, inertial, inertial_xml, joint_xml
from refcommon import DATA, REPO, dump_json

SCRIPT = "scripts/reference/make_pinocchio_mimic.py"
SEED = 20261127


def mimic_joints(text):
    """{mimic joint: (master, multiplier, offset)} of a URDF text."""
    out = {}
    for j in ET.fromstring(text).findall("joint"):
        m = j.find("mimic")
        if m is not None:
            out[j.get("name")] = (m.get("joint"), float(m.get("multiplier", "1")), float(m.get("offset", "0")))
    return out


def panda_mimic_urdf():
    text = (REPO / "dynagen" / "robots" / "panda.urdf").read_text()
    anchor = '<child link="panda_rightfinger"/>'
    assert text.count(anchor) == 1
    # franka_description's hand: <mimic joint="${arm_id}_finger_joint1" />
    return text.replace(anchor, anchor + '\n    <mimic joint="panda_finger_joint1" />')


def unit_axis(rng):
    a = rng.normal(size=3)
    return a / np.linalg.norm(a)


def gripper_mimic_urdf(rng):
    # (name, type, parent, child, xyz, rpy, axis, mimic); the children of a
    # link in the order of their joints' names, as urdfdom (Pinocchio) takes them
    joints = [
        ("a_shoulder", "revolute", "base", "upper", [0, 0, 0.1], [0, 0, 0], [0, 0, 1], None),
        ("b_elbow", "revolute", "upper", "palm", [0.05, 0, 0.3], [0.1, -0.2, 0.3], unit_axis(rng), None),
        ("c_finger", "revolute", "palm", "knuckle_l", [0, 0.03, 0.05], [0, 0, 0.4], [1, 0, 0], None),
        ("d_tip_l", "revolute", "knuckle_l", "tip_l", [0, 0.01, 0.04], [0, 0.3, 0], unit_axis(rng),
         ("c_finger", -0.75, 0.2)),
        ("e_knuckle_r", "revolute", "palm", "knuckle_r", [0, -0.03, 0.05], [0, 0, -0.4], [-1, 0, 0],
         ("c_finger", 1.0, -0.1)),
        ("f_tip_r", "revolute", "knuckle_r", "tip_r", [0, -0.01, 0.04], [0, 0, 0], [1, 0, 0], ("c_finger", -1.0, 0.0)),
        ("g_slide", "prismatic", "palm", "slider", [0.02, 0, 0.03], [0, 0, 0], [0, 1, 0], ("c_finger", 0.02, 0.01)),
        ("h_cam", "revolute", "palm", "cam", [-0.02, 0, 0.06], [0.2, 0, 0], unit_axis(rng), None),
    ]
    links = [(child, inertial_xml(*inertial(rng, rng.uniform(0.05, 1.5)))) for _, _, _, child, *_ in joints]
    out = []
    for name, jtype, parent, child, xyz, rpy, axis, mimic in joints:
        j = joint_xml(name, jtype, parent, child, xyz, rpy, axis)
        if mimic is not None:
            master, k, o = mimic
            j = j.replace("</joint>", f'<mimic joint="{master}" multiplier="{g17(k)}" offset="{g17(o)}"/></joint>')
        out.append(j)
    return chain_urdf("gripper_mimic", links, out).replace("make_file_robots_data.py", "make_pinocchio_mimic.py")


def mimic_data(name, text, rng):
    """The file, and Pinocchio's dynamics of it with mimic joints."""
    path = DATA / f"{name}_mimic.urdf"
    path.write_text(text)
    model = pin.buildModelFromUrdf(str(path), mimic=True)
    full = pin.buildModelFromUrdf(str(path))
    for m in (model, full):
        m.gravity.linear = GRAVITY
    mimics = mimic_joints(text)
    # Pinocchio's independent joints in velocity order, and every joint of the full model
    names = [nm for _, nm in sorted((model.joints[i].idx_v, model.names[i]) for i in range(1, model.njoints)
                                    if model.joints[i].nv == 1)]
    full_names = list(full.names)[1:]
    assert all(full.joints[i].nv == 1 and full.joints[i].nq == 1 for i in range(1, full.njoints))
    assert [nm for nm in full_names if nm not in mimics] == names, (full_names, names)
    n, nf = len(names), len(full_names)
    g, off = np.zeros((nf, n)), np.zeros(nf)
    for r, nm in enumerate(full_names):
        master, k, o = mimics.get(nm, (nm, 1.0, 0.0))
        g[r, names.index(master)] = k
        off[r] = o
    idx = {nm: full.joints[full.getJointId(nm)].idx_q for nm in full_names}
    prismatic = {nm: full.joints[full.getJointId(nm)].shortname().startswith("JointModelP") for nm in full_names}
    data, fdata = model.createData(), full.createData()
    states, worst = [], 0.0
    for s in range(9):
        q = np.array([rng.uniform(full.lowerPositionLimit[idx[nm]], full.upperPositionLimit[idx[nm]])
                      if prismatic[nm] else rng.uniform(-np.pi, np.pi) for nm in names])
        qd, qdd, tau = rng.uniform(-2, 2, n), rng.uniform(-5, 5, n), rng.uniform(-10, 10, n)
        if s == 0:
            q, qd, qdd, tau = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
        rnea = pin.rnea(model, data, q, qd, qdd).copy()
        m = pin.crba(model, data, q).copy()
        m = np.triu(m) + np.triu(m, 1).T
        h = pin.nonLinearEffects(model, data, q, qd).copy()
        grav = pin.computeGeneralizedGravity(model, data, q).copy()
        qdd_fd = np.linalg.solve(m, tau - h)
        # the same through the full model and G
        qf = g @ q + off
        mf = pin.crba(full, fdata, qf).copy()
        mf = np.triu(mf) + np.triu(mf, 1).T
        checks = [(rnea, g.T @ pin.rnea(full, fdata, qf, g @ qd, g @ qdd)), (m, g.T @ mf @ g),
                  (h, g.T @ pin.nonLinearEffects(full, fdata, qf, g @ qd)),
                  (grav, g.T @ pin.computeGeneralizedGravity(full, fdata, qf)), (m @ qdd_fd + h, tau)]
        for a, b in checks:
            worst = max(worst, np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1.0))
        states.append({"q": q.tolist(), "qd": qd.tolist(), "qdd": qdd.tolist(), "tau_in": tau.tolist(),
                       "tau": rnea.tolist(), "M": m.tolist(), "h": h.tolist(), "g": grav.tolist(),
                       "qdd_fd": qdd_fd.tolist()})
    assert worst < 1e-12, f"{name}: Pinocchio's mimic model and its projected full model differ by {worst}"
    source = (f"{SCRIPT}: {name}_mimic.urdf by buildModelFromUrdf(path, mimic=True); rnea, crba (upper triangle "
              f"mirrored), nonLinearEffects, computeGeneralizedGravity; qdd_fd = numpy.linalg.solve(M, tau_in - h); "
              f"Pinocchio {metadata.version('pin')}, numpy {np.__version__}, Python {sys.version.split()[0]}; "
              f"seed {SEED}")
    dump_json({"source": source, "joint_names": names, "mimic": {k: list(v) for k, v in mimics.items()},
               "mimic_vs_projected_full_max_rel_diff": worst, "states": states},
              DATA / f"pinocchio_mimic_{name}.json")


def main():
    rng = np.random.default_rng(SEED)
    mimic_data("panda", panda_mimic_urdf(), rng)
    mimic_data("gripper", gripper_mimic_urdf(rng), rng)


if __name__ == "__main__":
    main()

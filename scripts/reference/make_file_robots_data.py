#!/usr/bin/env python3
"""Reference dynamics, computed by Pinocchio, of robots as other tools write them.

Writes to dynagen/tests/data/:

- unit_axes_chain.urdf: a 7-joint chain (revolute joints with limits of
  1e5 rad and one prismatic joint) whose axes are random directions normalised in double
  precision and printed with 17 significant digits, so that each axis has
  length 1 +- 1 ulp, as a file written with full decimals does;
- pinocchio_unit_axes.json: Pinocchio's rnea, crba, nonLinearEffects and
  computeGeneralizedGravity on that file at states with |q| up to 1e4 rad
  (continuous joints that have spun for a while);
- nonphysical_inertia.urdf: a 3-joint chain one of whose links has a
  rotational inertia that is not positive semi-definite (principal moments
  -0.65, 1.65, 2.86 kg m^2, those of utorso in GRiD's benchmark Atlas);
- pinocchio_nonphysical_inertia.json: Pinocchio's rnea and crba on it.

Pinocchio's URDF parser normalises every axis (the joint turns by exactly q
about the unit axis) and accepts the non-physical inertia.  Not run in CI.
"""

from importlib import metadata
import sys

import numpy as np
import pinocchio as pin

from refcommon import DATA, dump_json

SCRIPT = "scripts/reference/make_file_robots_data.py"
SEED = 20261125
GRAVITY = np.array([0.0, 0.0, -9.81])


def g17(x):
    return "%.17g" % x


def inertial(rng, mass):
    # a physical inertia: R diag(m) R^T with moments meeting the triangle inequality
    a, b = rng.uniform(0.03, 0.06, 2)  # |a - b| <= (a + b)/2
    moments = np.array([a, b, 0.5 * (a + b)])
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    i = q @ np.diag(moments) @ q.T
    com = rng.uniform(-0.1, 0.1, 3)
    return mass, com, i


def inertial_xml(mass, com, i):
    return (f'<inertial><origin xyz="{" ".join(g17(x) for x in com)}" rpy="0 0 0"/>'
            f'<mass value="{g17(mass)}"/>'
            f'<inertia ixx="{g17(i[0, 0])}" iyy="{g17(i[1, 1])}" izz="{g17(i[2, 2])}" '
            f'ixy="{g17(i[0, 1])}" ixz="{g17(i[0, 2])}" iyz="{g17(i[1, 2])}"/></inertial>')


def chain_urdf(name, links, joints):
    out = [f'<?xml version="1.0"?>', f'<!-- written by {SCRIPT} -->', f'<robot name="{name}">',
           '  <link name="base"/>']
    for lname, body in links:
        out.append(f'  <link name="{lname}">{body}</link>')
    for j in joints:
        out.append("  " + j)
    out.append("</robot>")
    return "\n".join(out) + "\n"


def joint_xml(name, jtype, parent, child, xyz, rpy, axis):
    lim = '<limit lower="-1e5" upper="1e5" effort="100" velocity="10"/>' if jtype != "continuous" else ""
    return (f'<joint name="{name}" type="{jtype}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{" ".join(g17(x) for x in xyz)}" rpy="{" ".join(g17(x) for x in rpy)}"/>'
            f'<axis xyz="{" ".join(g17(x) for x in axis)}"/>{lim}</joint>')


def unit_axes_chain(rng):
    # revolute joints with limits of 1e5 rad: Pinocchio takes a continuous
    # joint's position as (cos q, sin q), which would hide the angle
    types = ["revolute", "revolute", "revolute", "prismatic", "revolute", "revolute", "revolute"]
    links, joints = [], []
    parent = "base"
    for k, t in enumerate(types):
        lname = f"l{k + 1}"
        links.append((lname, inertial_xml(*inertial(rng, rng.uniform(0.5, 3.0)))))
        while True:
            a = rng.normal(size=3)
            a = a / np.linalg.norm(a)
            # a length of 1 +- ulp, as the test wants to show
            if np.sqrt(a @ a) != 1.0 or k % 2 == 0:
                break
        joints.append(joint_xml(f"j{k + 1}", t, parent, lname, rng.uniform(-0.2, 0.3, 3),
                                rng.uniform(-1, 1, 3), a))
        parent = lname
    return chain_urdf("unit_axes_chain", links, joints)


def nonphysical_urdf(rng):
    links, joints = [], []
    parent = "base"
    axes = [[0, 0, 1], [0, 1, 0], [1, 0, 0]]
    for k in range(3):
        lname = f"l{k + 1}"
        mass, com, i = inertial(rng, 2.0 + k)
        if k == 1:
            lname = "utorso"
            q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
            i = q @ np.diag([-0.65, 1.65, 2.86]) @ q.T
        links.append((lname, inertial_xml(mass, com, i)))
        joints.append(joint_xml(f"j{k + 1}", "revolute", parent, lname, rng.uniform(-0.2, 0.3, 3),
                                rng.uniform(-1, 1, 3), axes[k]))
        parent = lname
    return chain_urdf("nonphysical_inertia", links, joints)


def evaluate(model, states):
    data = model.createData()
    out = []
    for q, qd, qdd in states:
        tau = pin.rnea(model, data, q, qd, qdd).copy()
        m = pin.crba(model, data, q).copy()
        m = np.triu(m) + np.triu(m, 1).T
        h = pin.nonLinearEffects(model, data, q, qd).copy()
        g = pin.computeGeneralizedGravity(model, data, q).copy()
        out.append({"q": q.tolist(), "qd": qd.tolist(), "qdd": qdd.tolist(), "tau": tau.tolist(),
                    "M": m.tolist(), "h": h.tolist(), "g": g.tolist()})
    return out


def source(what):
    return (f"{SCRIPT}: {what}; Pinocchio {metadata.version('pin')}, numpy {np.__version__}, "
            f"Python {sys.version.split()[0]}; seed {SEED}")


def main():
    rng = np.random.default_rng(SEED)
    text = unit_axes_chain(rng)
    (DATA / "unit_axes_chain.urdf").write_text(text)
    model = pin.buildModelFromXML(text)
    model.gravity.linear = GRAVITY
    n = model.nq
    states = []
    for scale in [1e3, 1e3, 3e3, 1e4, 1e4, 1e4, 1e4, 1e4]:
        q = rng.uniform(-scale, scale, n)
        q[3] = rng.uniform(-0.5, 0.5)  # the prismatic joint: metres
        states.append((q, rng.uniform(-2, 2, n), rng.uniform(-5, 5, n)))
    dump_json({"source": source("unit_axes_chain.urdf at |q| up to 1e4 rad"), "states": evaluate(model, states)},
              DATA / "pinocchio_unit_axes.json")

    text = nonphysical_urdf(rng)
    (DATA / "nonphysical_inertia.urdf").write_text(text)
    model = pin.buildModelFromXML(text)
    model.gravity.linear = GRAVITY
    n = model.nq
    states = [(rng.uniform(-3, 3, n), rng.uniform(-2, 2, n), rng.uniform(-5, 5, n)) for _ in range(6)]
    dump_json({"source": source("nonphysical_inertia.urdf (link utorso not PSD)"),
               "states": evaluate(model, states)}, DATA / "pinocchio_nonphysical_inertia.json")


if __name__ == "__main__":
    main()

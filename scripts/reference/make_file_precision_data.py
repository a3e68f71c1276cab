#!/usr/bin/env python3
"""Forward dynamics of robots as their files define them, at 50 digits.

Writes to dynagen/tests/data/:

- precision_chain8.urdf, precision_hand.urdf, precision_tiny.urdf,
  precision_huge.urdf: robots with non-aligned joint axes (written with a
  few decimals, not of unit length) and rotated frames (rpy with five
  decimals), rotated inertial frames, and links fixed to others through
  rotated fixed joints: an 8-joint chain (one joint prismatic), an 18-joint
  hand (a 2-joint wrist, a 4-joint thumb, four 3-joint fingers, fingertips
  fixed to the last phalanges), an 8-joint chain of 1-3 mm links, an
  8-joint chain of 60-100 m links; precision_near_dependent.urdf and
  precision_dependent.urdf: 8-joint chains whose joints j3 and j4 sit at
  the same point with axes 3e-4 and 3e-5 rad apart (cond(M) about 1e9 and
  1e11: M nearly singular, where the f64 solve itself loses digits);
- file_precision.json: for each robot, states (q, qd, tau) and, computed by
  this script with mpmath at 50 digits from the file's decimals taken as
  exact (no rounding to double anywhere: rotations from rpy, unit axes,
  inertias moved to body frames and fixed links merged in 50 digits),
  h(q, qd), g(q), M(q), tau(q, qd, qdd_in), the forward dynamics
  qdd = M^-1 (tau - h), cond(M) and the cancellation ||h|| / ||tau - h||.

"cancelling" states: |qd| of 1e2 to 1e3 rad/s and tau = the script's own
double-precision RNEA at (q, qd, qdd_in) for a small qdd_in, so that tau - h
cancels (tau as a controller computing in f64 would give it).  "ordinary"
states: |qd| <= 2, tau drawn at the scale of h.  Gravity is the double
nearest -9.81 m/s^2 along z, taken as exact (dynagen takes gravity as an
f64 input, not from the file).

The dynamics are written here from the textbook (recursive Newton-Euler in
body frames, Lynch & Park ch. 8; M column by column; a Gaussian solve),
independently of dynagen's code; the same functions run on Python floats
give the f64 torques, and on the float model they are checked against
Pinocchio (rnea, crba), which also checks the joint order.  References are
written as decimal strings of 40 significant digits.  Not run in CI.
"""

from importlib import metadata
import math
import sys
import xml.etree.ElementTree as ET

import mpmath
from mpmath import mp, mpf
import numpy as np
import pinocchio as pin

from refcommon import DATA, dump_json

SCRIPT = "scripts/reference/make_file_precision_data.py"
SEED = 20260719
DIGITS = 50
mp.dps = DIGITS
GRAVITY_Z = -9.81  # the double nearest -9.81, taken as exact


# --- numbers: the same dynamics on mpmath (exact decimals) and on floats ---

class Exact:
    """mpmath at DIGITS digits; a file's decimal is read exactly."""
    num = staticmethod(lambda text: mpf(text))
    const = staticmethod(lambda x: mpf(x))
    sin = staticmethod(mpmath.sin)
    cos = staticmethod(mpmath.cos)
    sqrt = staticmethod(mpmath.sqrt)


class Double:
    """Python floats: what a double-precision program computes."""
    num = staticmethod(float)
    const = staticmethod(float)
    sin = staticmethod(math.sin)
    cos = staticmethod(math.cos)
    sqrt = staticmethod(math.sqrt)


def vadd(a, b):
    return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]


def vsub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def vscale(a, s):
    return [a[0] * s, a[1] * s, a[2] * s]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def mv(m, v):
    return [dot(m[0], v), dot(m[1], v), dot(m[2], v)]


def mtv(m, v):
    return [m[0][k] * v[0] + m[1][k] * v[1] + m[2][k] * v[2] for k in range(3)]


def mm(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def rpy_matrix(F, r, p, y):
    """URDF roll-pitch-yaw: R = Rz(y) Ry(p) Rx(r)."""
    cr, sr, cp, sp, cy, sy = F.cos(r), F.sin(r), F.cos(p), F.sin(p), F.cos(y), F.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def axis_rotation(F, a, q):
    """Rotation by q about the unit vector a (Rodrigues)."""
    c, s = F.cos(q), F.sin(q)
    t = 1 - c
    x, y, z = a
    return [[c + t * x * x, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, c + t * y * y, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, c + t * z * z]]


# --- the robot as its file defines it ---

def numbers(F, text, n):
    vals = [F.num(t) for t in text.split()]
    assert len(vals) == n, text
    return vals


def origin_of(F, elem):
    """(R, p) of an <origin> child of elem; identity when absent."""
    o = elem.find("origin") if elem is not None else None
    zero = [F.const(0)] * 3
    xyz = numbers(F, o.get("xyz", "0 0 0"), 3) if o is not None else zero
    rpy = numbers(F, o.get("rpy", "0 0 0"), 3) if o is not None else zero
    return rpy_matrix(F, *rpy), xyz


def compose(a, b):
    (ra, pa), (rb, pb) = a, b
    return mm(ra, rb), vadd(mv(ra, pb), pa)


def link_inertia(F, link):
    """(m, m*c, I about the link origin) in the link frame, or None."""
    inertial = link.find("inertial")
    if inertial is None:
        return None
    m = F.num(inertial.find("mass").get("value"))
    r_in, c = origin_of(F, inertial)
    e = inertial.find("inertia")
    ixx, iyy, izz, ixy, ixz, iyz = (F.num(e.get(k)) for k in ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"])
    i_in = [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]
    i_c = mm(mm(r_in, i_in), transpose(r_in))
    return m, vscale(c, m), shift_to_origin(i_c, m, c)


def shift_to_origin(i_c, m, c):
    """Inertia about the origin of a body of mass m, centre c, I_c about c."""
    cc = dot(c, c)
    return [[i_c[i][j] + m * ((cc if i == j else 0) - c[i] * c[j]) for j in range(3)] for i in range(3)]


def moved(inertia, pose):
    """A (m, h, I_origin) given in frame B, expressed in A, pose = (R_AB, p_AB)."""
    m, h, i_o = inertia
    r, p = pose
    # about B's origin in A's axes, then shifted to A's origin: I_A = R I Rt - [p][h'] - [h'][p] + m [p]t[p]
    i_r = mm(mm(r, i_o), transpose(r))
    h_r = mv(r, h)
    ph = dot(p, h_r)
    pp = dot(p, p)
    i_a = [[i_r[i][j] + ((2 * ph if i == j else 0) - p[i] * h_r[j] - h_r[i] * p[j])
            + m * ((pp if i == j else 0) - p[i] * p[j]) for j in range(3)] for i in range(3)]
    return m, vadd(h_r, vscale(p, m)), i_a


def add_inertia(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return a[0] + b[0], vadd(a[1], b[1]), [[a[2][i][j] + b[2][i][j] for j in range(3)] for i in range(3)]


def build(F, urdf_text):
    """Bodies in depth-first order (children in file order), fixed links merged."""
    root_elem = ET.fromstring(urdf_text)
    links = {l.get("name"): l for l in root_elem.findall("link")}
    joints = root_elem.findall("joint")
    children = {name: [] for name in links}
    has_parent = set()
    for j in joints:
        children[j.find("parent").get("link")].append(j)
        has_parent.add(j.find("child").get("link"))
    root = next(n for n in links if n not in has_parent)
    identity = ([[F.const(1) if i == k else F.const(0) for k in range(3)] for i in range(3)], [F.const(0)] * 3)
    bodies = []  # dicts: name, parent, kind, placement (R, p), axis, inertia
    stack = [(root, None, identity, None)]
    while stack:
        link, body, pose, joint = stack.pop()
        if joint is not None:
            a = numbers(F, joint.find("axis").get("xyz"), 3)
            n = F.sqrt(dot(a, a))
            bodies.append({"name": joint.get("name"), "parent": body, "kind": joint.get("type"),
                           "placement": pose, "axis": vscale(a, 1 / n), "inertia": None})
            body, pose = len(bodies) - 1, identity
        li = link_inertia(F, links[link])
        if body is not None and li is not None:
            bodies[body]["inertia"] = add_inertia(bodies[body]["inertia"], moved(li, pose))
        for j in reversed(children[link]):
            child_pose = compose(pose, origin_of(F, j))
            moving = j if j.get("type") != "fixed" else None
            stack.append((j.find("child").get("link"), body, child_pose, moving))
    zero = F.const(0)
    for b in bodies:
        if b["inertia"] is None:  # a massless link
            b["inertia"] = (zero, [zero] * 3, [[zero] * 3 for _ in range(3)])
    return bodies


# --- dynamics ---

def rnea(F, bodies, q, qd, qdd, gravity):
    """Joint torques; gravity as the base's acceleration -g."""
    zero = [F.const(0)] * 3
    n = len(bodies)
    w, wd, vd, rot, pos = [None] * n, [None] * n, [None] * n, [None] * n, [None] * n
    for i, b in enumerate(bodies):
        r0, p0 = b["placement"]
        a = b["axis"]
        if b["parent"] is None:
            wp, wdp, vdp = zero, zero, vscale(gravity, -1)
        else:
            wp, wdp, vdp = w[b["parent"]], wd[b["parent"]], vd[b["parent"]]
        if b["kind"] == "prismatic":
            r, p = r0, vadd(p0, mv(r0, vscale(a, q[i])))
        else:
            r, p = mm(r0, axis_rotation(F, a, q[i])), p0
        rot[i], pos[i] = r, p
        # the parent's motion at this body's origin, in this body's axes
        vd_o = mtv(r, vadd(vdp, vadd(cross(wdp, p), cross(wp, cross(wp, p)))))
        w_in, wd_in = mtv(r, wp), mtv(r, wdp)
        if b["kind"] == "prismatic":
            w[i], wd[i] = w_in, wd_in
            vd[i] = vadd(vd_o, vadd(vscale(cross(w_in, a), 2 * qd[i]), vscale(a, qdd[i])))
        else:
            w[i] = vadd(w_in, vscale(a, qd[i]))
            wd[i] = vadd(vadd(wd_in, vscale(a, qdd[i])), vscale(cross(w_in, a), qd[i]))
            vd[i] = vd_o
    f, nm = [None] * n, [None] * n
    for i, b in enumerate(bodies):
        m, h, i_o = b["inertia"]
        # f = m a_c with a_c = vd + wd x c + w x (w x c); n about the origin = I_o wd + w x I_o w + h x vd
        f[i] = vadd(vscale(vd[i], m), vadd(cross(wd[i], h), cross(w[i], cross(w[i], h))))
        nm[i] = vadd(vadd(mv(i_o, wd[i]), cross(w[i], mv(i_o, w[i]))), cross(h, vd[i]))
    tau = [None] * n
    for i in reversed(range(n)):
        b = bodies[i]
        tau[i] = dot(b["axis"], f[i] if b["kind"] == "prismatic" else nm[i])
        p = b["parent"]
        if p is not None:
            fr = mv(rot[i], f[i])
            f[p] = vadd(f[p], fr)
            nm[p] = vadd(nm[p], vadd(mv(rot[i], nm[i]), cross(pos[i], fr)))
    return tau


def mass_matrix(F, bodies, q):
    n = len(bodies)
    zero = [F.const(0)] * n
    cols = []
    for j in range(n):
        e = [F.const(1) if k == j else F.const(0) for k in range(n)]
        cols.append(rnea(F, bodies, q, zero, e, [F.const(0)] * 3))
    return [[cols[j][i] for j in range(n)] for i in range(n)]


# --- the test robots ---

def f(x, digits):
    return f"{x:.{digits}g}"


def inertial_xml(rng, mass, com, size):
    """A physical inertia (moments meeting the triangle inequality) in a rotated inertial frame."""
    a, b = rng.uniform(0.5, 1.0, 2) * mass * size * size / 12
    c = rng.uniform(abs(a - b) * 1.05, (a + b) * 0.95)
    rpy = rng.uniform(-math.pi, math.pi, 3)
    return (f'<inertial><origin xyz="{" ".join(f(x, 4) for x in com)}" rpy="{" ".join(f(x, 5) for x in rpy)}"/>'
            f'<mass value="{f(mass, 4)}"/>'
            f'<inertia ixx="{f(a, 6)}" iyy="{f(b, 6)}" izz="{f(c, 6)}" ixy="0" ixz="0" iyz="0"/></inertial>')


def axis_text(rng, near=None):
    """A direction written with three decimals (not of unit length): random, or near a given one."""
    v = rng.normal(size=3) if near is None else np.array(near, float) + rng.normal(scale=0.15, size=3)
    v = v / np.linalg.norm(v) * rng.uniform(0.7, 1.3)
    return " ".join(f"{x:.3f}" for x in v)


def joint_xml(name, kind, parent, child, xyz, rpy, axis=None):
    lim = '<limit lower="-1e5" upper="1e5" effort="1e9" velocity="1e4"/>' if kind in ("revolute", "prismatic") else ""
    ax = f'<axis xyz="{axis}"/>' if axis is not None else ""
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{" ".join(f(x, 4) for x in xyz)}" rpy="{" ".join(f"{x:.5f}" for x in rpy)}"/>'
            f'{ax}{lim}</joint>')


def urdf(name, links, joints):
    out = ['<?xml version="1.0"?>', f"<!-- written by {SCRIPT} (seed {SEED}) -->", f'<robot name="{name}">']
    out += [f'  <link name="{l}">{body}</link>' for l, body in links]
    out += ["  " + j for j in joints]
    return "\n".join(out + ["</robot>"]) + "\n"


def chain(rng, name, n, length, mass, prismatic=()):
    """A serial chain; every third link carries a sensor fixed to it by a rotated fixed joint."""
    links, joints = [("base", "")], []
    parent = "base"
    for k in range(n):
        lname = f"l{k}"
        ln, m = rng.uniform(*length), mass(rng)
        com = rng.uniform(-0.2, 0.2, 3) * ln + np.array([0, 0, 0.5 * ln])
        links.append((lname, inertial_xml(rng, m, com, ln)))
        kind = "prismatic" if k in prismatic else "revolute"
        xyz = rng.uniform(-0.3, 0.3, 3) * ln + np.array([0, 0, ln])
        joints.append(joint_xml(f"j{k}", kind, parent, lname, xyz, rng.uniform(-math.pi, math.pi, 3),
                                axis_text(rng)))
        if k % 3 == 2:
            sname = f"sensor{k}"
            links.append((sname, inertial_xml(rng, 0.2 * m, rng.uniform(-0.1, 0.1, 3) * ln, 0.3 * ln)))
            joints.append(joint_xml(f"j{k}_sensor", "fixed", lname, sname, rng.uniform(-0.3, 0.3, 3) * ln,
                                    rng.uniform(-math.pi, math.pi, 3)))
        parent = lname
    return urdf(name, links, joints)


def near_dependent(rng, name, angle):
    """An 8-joint chain whose joints j3 and j4 sit at the same point with axes `angle` rad apart
    (link l3 between them massless): M is nearly singular, cond(M) growing as 1/angle^2."""
    text = chain(rng, name, 8, (0.15, 0.45), lambda r: r.uniform(0.5, 3.0))
    a = rng.normal(size=3)
    a /= np.linalg.norm(a)
    p = np.cross(a, rng.normal(size=3))
    p /= np.linalg.norm(p)
    b = math.cos(angle) * a + math.sin(angle) * p
    root = ET.fromstring(text)
    for link in root.findall("link"):
        if link.get("name") == "l3":
            link.remove(link.find("inertial"))
    for joint in root.findall("joint"):
        if joint.get("name") in ("j3", "j4"):
            joint.find("axis").set("xyz", " ".join(f"{x:.12f}" for x in (a if joint.get("name") == "j3" else b)))
        if joint.get("name") == "j4":
            joint.find("origin").set("xyz", "0 0 0")
            joint.find("origin").set("rpy", "0 0 0")
    body = ET.tostring(root, encoding="unicode")
    return f'<?xml version="1.0"?>\n<!-- written by {SCRIPT} (seed {SEED}) -->\n{body}\n'


def hand(rng):
    """A wrist (2 joints) and a palm with a thumb (4 joints) and four fingers (3 joints each)."""
    links = [("base", ""), ("forearm", inertial_xml(rng, 1.0, [0, 0, 0.1], 0.25))]
    joints = [joint_xml("a0_wrist_dev", "revolute", "base", "forearm", [0, 0, 0.05], [0.01, -0.02, 0.3],
                        axis_text(rng, [1, 0, 0]))]
    links.append(("palm", inertial_xml(rng, 0.4, [0.0, 0.04, 0.005], 0.09)))
    joints.append(joint_xml("a1_wrist_flex", "revolute", "forearm", "palm", [0, 0, 0.24], [0.12, 0.03, -0.05],
                            axis_text(rng, [0, 1, 0])))
    fingers = [("b_thumb", [0.035, 0.01, -0.01], [0.6, -0.4, -0.9], [0.045, 0.04, 0.035, 0.03]),
               ("c_index", [0.025, 0.09, 0.0], [0.02, 0.05, 0.08], [0.045, 0.028, 0.02]),
               ("d_middle", [0.005, 0.095, 0.0], [0.0, 0.0, 0.0], [0.05, 0.032, 0.022]),
               ("e_ring", [-0.015, 0.09, 0.0], [-0.03, -0.04, -0.07], [0.046, 0.03, 0.021]),
               ("f_little", [-0.035, 0.08, -0.003], [-0.06, -0.08, -0.15], [0.038, 0.022, 0.018])]
    for fname, base_xyz, base_rpy, lengths in fingers:
        parent, xyz, rpy = "palm", base_xyz, base_rpy
        for k, ln in enumerate(lengths):
            lname = f"{fname}_{k}"
            m = 0.0008 * ln * 1000 * rng.uniform(0.8, 1.2)  # about 36 g for a 45 mm phalanx
            com = [rng.uniform(-0.05, 0.05) * ln, 0.5 * ln, rng.uniform(-0.05, 0.05) * ln]
            links.append((lname, inertial_xml(rng, m, com, ln)))
            # the first joint of a finger spreads it (about the palm's normal), the others bend it
            near = [0, 0, 1] if k == 0 else [1, 0, 0]
            joints.append(joint_xml(f"{fname}_{k}", "revolute", parent, lname, xyz, rpy, axis_text(rng, near)))
            parent, xyz = lname, [rng.uniform(-0.02, 0.02) * ln, ln, rng.uniform(-0.02, 0.02) * ln]
            rpy = rng.uniform(-0.05, 0.05, 3)
        tip = f"{fname}_tip"
        links.append((tip, inertial_xml(rng, 0.004, [0, 0.004, 0.002], 0.012)))
        joints.append(joint_xml(f"{fname}_tip", "fixed", parent, tip, xyz, rng.uniform(-0.3, 0.3, 3)))
    return urdf("precision_hand", links, joints)


# --- states and references ---

def s40(x):
    return mpmath.nstr(x, 40, min_fixed=1, max_fixed=0)


def solve(m, rhs):
    return list(mp.lu_solve(mpmath.matrix(m), mpmath.matrix(rhs)))


def norm(v):
    return mpmath.sqrt(sum(x * x for x in v))


def reference_state(text, exact, double, kind, q, qd, qdd_in, tau=None):
    """One state: tau from the double-precision RNEA if not given, and the 50-digit references."""
    gd, ge = [0.0, 0.0, GRAVITY_Z], [mpf(0), mpf(0), mpf(GRAVITY_Z)]
    if tau is None:
        tau = rnea(Double, double, q, qd, qdd_in, gd)
    qe, qde, qdde, taue = ([mpf(x) for x in v] for v in (q, qd, qdd_in, tau))
    zero = [mpf(0)] * len(q)
    h = rnea(Exact, exact, qe, qde, zero, ge)
    g = rnea(Exact, exact, qe, zero, zero, ge)
    tau_of_qdd = rnea(Exact, exact, qe, qde, qdde, ge)
    m = mass_matrix(Exact, exact, qe)
    u = [t - x for t, x in zip(taue, h)]
    qdd = solve(m, u)
    ev = list(mp.eigsy(mpmath.matrix(m))[0])
    cond = max(ev) / min(ev)
    return {"kind": kind, "q": list(q), "qd": list(qd), "qdd_in": list(qdd_in), "tau": list(tau),
            "cond_M": float(cond), "cancellation": float(norm(h) / norm(u)),
            "qdd": [s40(x) for x in qdd], "h": [s40(x) for x in h], "g": [s40(x) for x in g],
            "tau_of_qdd_in": [s40(x) for x in tau_of_qdd], "M": [[s40(x) for x in row] for row in m]}


def check_against_pinocchio(name, text, double):
    """The float dynamics of this script against Pinocchio on the same file: joint order, rnea, crba."""
    model = pin.buildModelFromXML(text)
    names = [model.names[i] for i in range(1, model.njoints)]
    assert names == [b["name"] for b in double], (name, names)
    data = model.createData()
    rng = np.random.default_rng(1)
    worst = 0.0
    for _ in range(3):
        q, qd, qdd = (rng.uniform(-2, 2, model.nq) for _ in range(3))
        tau = pin.rnea(model, data, q, qd, qdd)
        mine = rnea(Double, double, q, qd, qdd, [0.0, 0.0, GRAVITY_Z])
        m_pin = pin.crba(model, data, q)
        m_pin = np.triu(m_pin) + np.triu(m_pin, 1).T
        m_mine = np.array(mass_matrix(Double, double, list(q)))
        worst = max(worst, np.max(np.abs(tau - mine)) / np.max(np.abs(tau)),
                    np.max(np.abs(m_pin - m_mine)) / np.max(np.abs(m_pin)))
    assert worst < 1e-11, (name, worst)
    return worst


def robot_entry(rng, name, text, q_scale, n_cancelling=4, n_ordinary=2):
    (DATA / f"{name}.urdf").write_text(text)
    exact, double = build(Exact, text), build(Double, text)
    pin_diff = check_against_pinocchio(name, text, double)
    n = len(exact)
    prismatic = [b["kind"] == "prismatic" for b in exact]
    states = []
    for k in range(n_cancelling + n_ordinary):
        q = [float(rng.uniform(-0.3, 0.3) * q_scale if p else rng.uniform(-math.pi, math.pi)) for p in prismatic]
        if k < n_cancelling:
            speed = [1e2, 3e2, 1e3, 1e3][k % 4]
            qd = [float(x) for x in rng.uniform(-1, 1, n) * speed]
            qdd_in = [float(x) for x in rng.uniform(-1, 1, n)]
            states.append(reference_state(text, exact, double, "cancelling", q, qd, qdd_in))
        else:
            qd, qdd_in = [float(x) for x in rng.uniform(-2, 2, n)], [float(x) for x in rng.uniform(-5, 5, n)]
            g = rnea(Double, double, q, [0.0] * n, [0.0] * n, [0.0, 0.0, GRAVITY_Z])
            scale = max(1.0, max(abs(x) for x in g))
            tau = [float(x) for x in rng.uniform(-1, 1, n) * scale]
            states.append(reference_state(text, exact, double, "ordinary", q, qd, qdd_in, tau))
        print(f"{name} state {k}: cond(M) {states[-1]['cond_M']:.2e}, cancellation {states[-1]['cancellation']:.1e}")
    return {"name": name, "urdf": f"{name}.urdf", "joint_names": [b["name"] for b in exact],
            "pinocchio_float_max_rel_diff": pin_diff, "states": states}


def main():
    rng = np.random.default_rng(SEED)
    robots = [
        ("precision_chain8", chain(rng, "precision_chain8", 8, (0.15, 0.45), lambda r: r.uniform(0.5, 3.0), (4,)), 1.0),
        ("precision_hand", hand(rng), 0.05),
        ("precision_tiny", chain(rng, "precision_tiny", 8, (0.001, 0.003), lambda r: r.uniform(1e-5, 5e-5)), 0.002),
        ("precision_huge", chain(rng, "precision_huge", 8, (60.0, 100.0), lambda r: r.uniform(1e4, 1e5)), 50.0),
        ("precision_near_dependent", near_dependent(rng, "precision_near_dependent", 3e-4), 1.0),
        ("precision_dependent", near_dependent(rng, "precision_dependent", 3e-5), 1.0),
    ]
    entries = [robot_entry(rng, name, text, q_scale) for name, text, q_scale in robots]
    source = (f"{SCRIPT}: mpmath {mpmath.__version__} at {DIGITS} digits from the files' decimals; tau of "
              f"cancelling states from the script's float RNEA; float dynamics checked against Pinocchio "
              f"{metadata.version('pin')}; numpy {np.__version__}, Python {sys.version.split()[0]}; seed {SEED}")
    dump_json({"source": source, "gravity": [0.0, 0.0, GRAVITY_Z], "robots": entries},
              DATA / "file_precision.json")


if __name__ == "__main__":
    main()

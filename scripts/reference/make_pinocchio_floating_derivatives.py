#!/usr/bin/env python3
"""Reference derivatives of floating-base robots, computed by Pinocchio.

Writes dynagen/tests/data/pinocchio_floating_derivatives.json: for the
bundled quadruped12 and torso_two_arms and the random tree of
tests/data/random_tree20.urdf, each with a JointModelFreeFlyer root
(pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())), at 6 states
(random unit quaternions, joints in [-pi, pi], |qd| of 2 and of 20; 4
states, 2 for the 20-joint tree):

  computeRNEADerivatives(q, v, a)  -> dtau_dq, dtau_dqd (its M not kept)
  computeABADerivatives(q, v, tau) -> dqdd_dq, dqdd_dqd, minv

(checked here: M·minv = 1, computeMinverse = minv, the chain rule
dqdd_dq = -minv dtau_dq at qdd = aba; the values of M are in
pinocchio_floating_<robot>.json already).

Pinocchio's free-flyer tangent is the base's body twist: q (+) dv =
integrate(q, dv) moves the base to T exp(dv), the convention dynagen's
derivatives share; each column of dtau_dq is also checked here against a
central difference through pin.integrate (1e-6 of the matrix's norm).

Conventions are converted to dynagen's (shared/DESIGN.md), as
make_pinocchio_floating.py does: the velocity side (rows and columns of
every matrix, qd, qdd, tau) is permuted by PERM = [3, 4, 5, 0, 1, 2, 6, ...]
(Pinocchio's base twist and wrench are (linear; angular), dynagen's
(angular; linear)) and the joints to dynagen's order (refcommon.file_order);
q keeps its layout [p, quaternion (x, y, z, w), joints] with the joints
permuted.  Matrices are [output][input]; Pinocchio's upper triangles of M
and M^-1 are mirrored.

Not run in CI.  See README.md in this folder.
"""

import sys
from importlib import metadata

import numpy as np
import pinocchio as pin

from refcommon import DATA, REPO, dump_json, file_order

SCRIPT = "scripts/reference/make_pinocchio_floating_derivatives.py"
SEED = 20261127
GRAVITY = np.array([0.0, 0.0, -9.81])
ROBOTS = {
    "quadruped12": "dynagen/robots/quadruped12.urdf",
    "torso_two_arms": "dynagen/robots/torso_two_arms.urdf",
    "random_tree20": "dynagen/tests/data/random_tree20.urdf",
}
ANG_LIN = [3, 4, 5, 0, 1, 2]


def mirror_upper(m):
    u = np.triu(m)
    return u + np.triu(u, 1).T


def run(robot, rel, rng):
    model = pin.buildModelFromUrdf(str(REPO / rel), pin.JointModelFreeFlyer())
    data = model.createData()
    assert np.allclose(model.gravity.linear, GRAVITY)
    assert model.nq == model.nv + 1, "a joint with nq != nv (continuous?)"
    n, nv = model.nv - 6, model.nv
    names = file_order(REPO / rel)
    pin_names = list(model.names)[2:]
    assert sorted(names) == sorted(pin_names)
    perm = ANG_LIN + [6 + pin_names.index(name) for name in names]  # ours[k] = pin[perm[k]]
    inv = np.argsort(perm)
    qperm = list(range(7)) + [7 + pin_names.index(name) for name in names]
    mat = lambda m: m[np.ix_(perm, perm)].tolist()  # noqa: E731 (Pinocchio's to dynagen's)
    records = []
    # relative to the matrix norm, but M Minv - 1 and minv_alone: largest absolute entry
    worst = {"fd_dtau_dq": 0.0, "M_minv_minus_1": 0.0, "chain_rule": 0.0, "minv_alone": 0.0}
    count = 2 if n > 12 else 4
    for k in range(count):
        quat = rng.normal(size=4)
        quat /= np.linalg.norm(quat)
        ours = dict(q=np.concatenate([rng.uniform(-2, 2, 3), quat, rng.uniform(-np.pi, np.pi, n)]),
                    qd=rng.uniform(-1, 1, nv), qdd=rng.uniform(-5, 5, nv), tau=rng.uniform(-10, 10, nv))
        ours["qd"] *= (2.0 if k < count // 2 else 20.0) / np.linalg.norm(ours["qd"])
        q = ours["q"][np.argsort(qperm)]
        v, a, tau = (ours[key][inv] for key in ("qd", "qdd", "tau"))
        dq, dv, M = (x.copy() for x in pin.computeRNEADerivatives(model, data, q, v, a))
        M = mirror_upper(M)
        fq, fv, minv = (x.copy() for x in pin.computeABADerivatives(model, data, q, v, tau))
        minv = mirror_upper(minv)
        alone = mirror_upper(pin.computeMinverse(model, data, q).copy())
        # The tangent convention, by central differences through integrate.
        h, fd = 1e-6, np.zeros((nv, nv))
        for j in range(nv):
            e = np.zeros(nv)
            e[j] = h
            fd[:, j] = (pin.rnea(model, data, pin.integrate(model, q, e), v, a)
                        - pin.rnea(model, data, pin.integrate(model, q, -e), v, a)) / (2 * h)
        worst["fd_dtau_dq"] = max(worst["fd_dtau_dq"], float(np.linalg.norm(fd - dq) / np.linalg.norm(dq)))
        worst["M_minv_minus_1"] = max(worst["M_minv_minus_1"], float(np.max(np.abs(M @ minv - np.eye(nv)))))
        worst["minv_alone"] = max(worst["minv_alone"], float(np.max(np.abs(minv - alone))))
        acc = pin.aba(model, data, q, v, tau).copy()
        dq_at = pin.computeRNEADerivatives(model, data, q, v, acc)[0].copy()
        worst["chain_rule"] = max(worst["chain_rule"],
                                  float(np.linalg.norm(fq + minv @ dq_at) / np.linalg.norm(fq)))
        rec = {key: ours[key].tolist() for key in ("q", "qd", "qdd")}
        rec["tau_in"] = ours["tau"].tolist()
        rec.update({"dtau_dq": mat(dq), "dtau_dqd": mat(dv), "dqdd_dq": mat(fq), "dqdd_dqd": mat(fv),
                    "minv": mat(minv)})
        records.append(rec)
    print(f"{robot} ({n} joints, free flyer): consistency {worst}")
    if worst["fd_dtau_dq"] > 1e-6 or max(worst["M_minv_minus_1"], worst["chain_rule"], worst["minv_alone"]) > 1e-8:
        sys.exit(f"{robot}: Pinocchio's derivatives are not consistent")
    return {"urdf": rel, "joint_names": names, "consistency_checks": worst, "states": records}


def main():
    rng = np.random.default_rng(SEED)
    doc = {
        "source": {
            "generator": "pinocchio",
            "pinocchio_version": pin.__version__,
            "pin_package_version": metadata.version("pin"),
            "numpy_version": np.__version__,
            "script": SCRIPT,
            "load": "pinocchio.buildModelFromUrdf(<urdf>, pinocchio.JointModelFreeFlyer())",
            "seed": SEED,
        },
        "notes": [
            "dtau_dq, dtau_dqd = pinocchio.computeRNEADerivatives(q, qd, qdd) with gravity (0,0,-9.81) "
            "in the world; dqdd_dq, dqdd_dqd, minv = pinocchio.computeABADerivatives(q, qd, tau_in) "
            "(minv equals pinocchio.computeMinverse(q) exactly: checked).",
            "The tangent of q is the base's body twist (Pinocchio's integrate: the base to T exp(dv)).",
            "In dynagen's conventions: velocity-side vectors and every matrix's rows and columns are "
            "[w_b, v_b, joints] (Pinocchio's [v_b, w_b, ...] permuted), the base rows of tau are the "
            "wrench (moment; force) on the base in its frame, joints in dynagen's order (joint_names).",
            "Matrices are lists of rows, [output][input]; M^-1 is Pinocchio's upper triangle mirrored.",
        ],
        "robots": {r: run(r, rel, rng) for r, rel in ROBOTS.items()},
    }
    path = DATA / "pinocchio_floating_derivatives.json"
    dump_json(doc, path)
    print(f"wrote {path.relative_to(REPO)}")


if __name__ == "__main__":
    main()

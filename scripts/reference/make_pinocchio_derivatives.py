#!/usr/bin/env python3
"""Reference derivatives of the dynamics of the bundled robots, by Pinocchio.

Writes dynagen/tests/data/pinocchio_derivatives.json: for each URDF in
dynagen/robots/, at the zero state and 4 random states, Pinocchio's
analytical derivatives (Carpentier & Mansard, RSS 2018):

  computeRNEADerivatives(q, v, a)  -> dtau_dq, dtau_dqd (and dtau_dqdd = M)
  computeABADerivatives(q, v, tau) -> dqdd_dq, dqdd_dqd, minv (= dqdd_dtau)
  computeMinverse(q)               -> minv_alone

Matrices are [output][input] (rows = outputs), as dynagen's.  Pinocchio
fills only the upper triangle of M and M^-1: it is mirrored before saving.

Not run in CI.  See README.md in this folder.
"""

import sys

import numpy as np
import pinocchio as pin

from refcommon import DATA, REPO, dump_json, file_order

SCRIPT = "scripts/reference/make_pinocchio_derivatives.py"
SEED = 20261125
N_RANDOM = 4
GRAVITY = np.array([0.0, 0.0, -9.81])
ROBOTS = ["ur5", "panda", "torso_two_arms", "planar_2link", "iiwa14", "quadruped12"]


def mirror_upper(m):
    u = np.triu(m)
    return u + np.triu(u, 1).T


def run(robot, rng):
    rel = f"dynagen/robots/{robot}.urdf"
    model = pin.buildModelFromUrdf(str(REPO / rel))  # fixed base
    data = model.createData()
    assert model.nq == model.nv
    assert np.allclose(model.gravity.linear, GRAVITY)
    # dynagen's joint k is Pinocchio's perm[k] (Pinocchio may visit a link's
    # children in another order than the file's: the quadruped12's legs)
    pin_names = list(model.names)[1:]
    names = file_order(REPO / rel)
    assert sorted(names) == sorted(pin_names)
    perm = [pin_names.index(name) for name in names]
    n = model.nv
    lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    states = [dict(q=np.zeros(n), qd=np.zeros(n), qdd=np.zeros(n), tau=np.zeros(n))]
    for _ in range(N_RANDOM):
        q = np.empty(n)
        for i in range(n):
            j = model.joints[i + 1]
            kind = j.shortname()
            if kind.startswith("JointModelP") and not kind.startswith("JointModelPlanar"):
                q[i] = rng.uniform(lower[i], upper[i])
            else:
                q[i] = rng.uniform(-np.pi, np.pi)
        states.append(dict(q=q, qd=rng.uniform(-2, 2, n), qdd=rng.uniform(-5, 5, n),
                           tau=rng.uniform(-10, 10, n)))
    out = []
    worst = {"dtau_dqdd_vs_crba": 0.0, "minv_vs_computeMinverse": 0.0,
             "dqdd_dq_vs_minus_minv_dtau_dq": 0.0, "M_minv_minus_1": 0.0}
    for s in states:
        q, qd, qdd, tau = s["q"], s["qd"], s["qdd"], s["tau"]
        dq, dv, da = pin.computeRNEADerivatives(model, data, q, qd, qdd)
        dq, dv, M = dq.copy(), dv.copy(), mirror_upper(da.copy())
        fq, fv, minv = pin.computeABADerivatives(model, data, q, qd, tau)
        fq, fv, minv = fq.copy(), fv.copy(), mirror_upper(minv.copy())
        alone = mirror_upper(pin.computeMinverse(model, data, q).copy())
        # consistency of what is recorded
        worst["dtau_dqdd_vs_crba"] = max(worst["dtau_dqdd_vs_crba"], float(np.max(np.abs(
            M - mirror_upper(pin.crba(model, data, q).copy())))))
        worst["minv_vs_computeMinverse"] = max(worst["minv_vs_computeMinverse"],
                                               float(np.max(np.abs(minv - alone))))
        worst["M_minv_minus_1"] = max(worst["M_minv_minus_1"],
                                      float(np.max(np.abs(M @ minv - np.eye(n)))))
        a = pin.aba(model, data, q, qd, tau).copy()
        dq_at, _, _ = pin.computeRNEADerivatives(model, data, q, qd, a)
        worst["dqdd_dq_vs_minus_minv_dtau_dq"] = max(
            worst["dqdd_dq_vs_minus_minv_dtau_dq"],
            float(np.max(np.abs(fq + minv @ dq_at.copy()))))
        vec = lambda v: v[perm].tolist()  # noqa: E731 (to dynagen's joint order)
        mat = lambda m: m[np.ix_(perm, perm)].tolist()  # noqa: E731
        out.append({
            "q": vec(q), "qd": vec(qd), "qdd": vec(qdd), "tau_in": vec(tau),
            "dtau_dq": mat(dq), "dtau_dqd": mat(dv), "dtau_dqdd": mat(M),
            "dqdd_dq": mat(fq), "dqdd_dqd": mat(fv), "minv": mat(minv),
            "minv_alone": mat(alone),
        })
    print(f"{robot}: {names}; consistency {worst}")
    if max(worst.values()) > 1e-8:
        sys.exit(f"{robot}: Pinocchio's derivatives are not consistent")
    return {"joint_names": names, "consistency_checks_max_abs": worst, "states": out}


def main():
    rng = np.random.default_rng(SEED)
    doc = {
        "source": {
            "generator": "pinocchio",
            "pinocchio_version": pin.__version__,
            "numpy_version": np.__version__,
            "script": SCRIPT,
            "load": "pinocchio.buildModelFromUrdf(dynagen/robots/<robot>.urdf) (fixed base)",
            "seed": SEED,
        },
        "notes": [
            "dtau_dq, dtau_dqd, dtau_dqdd = pinocchio.computeRNEADerivatives(q, qd, qdd) with "
            "gravity (0,0,-9.81); dqdd_dq, dqdd_dqd, minv = pinocchio.computeABADerivatives(q, "
            "qd, tau_in); minv_alone = pinocchio.computeMinverse(q).",
            "Matrices are lists of rows, [output][input].  dtau_dqdd, minv and minv_alone are "
            "Pinocchio's upper triangles mirrored.",
            "States: the first is the zero state; the next drawn with numpy.random.default_rng"
            "(seed), robot by robot in the order of 'robots': q uniform in [-pi, pi] for revolute "
            "joints and within the limits for prismatic ones, qd in [-2, 2], qdd in [-5, 5], "
            "tau_in in [-10, 10].",
            "States are drawn in Pinocchio's joint order, then every vector and matrix is "
            "permuted to dynagen's (depth first over the URDF tree, children in file order), "
            "which joint_names gives (the test checks it equals dynagen's).",
        ],
        "robots": {r: run(r, rng) for r in ROBOTS},
    }
    path = DATA / "pinocchio_derivatives.json"
    dump_json(doc, path)
    print(f"wrote {path.relative_to(REPO)}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Writes a C++ header that builds Pinocchio models without its URDF parser.

Usage: make_pinocchio_models.py OUT.hpp ROBOT.urdf[:floating|:mimic] ...

Pinocchio's URDF parser lives in the `pin` wheel's prebuilt
libpinocchio_parsers, compiled for baseline x86-64: a benchmark built with
-march=native cannot use it (Eigen's alignment changes the layout of Model,
and the program segfaults). So the models are read here, in Python, and
written out as C++ that makes the same model with Pinocchio's header-only
API (addJoint, appendBodyToJoint, the joint limits), which the benchmark then
compiles with whatever flags it likes. `:floating` puts a
JointModelFreeFlyer root above the URDF's root link, as
`buildModelFromUrdf(path, JointModelFreeFlyer())` does; `:mimic` reads the
file with the parser's mimic option (`buildModelFromUrdf(path, mimic=True)`):
a JointModelMimic of the joint's own type, following its master's joint.

The header also holds, for each model, rnea at one state as Python's
Pinocchio computed it; `pinocchio_models::build` rebuilds the model, runs
rnea there and stops the program if any entry differs by more than 1e-12
relative, so a benchmark never times a model that is not the URDF's.
"""

import os
import sys

import numpy as np
import pinocchio as pin


def cpp(x):
    return repr(float(x))


def vec(v):
    return ", ".join(cpp(x) for x in np.asarray(v).ravel())


def se3(m):
    return (f"pinocchio::SE3((Eigen::Matrix3d() << {vec(m.rotation)}).finished(), "
            f"Eigen::Vector3d({vec(m.translation)}))")


def joint(jm):
    name = jm.shortname()
    if name in ("JointModelRevoluteUnaligned", "JointModelPrismaticUnaligned"):
        return f"pinocchio::{name}(Eigen::Vector3d({vec(jm.extract().axis)}))"
    simple = {"JointModelRX", "JointModelRY", "JointModelRZ", "JointModelPX",
              "JointModelPY", "JointModelPZ", "JointModelRUBX", "JointModelRUBY",
              "JointModelRUBZ", "JointModelFreeFlyer"}
    if name not in simple:
        sys.exit(f"make_pinocchio_models.py: joint type {name} is not handled")
    return f"pinocchio::{name}()"


def check_state(model):
    """A fixed, generic state (no zeros, a unit quaternion on a floating root)."""
    q = pin.neutral(model)
    for i in range(model.nq):
        q[i] += 0.1 * (i % 7) + 0.05
    if model.joints[1].shortname() == "JointModelFreeFlyer":
        q[3:7] /= np.linalg.norm(q[3:7])
    v = np.array([0.3 - 0.07 * i for i in range(model.nv)])
    a = np.array([-0.5 + 0.11 * i for i in range(model.nv)])
    return q, v, a


def mimic_joint(model, full, i):
    """JointModelMimic i of `model`: its own type, read from `full` (the same
    file without the mimic option), following its master's joint."""
    jm = model.joints[i].extract()
    master = list(model.mimicked_joints)[list(model.mimicking_joints).index(i)]
    own = joint(full.joints[full.getJointId(model.names[i])])
    return f"pinocchio::JointModelMimic({own}, m.joints[{master}], {cpp(jm.scaling)}, {cpp(jm.offset)})"


def emit(name, model, full=None):
    lines = [f"inline pinocchio::Model build_{name}() {{", "  pinocchio::Model m;"]
    for i in range(1, model.njoints):
        jm = model.joints[i]
        made = mimic_joint(model, full, i) if jm.shortname() == "JointModelMimic" else joint(jm)
        lines.append(
            f"  m.addJoint({model.parents[i]}, {made}, "
            f"{se3(model.jointPlacements[i])}, \"{model.names[i]}\");")
        inertia = model.inertias[i]
        lines.append(
            f"  m.appendBodyToJoint({i}, pinocchio::Inertia({cpp(inertia.mass)}, "
            f"Eigen::Vector3d({vec(inertia.lever)}), "
            f"(Eigen::Matrix3d() << {vec(inertia.inertia)}).finished()), pinocchio::SE3::Identity());")
    lines.append(f"  m.lowerPositionLimit = (Eigen::VectorXd({model.nq}) << "
                 f"{vec(model.lowerPositionLimit)}).finished();")
    lines.append(f"  m.upperPositionLimit = (Eigen::VectorXd({model.nq}) << "
                 f"{vec(model.upperPositionLimit)}).finished();")
    lines.append("  return m;")
    lines.append("}")
    q, v, a = check_state(model)
    tau = pin.rnea(model, model.createData(), q, v, a)
    lines.append(f"inline Check check_{name}() {{")
    lines.append(f"  return {{(Eigen::VectorXd({model.nq}) << {vec(q)}).finished(),")
    lines.append(f"          (Eigen::VectorXd({model.nv}) << {vec(v)}).finished(),")
    lines.append(f"          (Eigen::VectorXd({model.nv}) << {vec(a)}).finished(),")
    lines.append(f"          (Eigen::VectorXd({model.nv}) << {vec(tau)}).finished()}};")
    lines.append("}")
    return "\n".join(lines)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, robots = sys.argv[1], sys.argv[2:]
    parts, table = [], []
    for spec in robots:
        path, _, kind = spec.partition(":")
        floating = kind == "floating"
        model = (pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating
                 else pin.buildModelFromUrdf(path, mimic=kind == "mimic"))
        key = os.path.basename(path) + (f":{kind}" if kind else "")
        ident = "".join(c if c.isalnum() else "_" for c in key)
        parts.append(emit(ident, model, pin.buildModelFromUrdf(path)))
        table.append((key, ident))
    dispatch = "\n".join(
        f"  if (key == \"{key}\") {{ m = build_{ident}(); c = check_{ident}(); }}"
        for key, ident in table)
    header = f"""// Written by scripts/reference/make_pinocchio_models.py from
// {', '.join(robots)} with Pinocchio {pin.__version__} (Python): the models
// as its URDF parser builds them, made with the header-only API.
#pragma once
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include "pinocchio/algorithm/rnea.hpp"  // brings Model, Data and the joints

namespace pinocchio_models {{

struct Check {{ Eigen::VectorXd q, v, a, tau; }};

{chr(10).join(parts)}

// The model of `key` (a URDF file name, with ":floating" for a free-flyer
// root, ":mimic" for the mimic option), checked against Python's rnea; exits
// on an unknown key or a
// mismatch.
inline pinocchio::Model build(const std::string& key) {{
  pinocchio::Model m;
  Check c;
{dispatch}
  if (m.njoints <= 1) {{ std::fprintf(stderr, "no model for %s: regenerate the header\\n", key.c_str()); std::exit(2); }}
  pinocchio::Data d(m);
  const Eigen::VectorXd tau = pinocchio::rnea(m, d, c.q, c.v, c.a);
  const double err = (tau - c.tau).norm() / std::max(1.0, c.tau.norm());
  if (!(err <= 1e-12)) {{ std::fprintf(stderr, "model %s differs from Python's: %g\\n", key.c_str(), err); std::exit(2); }}
  return m;
}}

}}  // namespace pinocchio_models
"""
    with open(out, "w") as f:
        f.write(header)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Collect the worked examples of the `modern_robotics` package's docstrings.

Writes dynagen/tests/data/modern_robotics_examples.json.

For each function below, the example in its docstring is taken from the
installed package source itself: the "Example Input" block is run as Python
(so the inputs are exactly the docstring's, including Mlist, Glist, Slist, g,
Ftip, dt and intRes), the printed "Output" block is kept as text and as the
numbers it shows, and the function is called again on the inputs to record
the output at full double precision.

Not run in CI.  See README.md in this folder.
"""

import inspect
import re
import sys
import textwrap
from importlib import metadata

import numpy as np
import modern_robotics as mr

from refcommon import DATA, REPO, dump_json

OUT = DATA / "modern_robotics_examples.json"

# Functions whose docstring example we record, in the order of the book.
FUNCTIONS = [
    # chapter 3: rigid-body motions
    "VecToso3", "MatrixExp3", "MatrixLog3", "TransInv", "VecTose3",
    "se3ToVec", "Adjoint", "ScrewToAxis", "MatrixExp6", "MatrixLog6",
    # chapter 4: forward kinematics
    "FKinBody", "FKinSpace",
    # chapter 5: velocity kinematics
    "JacobianBody", "JacobianSpace",
    # chapter 8: dynamics of open chains
    "ad", "InverseDynamics", "MassMatrix", "VelQuadraticForces",
    "GravityForces", "EndEffectorForces", "ForwardDynamics", "EulerStep",
    "InverseDynamicsTrajectory", "ForwardDynamicsTrajectory",
]

# The two trajectory examples print no numbers (they plot); their example
# code ends with the call itself, and is cut at the comment before plotting.
NO_PRINTED_OUTPUT = {"InverseDynamicsTrajectory", "ForwardDynamicsTrajectory"}

NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


def to_json(x):
    """numpy -> nested lists of float; tuples -> lists; ints kept as ints."""
    if isinstance(x, np.ndarray):
        return np.asarray(x, dtype=float).tolist()
    if isinstance(x, (list, tuple)):
        if len(x) and all(isinstance(e, np.ndarray) for e in x):
            return np.asarray(x, dtype=float).tolist()
        return [to_json(e) for e in x]
    if isinstance(x, (np.floating,)):
        return float(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    return x


def half_unit_last_place(token):
    """Half a unit in the last digit shown by a printed number."""
    mant, _, exp = token.lower().partition("e")
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return 0.5 * 10.0 ** (-decimals + (int(exp) if exp else 0))


def split_docstring(doc):
    """Return (input code, printed output text) of a docstring example."""
    lines = doc.splitlines()
    start = next(i for i, l in enumerate(lines)
                 if l.strip().lower().startswith("example input"))
    end = next((i for i, l in enumerate(lines)
                if i > start and (l.strip().startswith("Output")
                                  or l.strip().startswith("# Output"))),
               len(lines))
    code = textwrap.dedent("\n".join(lines[start + 1:end]))
    output = textwrap.dedent("\n".join(lines[end + 1:])).strip()
    return code, output


def main():
    version = metadata.version("modern_robotics")
    examples = []
    for name in FUNCTIONS:
        fn = getattr(mr, name)
        doc = inspect.getdoc(fn)
        code, printed = split_docstring(doc)
        code = code.replace("from __future__ import print_function", "")
        ns = {"np": np, "mr": mr}
        exec(compile(code, f"<{name} docstring>", "exec"), ns)
        params = list(inspect.signature(fn).parameters)
        inputs = {p: ns[p] for p in params}
        result = fn(*[inputs[p] for p in params])

        entry = {
            "function": name,
            "args": params,
            "inputs": {p: to_json(v) for p, v in inputs.items()},
        }
        if name in NO_PRINTED_OUTPUT:
            entry["docstring_output_text"] = None
            entry["docstring_output"] = None
            entry["note"] = (
                "The docstring prints no numbers for this example (it plots "
                "the result).  The inputs are those the docstring's example "
                "code builds; 'output' is the package's result on them.")
            if name == "InverseDynamicsTrajectory":
                entry["inputs_recipe"] = {
                    "thetastart": to_json(ns["thetastart"]),
                    "thetaend": to_json(ns["thetaend"]),
                    "Tf": ns["Tf"], "N": ns["N"], "method": ns["method"],
                    "how": ("thetamat = mr.JointTrajectory(thetastart, "
                            "thetaend, Tf, N, method); dthetamat and "
                            "ddthetamat are backward differences with "
                            "dt = Tf/(N-1) and a zero first row; Ftipmat = "
                            "ones((N, 6))"),
                }
            max_diff = None
        else:
            entry["docstring_output_text"] = printed
            numbers = [float(s) for s in NUMBER.findall(printed)]
            flat = np.concatenate([np.ravel(np.asarray(r, dtype=float))
                                   for r in (result if isinstance(result, tuple)
                                             else (result,))])
            if len(numbers) != flat.size:
                sys.exit(f"{name}: parsed {len(numbers)} printed numbers, "
                         f"result has {flat.size}")
            # Give the printed numbers the shape of the result.
            if isinstance(result, tuple):
                parts, k = [], 0
                for r in result:
                    n = np.size(r)
                    parts.append(np.reshape(numbers[k:k + n],
                                            np.shape(r)).tolist())
                    k += n
                entry["docstring_output"] = parts
            else:
                entry["docstring_output"] = np.reshape(
                    numbers, np.shape(result)).tolist()
            max_diff = float(np.max(np.abs(flat - np.asarray(numbers))))
            entry["max_abs_diff_docstring_vs_output"] = max_diff
            # Half a unit in the last printed digit of each number.
            half_ulp = np.array([half_unit_last_place(s)
                                 for s in NUMBER.findall(printed)])
            excess = np.abs(flat - np.asarray(numbers)) - half_ulp
            entry["docstring_within_printed_precision"] = bool(
                np.all(excess <= 1e-15 * np.maximum(1.0, np.abs(flat))))
        entry["output"] = to_json(result)
        examples.append(entry)
        print(f"{name:28s} max |docstring - recomputed| = {max_diff}"
              f"  within printed precision: "
              f"{entry.get('docstring_within_printed_precision')}")

    doc = {
        "source": {
            "package": "modern_robotics",
            "version": version,
            "python": sys.version.split()[0],
            "numpy": np.__version__,
            "script": "scripts/reference/make_mr_examples.py",
        },
        "notes": [
            "Examples from the docstrings of the modern_robotics package "
            "(Lynch & Park, Modern Robotics code library), read from the "
            "installed package source.",
            "'inputs' are exactly the docstring's example inputs, keyed by "
            "the function's parameter names; 'args' gives the call order.",
            "'docstring_output' is the output printed in the docstring "
            "(rounded, usually to 8 decimals or 9 significant digits); "
            "'output' is the installed package's result on the same inputs "
            "at full double precision.  Test against 'output' to ~1e-12 "
            "and against 'docstring_output' to the printed precision.",
            "Arrays are nested lists, row-major.  Slist / Blist are 6 x n "
            "(rows = screw components (omega; v), columns = joints), as in "
            "the library; Mlist is a list of 4x4 matrices (n + 1 of them, "
            "the last one M_{n,n+1} is the end-effector frame); Glist a list "
            "of 6x6 spatial inertias in (angular; linear) order.",
            "'docstring_within_printed_precision' says whether every "
            "recomputed number rounds to the printed one (|diff| <= half a "
            "unit in the last printed digit).",
            "Tuple results (EulerStep, ForwardDynamicsTrajectory) are lists "
            "of their parts.",
            "The 3-link examples' Slist is not a geometrically consistent "
            "description of the Mlist robot (its first column is (1,0,1,0,1,0), "
            "not a unit screw); the library does not check this, so the "
            "numbers are only meaningful as a test of the same computation.",
        ],
        "examples": examples,
    }
    dump_json(doc, OUT)
    print(f"wrote {OUT.relative_to(REPO)}")


if __name__ == "__main__":
    main()

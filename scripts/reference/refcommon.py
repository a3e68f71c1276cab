"""Shared helpers of the reference-data scripts (not run in CI)."""

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
DATA = REPO / "dynagen" / "tests" / "data"


def _is_number_list(x):
    return isinstance(x, list) and all(
        isinstance(e, (int, float)) and not isinstance(e, bool) for e in x)


def _fmt(x, indent, level):
    pad = " " * (indent * level)
    inner = " " * (indent * (level + 1))
    if isinstance(x, dict):
        if not x:
            return "{}"
        items = [f"{inner}{json.dumps(k)}: {_fmt(v, indent, level + 1)}"
                 for k, v in x.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(x, list):
        if _is_number_list(x):
            # A row of numbers on one line; floats at full precision (repr).
            return json.dumps(x)
        if not x:
            return "[]"
        items = [inner + _fmt(v, indent, level + 1) for v in x]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(x)


def dump_json(obj, path, indent=1):
    """Write obj as JSON, one matrix row per line, floats round-tripping."""
    text = _fmt(obj, indent, 0) + "\n"
    json.loads(text)  # it must parse
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(text)


# ---------------------------------------------------------------------------
# The UR5 of Modern Robotics (Lynch & Park), as given with the book's
# chapter-8 UR5 dynamics/simulation exercise and used with its code library:
# link frames {i} at the links' centres of mass, Mlist = [M01, ..., M67]
# (M67 is the end-effector frame), Glist = [G1, ..., G6] in frames {i},
# Slist 6 x 6 (rows = screw components (omega; v), columns = joints).
# dynagen/robots/ur5.urdf is built to be equivalent to these lists.
# ---------------------------------------------------------------------------
UR5_M01 = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.089159], [0, 0, 0, 1]]
UR5_M12 = [[0, 0, 1, 0.28], [0, 1, 0, 0.13585], [-1, 0, 0, 0], [0, 0, 0, 1]]
UR5_M23 = [[1, 0, 0, 0], [0, 1, 0, -0.1197], [0, 0, 1, 0.395], [0, 0, 0, 1]]
UR5_M34 = [[0, 0, 1, 0], [0, 1, 0, 0], [-1, 0, 0, 0.14225], [0, 0, 0, 1]]
UR5_M45 = [[1, 0, 0, 0], [0, 1, 0, 0.093], [0, 0, 1, 0], [0, 0, 0, 1]]
UR5_M56 = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.09465], [0, 0, 0, 1]]
UR5_M67 = [[1, 0, 0, 0], [0, 0, 1, 0.0823], [0, -1, 0, 0], [0, 0, 0, 1]]
UR5_MLIST = np.array([UR5_M01, UR5_M12, UR5_M23, UR5_M34, UR5_M45, UR5_M56,
                      UR5_M67], dtype=float)
UR5_GLIST = np.array([
    np.diag([0.010267495893, 0.010267495893, 0.00666, 3.7, 3.7, 3.7]),
    np.diag([0.22689067591, 0.22689067591, 0.0151074, 8.393, 8.393, 8.393]),
    np.diag([0.049443313556, 0.049443313556, 0.004095, 2.275, 2.275, 2.275]),
    np.diag([0.111172755531, 0.111172755531, 0.21942, 1.219, 1.219, 1.219]),
    np.diag([0.111172755531, 0.111172755531, 0.21942, 1.219, 1.219, 1.219]),
    np.diag([0.0171364731454, 0.0171364731454, 0.033822,
             0.1879, 0.1879, 0.1879]),
], dtype=float)
UR5_SLIST = np.array([
    [0, 0, 0, 0, 0, 0],
    [0, 1, 1, 1, 0, 1],
    [1, 0, 0, 0, -1, 0],
    [0, -0.089159, -0.089159, -0.089159, -0.10915, 0.005491],
    [0, 0, 0, 0, 0.81725, 0],
    [0, 0, 0.425, 0.81725, 0, 0.81725],
], dtype=float)


def file_order(path):
    """dynagen's joint order: moving joints depth first over the URDF tree,
    children in file order (Pinocchio may visit children in another)."""
    root = ET.parse(path).getroot()
    children, child_links = {}, set()
    for j in root.findall("joint"):
        children.setdefault(j.find("parent").get("link"), []).append(j)
        child_links.add(j.find("child").get("link"))
    roots = [l.get("name") for l in root.findall("link") if l.get("name") not in child_links]
    assert len(roots) == 1, roots
    order = []

    def visit(link):
        for j in children.get(link, []):
            if j.get("type") != "fixed":
                order.append(j.get("name"))
            visit(j.find("child").get("link"))

    visit(roots[0])
    return order

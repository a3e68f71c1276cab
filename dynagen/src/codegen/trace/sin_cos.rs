//! Sines and cosines as inputs: the body of `NAME_sc` from a traced
//! function of `q`, and back.

use crate::symbolic::{balance, factor, Graph, Latency, Node, NodeId, Rewrites, Traced};

/// A function traced with the sines and cosines of the joint angles as
/// inputs: `s[i]` and `c[i]` are the sine and cosine of joint `i`'s angle
/// θᵢ = `angle_scale[i]`·`q[q_offset + i]` (the scale is `|axis|`, 1 for a
/// unit axis; `None` for a joint whose angle the function does not read;
/// the offset 7 past a floating base's position and quaternion, else 0).
#[derive(Clone, Debug, PartialEq)]
pub struct SinCosTrace {
    /// The function, reading `s` and `c` instead of computing sines and
    /// cosines (and `q` only where a prismatic joint needs it).
    pub function: Traced,
    /// For each joint, the factor of `q[i]` in its angle, if it is read.
    pub angle_scale: Vec<Option<f64>>,
    /// Where joint 0's angle is in `q`.
    pub q_offset: usize,
}

/// A traced (unfactored) function of `q` with the sines and cosines of the
/// `n` joint angles `q[q_offset + i]` made inputs (see [`SinCosTrace`]), then
/// factored; `Err` names a sine of anything other than a joint angle (which
/// the algorithms never take).
pub fn sin_cos_inputs(f: &Traced, n: usize, q_offset: usize, rewrites: Rewrites) -> Result<SinCosTrace, String> {
    let nodes = f.nodes();
    let q = f.input_names().iter().position(|s| s == "q").map(|k| k as u32);
    let joint_of = |id: NodeId| match nodes[id as usize] {
        Node::Input { name, index } if Some(name) == q && index as usize >= q_offset => Some(index as usize - q_offset),
        _ => None,
    };
    let mut g = Graph::with_rewrites(rewrites);
    // Keep the input vectors' order (q, qd, …) and add s, c after them.
    for name in f.input_names() {
        g.input(name, 0);
    }
    let mut angle_scale: Vec<Option<f64>> = vec![None; n];
    let mut new: Vec<NodeId> = Vec::with_capacity(nodes.len());
    // For each SinCos node: its joint.
    let mut sc_joint: Vec<usize> = vec![usize::MAX; nodes.len()];
    for (id, node) in nodes.iter().enumerate() {
        if let Some(id) = g.arithmetic(node.map_operands(|x| new[x as usize])) {
            new.push(id);
            continue;
        }
        let mapped = match *node {
            Node::Const(_) => g.constant(node.constant().unwrap_or_default()),
            Node::Input { name, index } => g.input(&f.input_names()[name as usize], index as usize),
            Node::SinCos(a) => {
                let (joint, scale) = match (joint_of(a), nodes[a as usize]) {
                    (Some(i), _) => (i, 1.0),
                    (None, Node::Mul(x, y)) => match (joint_of(x), joint_of(y), nodes[x as usize], nodes[y as usize]) {
                        (Some(i), None, _, k) | (None, Some(i), k, _) => match k.constant() {
                            Some(k) => (i, k),
                            None => return Err(format!("{}: the sine of a non-angle", f.name())),
                        },
                        _ => return Err(format!("{}: the sine of a non-angle", f.name())),
                    },
                    _ => return Err(format!("{}: the sine of a non-angle", f.name())),
                };
                if angle_scale[joint].is_some_and(|k| k != scale) {
                    return Err(format!("{}: joint {joint} turns by two different angles", f.name()));
                }
                angle_scale[joint] = Some(scale);
                sc_joint[id] = joint;
                // Not read by anything but Sin and Cos, which map to inputs.
                g.constant(0.0)
            }
            Node::Sin(sc) => g.input("s", sc_joint[sc as usize]),
            Node::Cos(sc) => g.input("c", sc_joint[sc as usize]),
            _ => unreachable!("arithmetic is mapped above"),
        };
        new.push(mapped);
    }
    let outputs: Vec<NodeId> = f.outputs().iter().map(|&o| new[o as usize]).collect();
    let mut names = f.input_names().to_vec();
    for extra in ["s", "c"] {
        if !names.iter().any(|x| x == extra) {
            names.push(extra.to_string());
        }
    }
    let mut function = Traced::from_ids(f.name(), &g, &outputs);
    function.set_input_names(&names);
    let mut function = factor(&function, rewrites);
    if rewrites.reassociate {
        function = balance(&function, &Latency::default(), rewrites);
    }
    Ok(SinCosTrace { function, angle_scale, q_offset })
}

/// The inverse of [`sin_cos_inputs`]: `s[i]` and `c[i]` replaced by the
/// sine and cosine of `angle_scale[i]·q[q_offset + i]`, giving a function of `q` again
/// (for evaluation and operation counts of the `q` variant).
pub fn sin_cos_from_q(sc: &SinCosTrace, rewrites: Rewrites) -> Traced {
    let f = &sc.function;
    let mut g = Graph::with_rewrites(rewrites);
    for name in f.input_names() {
        if name != "s" && name != "c" {
            g.input(name, 0);
        }
    }
    let mut new: Vec<NodeId> = Vec::with_capacity(f.nodes().len());
    for node in f.nodes() {
        if let Some(id) = g.arithmetic(node.map_operands(|x| new[x as usize])) {
            new.push(id);
            continue;
        }
        let mapped = match *node {
            Node::Const(_) => g.constant(node.constant().unwrap_or_default()),
            Node::Input { name, index } => {
                let name = &f.input_names()[name as usize];
                if name == "s" || name == "c" {
                    let i = index as usize;
                    let q = g.input("q", sc.q_offset + i);
                    let scale = sc.angle_scale[i].unwrap_or(1.0);
                    let angle = if scale == 1.0 {
                        q
                    } else {
                        let k = g.constant(scale);
                        g.mul(q, k)
                    };
                    let (s, c) = g.sin_cos(angle);
                    if name == "s" {
                        s
                    } else {
                        c
                    }
                } else {
                    g.input(name, index as usize)
                }
            }
            Node::SinCos(_) | Node::Sin(_) | Node::Cos(_) => unreachable!("an _sc function has no sines"),
            _ => unreachable!("arithmetic is mapped above"),
        };
        new.push(mapped);
    }
    let outputs: Vec<NodeId> = f.outputs().iter().map(|&o| new[o as usize]).collect();
    let mut out = Traced::from_ids(f.name(), &g, &outputs);
    let names: Vec<String> = f.input_names().iter().filter(|n| *n != "s" && *n != "c").cloned().collect();
    out.set_input_names(&names);
    out
}

//! Sines and cosines as inputs: the body of `NAME_sc` from a traced
//! function of `q`, and back.

use crate::symbolic::{balance, factor, Graph, Latency, Node, NodeId, Rewrites, Traced};

/// A function traced with the sines and cosines of the joint angles as
/// inputs: `s[i]` and `c[i]` are the sine and cosine of joint `i`'s angle
/// θᵢ = `angle_scale[i]`·`q[q_offset + i]` (the scale is `|axis|`, 1 for a
/// unit axis; `None` for a joint whose angle the function does not read;
/// the offset 7 past a floating base's position and quaternion, else 0).
/// Past the joints', `s[n + e]` and `c[n + e]` are those of
/// `extra_angles[e]`: the angles of mimic joints that are not their
/// master's (a mimic joint at the master's angle reads the master's entry,
/// and one at its negation too, `sin(−θ) = −sin θ`).
#[derive(Clone, Debug, PartialEq)]
pub struct SinCosTrace {
    /// The function, reading `s` and `c` instead of computing sines and
    /// cosines (and `q` only where a prismatic joint needs it).
    pub function: Traced,
    /// For each joint, the factor of `q[i]` in its angle, if it is read.
    pub angle_scale: Vec<Option<f64>>,
    /// The angles read past the joints' own.
    pub extra_angles: Vec<Angle>,
    /// Where joint 0's angle is in `q`.
    pub q_offset: usize,
}

/// An angle of one joint's coordinate: `scale·q[q_offset + joint] + offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Angle {
    /// The joint (its index in the joint vectors).
    pub joint: usize,
    /// The factor of its coordinate.
    pub scale: f64,
    /// The constant added.
    pub offset: f64,
}

impl SinCosTrace {
    /// The number of angles `s` and `c` hold: one per joint, then the extra ones.
    pub fn angles(&self) -> usize {
        self.angle_scale.len() + self.extra_angles.len()
    }
}

/// The angle `id` as `scale·q[joint] + offset`, when it is one: a joint's
/// coordinate times and plus constants (`joint_of` finds the coordinates).
fn affine(nodes: &[Node], id: NodeId, joint_of: &dyn Fn(NodeId) -> Option<usize>) -> Option<Angle> {
    let constant = |x: NodeId| nodes[x as usize].constant();
    let scaled = |a: Angle, k: f64, o: f64| Angle { joint: a.joint, scale: k * a.scale, offset: k * a.offset + o };
    if let Some(joint) = joint_of(id) {
        return Some(Angle { joint, scale: 1.0, offset: 0.0 });
    }
    match nodes[id as usize] {
        Node::Neg(a) => Some(scaled(affine(nodes, a, joint_of)?, -1.0, 0.0)),
        Node::Mul(a, b) => match (constant(a), constant(b)) {
            (Some(k), None) => Some(scaled(affine(nodes, b, joint_of)?, k, 0.0)),
            (None, Some(k)) => Some(scaled(affine(nodes, a, joint_of)?, k, 0.0)),
            _ => None,
        },
        Node::Add(a, b) => match (constant(a), constant(b)) {
            (Some(o), None) => Some(scaled(affine(nodes, b, joint_of)?, 1.0, o)),
            (None, Some(o)) => Some(scaled(affine(nodes, a, joint_of)?, 1.0, o)),
            _ => None,
        },
        Node::Sub(a, b) => match (constant(a), constant(b)) {
            (Some(o), None) => Some(scaled(affine(nodes, b, joint_of)?, -1.0, o)),
            (None, Some(o)) => Some(scaled(affine(nodes, a, joint_of)?, 1.0, -o)),
            _ => None,
        },
        _ => None,
    }
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
    let mut extra_angles: Vec<Angle> = Vec::new();
    // For each SinCos node: its entry of s and c, and whether the angle is
    // that entry's negated.
    let mut sc_joint: Vec<(usize, bool)> = vec![(usize::MAX, false); nodes.len()];
    let new = f.copy_into(&mut g, |g, id, node, _| {
        Ok(match node {
            Node::Input { name, index } => g.input(&f.input_names()[name as usize], index as usize),
            Node::SinCos(a) => {
                let Some(angle) = affine(nodes, a, &joint_of) else {
                    return Err(format!("{}: the sine of a non-angle", f.name()));
                };
                sc_joint[id] = slot(angle, n, &mut angle_scale, &mut extra_angles);
                // Not read by anything but Sin and Cos, which map to inputs.
                g.constant(0.0)
            }
            Node::Sin(sc) => {
                let (k, negated) = sc_joint[sc as usize];
                let s = g.input("s", k);
                if negated {
                    g.neg(s)
                } else {
                    s
                }
            }
            Node::Cos(sc) => g.input("c", sc_joint[sc as usize].0),
            _ => unreachable!("arithmetic and constants are copied by copy_into"),
        })
    })?;
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
    Ok(SinCosTrace { function, angle_scale, extra_angles, q_offset })
}

/// The entry of `s` and `c` that holds `angle`, and whether the angle is
/// that entry's negated: a joint's own entry for its first angle without
/// offset (and for that angle negated), else an extra one.
fn slot(angle: Angle, n: usize, angle_scale: &mut [Option<f64>], extra: &mut Vec<Angle>) -> (usize, bool) {
    let Angle { joint, scale, offset } = angle;
    if offset == 0.0 {
        match angle_scale[joint] {
            None => {
                angle_scale[joint] = Some(scale);
                return (joint, false);
            }
            Some(k) if k == scale => return (joint, false),
            Some(k) if k == -scale => return (joint, true),
            Some(_) => {}
        }
    }
    let e = extra.iter().position(|a| *a == angle).unwrap_or_else(|| {
        extra.push(angle);
        extra.len() - 1
    });
    (n + e, false)
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
    let copied: Result<Vec<NodeId>, std::convert::Infallible> = f.copy_into(&mut g, |g, _, node, _| {
        Ok(match node {
            Node::Input { name, index } => {
                let name = &f.input_names()[name as usize];
                if name == "s" || name == "c" {
                    let i = index as usize;
                    let n = sc.angle_scale.len();
                    let Angle { joint, scale, offset } = match sc.extra_angles.get(i.wrapping_sub(n)) {
                        Some(a) if i >= n => *a,
                        _ => Angle { joint: i, scale: sc.angle_scale[i].unwrap_or(1.0), offset: 0.0 },
                    };
                    let q = g.input("q", sc.q_offset + joint);
                    let angle = if scale == 1.0 {
                        q
                    } else {
                        let k = g.constant(scale);
                        g.mul(q, k)
                    };
                    let o = g.constant(offset);
                    let angle = g.add(angle, o);
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
            _ => unreachable!("arithmetic and constants are copied by copy_into"),
        })
    });
    let Ok(new) = copied;
    let outputs: Vec<NodeId> = f.outputs().iter().map(|&o| new[o as usize]).collect();
    let mut out = Traced::from_ids(f.name(), &g, &outputs);
    let names: Vec<String> = f.input_names().iter().filter(|n| *n != "s" && *n != "c").cloned().collect();
    out.set_input_names(&names);
    out
}

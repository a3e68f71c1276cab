//! A traced function: the part of a graph its outputs reach.

use super::count::{CriticalPath, Latency, OpCount};
use super::expr::Expr;
use super::graph::Graph;
use super::node::{Node, NodeId};

/// A function of named input vectors: the nodes its outputs reach (dead
/// code eliminated), renumbered densely in topological order, and the
/// output nodes in output order. It owns its nodes, so it outlives the
/// trace that built it.
#[derive(Clone, Debug, PartialEq)]
pub struct Traced {
    name: String,
    nodes: Vec<Node>,
    input_names: Vec<String>,
    outputs: Vec<NodeId>,
}

impl Traced {
    /// Keeps what `outputs` reach in `graph` (dead code elimination).
    ///
    /// # Panics
    /// If an output is not a node of `graph`.
    pub fn new(name: &str, graph: &Graph, outputs: &[Expr]) -> Traced {
        let ids: Vec<NodeId> = outputs.iter().map(|e| e.id()).collect();
        Self::from_ids(name, graph, &ids)
    }
    /// As [`Traced::new`], with outputs given by node index.
    pub fn from_ids(name: &str, graph: &Graph, outputs: &[NodeId]) -> Traced {
        let nodes = graph.nodes();
        let mut live = vec![false; nodes.len()];
        for &o in outputs {
            live[o as usize] = true;
        }
        // Operands come before their users, so one backward sweep marks
        // everything reachable.
        for id in (0..nodes.len()).rev() {
            if live[id] {
                for op in nodes[id].operands() {
                    live[op as usize] = true;
                }
            }
        }
        let mut new_id = vec![NodeId::MAX; nodes.len()];
        let mut kept = Vec::new();
        for (id, node) in nodes.iter().enumerate() {
            if live[id] {
                new_id[id] = kept.len() as NodeId;
                kept.push(node.map_operands(|x| new_id[x as usize]));
            }
        }
        Traced {
            name: name.to_string(),
            nodes: kept,
            input_names: graph.input_names().to_vec(),
            outputs: outputs.iter().map(|&o| new_id[o as usize]).collect(),
        }
    }
    /// Copies the nodes into `g` in order, arithmetic through its
    /// simplifying constructors and constants as constants; every other node
    /// (an input, a sine or cosine) is `leaf(g, id, node, copied)`, with the
    /// ids of the nodes copied before it. Returns every node's id in `g`.
    pub fn copy_into<E>(
        &self,
        g: &mut Graph,
        mut leaf: impl FnMut(&mut Graph, usize, Node, &[NodeId]) -> Result<NodeId, E>,
    ) -> Result<Vec<NodeId>, E> {
        let mut new: Vec<NodeId> = Vec::with_capacity(self.nodes.len());
        for (id, node) in self.nodes.iter().enumerate() {
            let x = match g.arithmetic(node.map_operands(|x| new[x as usize])) {
                Some(x) => x,
                None => match node.constant() {
                    Some(c) => g.constant(c),
                    None => leaf(g, id, *node, &new)?,
                },
            };
            new.push(x);
        }
        Ok(new)
    }
    /// The function's name.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// The kept nodes, operands before users.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }
    /// The output nodes, in output order.
    pub fn outputs(&self) -> &[NodeId] {
        &self.outputs
    }
    /// How many times each node is read: as an operand of another node,
    /// or as an output (one count per output slot).
    pub fn use_counts(&self) -> Vec<u32> {
        let mut uses = vec![0u32; self.nodes().len()];
        for n in self.nodes() {
            for op in n.operands() {
                uses[op as usize] += 1;
            }
        }
        for &o in self.outputs() {
            uses[o as usize] += 1;
        }
        uses
    }
    /// The names of the input vectors ([`Node::Input::name`] indexes them).
    pub fn input_names(&self) -> &[String] {
        &self.input_names
    }
    /// Whether some kept node reads the input vector `name`.
    pub fn uses_input(&self, name: &str) -> bool {
        let Some(k) = self.input_names.iter().position(|s| s == name) else { return false };
        self.nodes.iter().any(|n| matches!(n, Node::Input { name, .. } if *name as usize == k))
    }
    pub(crate) fn set_input_names(&mut self, names: &[String]) {
        // Renumber the inputs to the given name table.
        let old = std::mem::replace(&mut self.input_names, names.to_vec());
        for n in &mut self.nodes {
            if let Node::Input { name, .. } = n {
                let s = &old[*name as usize];
                *name = self.input_names.iter().position(|x| x == s).expect("input name kept") as u32;
            }
        }
    }
    /// The operation count.
    pub fn op_count(&self) -> OpCount {
        OpCount::of(&self.nodes)
    }
    /// The latency-weighted depth with the default [`Latency`] (see
    /// [`CriticalPath`]).
    pub fn critical_path(&self) -> CriticalPath {
        CriticalPath::of(&self.nodes, &self.outputs, &Latency::default())
    }
}

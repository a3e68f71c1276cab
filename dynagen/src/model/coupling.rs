//! Mimic couplings indexed: which column of the joint vectors each body's
//! motion is in, and the tree the sparse LᵀDL factorisation of M follows.
//!
//! A body whose joint follows a master ([`Mimic`]) has no coordinate of its
//! own: with G the coupling matrix (one row per body, one column per joint
//! with a coordinate, `G[i][column(i)] = multiplier`, 1 for an independent
//! joint), the bodies' joint rates are `G q̇` and M = GᵀM_tree G. Two joints
//! then share an entry of M when a body of one and a body of the other lie
//! on one path from the root, which need not make a tree over the columns:
//! the factorisation follows the elimination tree of that pattern instead
//! (for a model without mimic joints, the kinematic tree itself).

use super::{Body, Mimic};

/// The couplings of a model's bodies, indexed (see the module docs).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Coupling {
    /// Per body: the joint it follows, if any.
    pub(crate) mimic: Vec<Option<Mimic>>,
    /// Per body: the column of its motion in the joint vectors (its
    /// master's for a mimic joint).
    pub(crate) column: Vec<usize>,
    /// Per column: the body of the joint it belongs to.
    pub(crate) body: Vec<usize>,
    /// Per column: its parent in the tree the LᵀDL factorisation of M
    /// follows (`parent < column`).
    pub(crate) parent: Vec<Option<usize>>,
}

impl Coupling {
    /// The couplings of `bodies` (in topological order), `mimic` per body
    /// with every master a body that follows no other.
    pub(crate) fn new(bodies: &[Body], mimic: Vec<Option<Mimic>>) -> Self {
        assert_eq!(bodies.len(), mimic.len(), "Coupling::new: one entry per body");
        let body: Vec<usize> = (0..bodies.len()).filter(|&i| mimic[i].is_none()).collect();
        let mut column = vec![usize::MAX; bodies.len()];
        for (k, &b) in body.iter().enumerate() {
            column[b] = k;
        }
        for (i, m) in mimic.iter().enumerate() {
            if let Some(m) = m {
                column[i] = column[m.master];
            }
        }
        let parent = if mimic.iter().all(Option::is_none) {
            bodies.iter().map(|b| b.parent).collect()
        } else {
            elimination_tree(bodies, &column, body.len())
        };
        Coupling { mimic, column, body, parent }
    }
    /// The number of columns (joints with a coordinate of their own).
    pub(crate) fn dof(&self) -> usize {
        self.body.len()
    }
    /// Whether some body follows another's joint.
    pub(crate) fn any(&self) -> bool {
        self.body.len() != self.mimic.len()
    }
}

/// The elimination tree of the pattern of M = GᵀM_tree G, eliminating from
/// the last column to the first as `ldlt::factorise` does: a column's
/// parent is the largest lower column it shares an entry with after the
/// fill-in of the columns eliminated before it. Every lower column a column
/// shares an entry with is then on its chain of parents.
fn elimination_tree(bodies: &[Body], column: &[usize], n: usize) -> Vec<Option<usize>> {
    let mut linked = vec![false; n * n];
    for i in 0..bodies.len() {
        // body i and each of its ancestors (and itself) lie on one path
        let mut a = Some(i);
        while let Some(j) = a {
            let (ci, cj) = (column[i], column[j]);
            linked[ci * n + cj] = true;
            linked[cj * n + ci] = true;
            a = bodies[j].parent;
        }
    }
    let mut parent = vec![None; n];
    for k in (0..n).rev() {
        let lower: Vec<usize> = (0..k).filter(|&c| linked[k * n + c]).collect();
        if let Some(&p) = lower.last() {
            parent[k] = Some(p);
            for &c in &lower[..lower.len() - 1] {
                linked[p * n + c] = true;
                linked[c * n + p] = true;
            }
        }
    }
    parent
}

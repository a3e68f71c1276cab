// An inline per-joint value given twice is an error on the second name
// (an inline value replaces a scene file's, but not another inline one).
mod arm {
    dynagen_macros::robot! {
        name: arm2,
        armature: { shoulder: 0.1, elbow: 0.2, shoulder: 0.3 },
        link base {},
        link upper { mass: 2.0, com: [0.5, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        link fore { mass: 1.5, com: [0.4, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        joint shoulder: revolute(base -> upper) { axis: [0, 0, 1] },
        joint elbow: revolute(upper -> fore) { origin: [1.0, 0, 0], axis: [0, 1, 0] },
    }
}

fn main() {}

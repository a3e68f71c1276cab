mod arm {
    dynagen_macros::robot! {
        name: arm3,
        gravity: sideways,
        link base {},
        link upper { mass: 2.0, com: [0.5, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        link fore { mass: 1.5, com: [0.4, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        link hand { mass: 0.5, com: [0.05, 0, 0], inertia: [0.001, 0.001, 0.001, 0, 0, 0] },
        joint shoulder: revolute(base -> upper) { axis: [0, 0, 1] },
        joint elbow: revolute(upper -> fore) { origin: [1.0, 0, 0], axis: [0, 1, 0] },
        joint wrist: revolute(fore -> hand) { origin: [0.8, 0, 0], axis: [1, 0, 0] },
    }
}

fn main() {}

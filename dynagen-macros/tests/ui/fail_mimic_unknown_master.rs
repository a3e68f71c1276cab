mod gripper {
    dynagen_macros::robot! {
        name: gripper,
        link palm {},
        link left { mass: 0.1, com: [0, 0.01, 0.02], inertia: [1e-5, 1e-5, 1e-5, 0, 0, 0] },
        link right { mass: 0.1, com: [0, -0.01, 0.02], inertia: [1e-5, 1e-5, 1e-5, 0, 0, 0] },
        joint slide: prismatic(palm -> left) { axis: [0, 1, 0] },
        joint mirror: prismatic(palm -> right) { axis: [0, -1, 0], mimic: slid },
    }
}

fn main() {}

mod arm {
    dynagen_macros::robot! {
        name: arm1,
        scene: "scenes/no_such_scene.toml",
        link base {},
        link upper { mass: 2.0, com: [0.5, 0, 0], inertia: [0.01, 0.02, 0.02, 0, 0, 0] },
        joint shoulder: revolute(base -> upper) { axis: [0, 0, 1] },
    }
}

fn main() {}

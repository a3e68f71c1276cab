mod pendulum {
    dynagen_macros::robot! {
        name: pendulum,
        functions: [mass_matrix, jacobian],
        link base {},
        link arm { mass: 1.0, com: [0, 0, -0.5] },
        joint hinge: revolute(base -> arm) { axis: [0, 1, 0] },
    }
}

fn main() {}

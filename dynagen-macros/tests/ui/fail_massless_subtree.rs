mod pendulum {
    dynagen_macros::robot! {
        name: pendulum,
        link base {},
        link arm { mass: 1.0, com: [0, 0, -0.5] },
        link ghost {},
        joint hinge: revolute(base -> arm) { axis: [0, 1, 0] },
        joint spin: revolute(arm -> ghost) { axis: [0, 0, 1] },
    }
}

fn main() {}

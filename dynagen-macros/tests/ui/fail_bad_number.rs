mod pendulum {
    dynagen_macros::robot! {
        name: pendulum,
        link base {},
        link arm { mass: heavy, com: [0, 0, -0.5] },
        joint hinge: revolute(base -> arm) { axis: [0, 1, 0] },
    }
}

fn main() {}

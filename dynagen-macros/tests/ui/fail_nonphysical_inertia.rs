// A rotational inertia that is not positive semi-definite is refused,
// naming the link and the option that accepts it.
mod arm {
    dynagen_macros::robot! {
        name: arm,
        link base {},
        link upper { mass: 2.0, com: [0.5, 0, 0], inertia: [-0.01, 0.02, 0.02, 0, 0, 0] },
        joint shoulder: revolute(base -> upper) { axis: [0, 0, 1] },
    }
}

fn main() {}

// With `allow_nonphysical_inertia: true` the same robot is accepted (as
// Pinocchio does) and its dynamics are generated from the numbers given:
// M = I_zz + m·|c|² about the shoulder's z axis, even with ixx < 0.
mod arm {
    dynagen_macros::robot! {
        name: arm,
        allow_nonphysical_inertia: true,
        functions: [mass_matrix],
        link base {},
        link upper { mass: 2.0, com: [0.5, 0, 0], inertia: [-0.01, 0.02, 0.02, 0, 0, 0] },
        joint shoulder: revolute(base -> upper) { axis: [0, 0, 1] },
    }
}

fn main() {
    let m = arm::mass_matrix(&[0.3]);
    assert!((m[0][0] - (0.02 + 2.0 * 0.25)).abs() < 1e-15, "{m:?}");
}

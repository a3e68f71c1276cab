//! A robot file whose every name tries to break out of where it lands in
//! the generated code (`dynagen/tests/data/hostile_names.urdf` and its scene:
//! newlines, CR, `*/`, quotes, backslashes, U+2028/U+2029, bidirectional
//! controls). That this crate compiles (the workspace's clippy runs with
//! `-D warnings`) shows that `urdf!` wrote nothing but its items; the names
//! come back as they are in `JOINT_NAMES`. `dynagen-macros`' own test lists
//! the expansion's items.

dynagen_macros::urdf!(
    "../../dynagen/tests/data/hostile_names.urdf",
    scene = "../../dynagen/tests/data/hostile_names.toml",
);

#[cfg(test)]
mod tests {
    #[test]
    fn the_names_are_strings_and_the_functions_run() {
        let inj = "pub fn injected() -> u32 { 42 }";
        assert_eq!(super::JOINT_NAMES[0], format!("J\n{inj}\n//"));
        assert_eq!(super::JOINT_NAMES[3], format!("J\u{2028}{inj}\u{2029}//"));
        assert_eq!(super::JOINT_NAMES[4], format!("J\"); {inj} //\\"));
        // The frame "h\n}\nfn injected() {\n" at q = 0: each joint origin is
        // 0.2 m up its parent's z, the frame 0.1 m above the last link, and the
        // scene locks the fifth joint (axis (0.8, 0, 0.6)) at 0.3 rad, which
        // turns the last 0.5 m: p = (0, 0, 1) + 0.5 R(k, 0.3) z (Rodrigues).
        let pose = super::frame_pose_h_fn_injected(&[0.0; super::DOF]);
        let (k, (s, c)) = ([0.8, 0.0, 0.6], 0.3f64.sin_cos());
        let rz = [k[0] * k[2] * (1.0 - c), -k[0] * s, c + k[2] * k[2] * (1.0 - c)];
        for (i, want) in [0.5 * rz[0], 0.5 * rz[1], 1.0 + 0.5 * rz[2]].iter().enumerate() {
            assert!((pose[i][3] - want).abs() < 1e-12, "{pose:?}");
        }
        let tau = super::gravity_torques(&[0.1; super::DOF], &[0.0; 10]);
        assert!(tau.iter().all(|t| t.is_finite()));
    }
}

//! Writes the UR5's dynamics into OUT_DIR/ur5.rs, as a user's build script would.

fn main() {
    dynagen::Builder::new()
        .urdf("../../dynagen/robots/ur5.urdf")
        .functions(&["mass_matrix", "bias_forces", "forward_dynamics"])
        .generate()
        .expect("generating the UR5 dynamics");
}

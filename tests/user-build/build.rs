//! Writes the UR5's dynamics into OUT_DIR/ur5.rs, and the planar arm's into
//! OUT_DIR/planar_2link.rs, as a user's build script would.

fn main() {
    dynagen::Builder::new()
        .urdf("../../dynagen/robots/ur5.urdf")
        .functions(&["mass_matrix", "bias_forces", "forward_dynamics"])
        .generate()
        .expect("generating the UR5 dynamics");
    // All five functions of the planar arm, of which src/lib.rs calls one
    // from a private module: it compiles without a dead-code warning.
    dynagen::Builder::new().urdf("../../dynagen/robots/planar_2link.urdf").generate().expect("the planar arm");
}

mod arm {
    dynagen_macros::urdf!("robots/arm.urdf", scene = "scenes/no_such_scene.toml");
}

fn main() {}

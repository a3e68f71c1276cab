mod ur5 {
    dynagen_macros::urdf!("robots/ur5.urdf", scalar = f32, colour = red);
}

fn main() {}

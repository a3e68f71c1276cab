mod ur5 {
    dynagen_macros::urdf!("robots/ur5.urdf", trig = batched, split_lets = 0);
}

fn main() {}

mod ur5 {
    dynagen_macros::urdf!("robots/no_such_robot.urdf");
}

fn main() {}

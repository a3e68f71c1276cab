mod hand {
    dynagen_macros::robot! {
        name: hand,
        link palm {},
        link a { mass: 0.1 },
        link b { mass: 0.1 },
        joint slide: prismatic(palm -> a) { axis: [0, 1, 0] },
        joint mirror: prismatic(palm -> b) { axis: [0, -1, 0], mimic: slid },
    }
}

fn main() {}

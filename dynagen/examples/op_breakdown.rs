//! Prints what the operations of the generated UR5 functions are.
//! `cargo run -p dynagen --example op_breakdown [path.urdf]`

use dynagen::codegen::{generate, CodegenOptions};
use dynagen::symbolic::Node;
use dynagen::Model;

fn main() {
    let path =
        std::env::args().nth(1).unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf").into());
    let model = Model::from_urdf_file(&path).unwrap();
    let module = generate(&model, &CodegenOptions::default()).unwrap();
    for f in &module.functions {
        let nodes = f.traced.nodes();
        let kind = |id: u32| match nodes[id as usize] {
            Node::Const(_) => "const",
            Node::Input { .. } => "input",
            Node::Sin(_) | Node::Cos(_) => "trig",
            _ => "op",
        };
        let mut mul_const = 0;
        let mut mul_trig = 0;
        let mut mul_other = 0;
        let mut addsub_const = 0;
        for n in nodes {
            match *n {
                Node::Mul(a, b) => match (kind(a), kind(b)) {
                    ("const", _) | (_, "const") => mul_const += 1,
                    ("trig", _) | (_, "trig") => mul_trig += 1,
                    _ => mul_other += 1,
                },
                Node::Add(a, b) | Node::Sub(a, b) if kind(a) == "const" || kind(b) == "const" => addsub_const += 1,
                _ => {}
            }
        }
        println!(
            "{:32} {}\n{:32} mul by constant {mul_const}, by sin/cos {mul_trig}, other {mul_other}; add/sub of a constant {addsub_const}",
            f.label(),
            f.op_count,
            ""
        );
    }
}

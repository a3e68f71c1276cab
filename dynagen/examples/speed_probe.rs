use dynagen::codegen::{generate, CodegenOptions};
use dynagen::Model;
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let model = Model::from_urdf_file(&path).unwrap();
    let module = generate(&model, &CodegenOptions::default()).unwrap();
    std::fs::write("/tmp/speed/out.rs", &module.source).unwrap();
}

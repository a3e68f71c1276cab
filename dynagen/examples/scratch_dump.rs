use dynagen::codegen::{regroup_inertia, slide_origins_along_axes, snap_rounding};
use dynagen::Model;
fn main() {
    let path =
        std::env::args().nth(1).unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.urdf").into());
    let model = Model::from_urdf_file(&path).unwrap();
    let (m, _) = snap_rounding(&model);
    let m = regroup_inertia(&slide_origins_along_axes(&m));
    for (i, b) in m.bodies.iter().enumerate() {
        println!(
            "body {i} parent {:?} kind {:?} axis {:?} align {:?} rotid {}",
            b.parent, b.joint.kind, b.joint.axis.0, b.joint.alignment, b.joint.placement_rotation_is_identity
        );
        println!("   rot {:?} trans {:?}", b.joint.placement.rot.0, b.joint.placement.trans.0);
        println!("   mass {} h {:?} ibar {:?}", b.inertia.mass, b.inertia.h.0, b.inertia.ibar.0);
    }
}

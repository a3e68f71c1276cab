//! A stable content hash of a model, for the generated file's header.

use crate::model::Model;
use std::fmt::Write;

/// The 64-bit FNV-1a hash of `bytes`.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// The model as text, one line per item, every number in shortest
/// round-trip form: what the content hash is taken of. Two models with the
/// same text have the same dynamics.
pub fn canonical_text(model: &Model) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "robot {:?} root {:?} gravity {:?}", model.name, model.root, model.gravity.0);
    for (i, b) in model.bodies.iter().enumerate() {
        let j = &b.joint;
        let _ = writeln!(
            s,
            "body {i} {:?} parent {:?} joint {:?} {:?} rot {:?} trans {:?} axis {:?} mass {:?} h {:?} ibar {:?}",
            b.name,
            b.parent,
            j.name,
            j.kind,
            j.placement.rot.0,
            j.placement.trans.0,
            j.axis.0,
            b.inertia.mass,
            b.inertia.h.0,
            b.inertia.ibar.0
        );
        // (only for a mimic joint: the text of other models is as it was)
        if let Some(m) = model.mimic(i) {
            let _ = writeln!(s, "mimic {i} master {} multiplier {:?} offset {:?}", m.master, m.multiplier, m.offset);
        }
    }
    for f in &model.frames {
        let _ = writeln!(
            s,
            "frame {:?} body {:?} rot {:?} trans {:?}",
            f.name, f.body, f.placement.rot.0, f.placement.trans.0
        );
    }
    s
}

/// FNV-1a of [`canonical_text`].
pub fn model_hash(model: &Model) -> u64 {
    fnv1a64(canonical_text(model).as_bytes())
}

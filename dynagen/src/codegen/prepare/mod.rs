//! Preparing the model: changes that are exact within the file's precision
//! and make the unrolled code shorter. Constants that are 0 or ±1 up to
//! rounding become exactly that ([`snap_rounding`]); inertia a joint cannot
//! move goes to its parent ([`regroup_inertia`], after moving body frames
//! where they cost less: [`center_prismatic_leaves`],
//! [`slide_origins_along_axes`]). [`model_hash`] names the model a module
//! was made from.

mod hash;
mod regroup;
mod rounding;

pub use hash::{canonical_text, fnv1a64, model_hash};
pub use regroup::{center_prismatic_leaves, regroup_inertia, slide_origins_along_axes};
pub use rounding::{snap_rounding, SnappedConstant, ROUNDING_TOLERANCE};

use super::CodegenOptions;
use crate::model::Model;
use crate::scene::SceneModel;

/// `model` snapped and regrouped as `options` ask, and the constants the
/// snap changed.
pub(crate) fn prepare_model(model: &Model, options: &CodegenOptions) -> (Model, Vec<SnappedConstant>) {
    let (snapped_model, snapped) =
        if options.snap_rounding { snap_rounding(model) } else { (model.clone(), Vec::new()) };
    // The regrouping gives the inertia a joint cannot move to its parent (a
    // fixed base drops it, a floating base carries it).
    let prepared = if options.regroup_inertia {
        let centred = center_prismatic_leaves(&snapped_model);
        // With branch loops, the parents of branches keep their origins.
        let keep: Vec<usize> = match options.branch_loops {
            true => super::trace::branches::groups(&centred, super::trace::branches::MIN_BODIES)
                .iter()
                .filter_map(|g| g.parent)
                .collect(),
            false => Vec::new(),
        };
        regroup_inertia(&regroup::slide_origins_except(&centred, &keep))
    } else {
        snapped_model
    };
    (prepared, snapped)
}

/// The scene code is generated from: `scene` with its reduced model
/// prepared as `options` ask ([`prepare_model`]; the regrouping is exact
/// for every function of a scene, as frames move with the slid bodies and
/// armature, friction and run-time payloads do not depend on the bodies'
/// own inertias), and the constants the snap changed.
pub fn prepare(scene: &SceneModel, options: &CodegenOptions) -> (SceneModel, Vec<SnappedConstant>) {
    let (model, snapped) = prepare_model(&scene.model, options);
    (SceneModel { model, ..scene.clone() }, snapped)
}

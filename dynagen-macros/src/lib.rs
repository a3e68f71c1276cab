//! The proc-macros of dynagen (`urdf!`, `robot!`). They hold no dynamics:
//! they parse their input and call dynagen's code generator. They are
//! filled in with code generation; for now the crate only builds.

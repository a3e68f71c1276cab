//! Generated dynamics of the bundled robots: `no_std`, no dependencies.
//! The modules are added with code generation.
#![no_std]

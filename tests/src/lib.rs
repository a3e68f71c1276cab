//! Integration tests across dynagen's crates live in `tests/tests/`.

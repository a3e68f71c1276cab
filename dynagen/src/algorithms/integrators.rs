//! Time integration of the forward dynamics. Filled in with the
//! trajectory functions.

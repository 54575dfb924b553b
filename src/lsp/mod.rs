//! `ptsc lsp`: a Language Server Protocol 3.17 server over stdio.

pub mod position;
pub mod transport;

//! `ptsc lsp`: a Language Server Protocol 3.17 server over stdio, built on
//! `lsp-server` (rust-analyzer's synchronous main loop) and `lsp-types`.
//! The server holds the editor's documents, checks them on a background
//! thread through the one compile driver (open documents win over the
//! disk: `MemoryFiles::over_disk`), and answers requests from `ide`.
//!
//! ```text
//! stdin ─transport─▶ server (documents, last checks) ─handlers─▶ ide ─▶ compile/check/syntax
//!                        │ ▲
//!                   jobs ▼ │ results
//!                      checker thread
//! ```

pub mod checker;
pub mod convert;
mod format;
pub mod handlers;
pub mod position;
pub mod server;
pub mod state;
pub mod transport;

pub use server::{serve, Ending};

/// Serves over stdin and stdout until the editor says `exit` (or closes
/// the input); `true` for a clean ending (`shutdown` first).
pub fn run_stdio() -> bool {
    let (connection, threads) = transport::stdio();
    let ending = serve(&connection);
    drop(connection);
    threads.join();
    ending == Ending::Clean
}

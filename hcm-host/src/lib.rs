//! hcm-host: the std side of hybrid contact modeling — the pipeline stages behind the
//! `hcm` command line. The library computes and returns values; only the CLI
//! (`src/cli/`) prints.
//!
//! The modules are layered, each using only those of the layers below it (bottom
//! first; `tests/repository/layers.rs` checks it):
//!
//! 1. [`numerics`], [`output`], [`law_catalogue`], [`progress`] — generic numerics and
//!    optimisers, atomic file output, laws by name, how a stage reports progress;
//! 2. [`input`] — files read within a size limit, messages quoting excerpts;
//! 3. [`residual`] — the stored residual network;
//! 4. [`scenario`] — scenario files, assignments, contact geometry;
//! 5. [`dataset`] — measured data;
//! 6. [`indicators`] — the paper's indicators of contact events;
//! 7. [`simulate`] — the simulator;
//! 8. [`experiment`], [`replay`], [`figure`] — noisy experiments, replays of recorded motion (tosses), figures;
//! 9. [`identify`] — physics parameters (PM2);
//! 10. [`train`], [`evaluate`] — the residual network, held-out evaluation;
//! 11. [`export`] — the blob a controller embeds;
//! 12. [`diagnose`] — what the simulation gets wrong, and why;
//! 13. [`pipeline`] — `hcm reproduce`'s presets over the stages.
//!
//! Each module is a facade: its submodules are private and what the other layers, the
//! CLI and the tests use is re-exported at its top (`hcm_host::diagnose::BaseFreedom`).
//! The regime a data file puts a stage in — 1D force, 3D wrench at poses, poses alone —
//! is [`dataset::Evidence`], decided once from the model and the data.

#![warn(missing_docs)]
// Module docs name the private submodules that hold each part, for readers of the source
// (`cargo doc --document-private-items` renders those links); the public API is the facades.
#![allow(rustdoc::private_intra_doc_links)]

pub mod dataset;
pub mod diagnose;
pub mod evaluate;
pub mod experiment;
pub mod export;
pub mod figure;
pub mod identify;
pub mod indicators;
pub mod input;
pub mod law_catalogue;
pub mod numerics;
pub mod output;
pub mod pipeline;
pub mod progress;
pub mod replay;
pub mod residual;
pub mod scenario;
pub mod simulate;
pub mod train;

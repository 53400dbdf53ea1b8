//! hcm-host: the std side of hybrid contact modeling — the pipeline stages behind the
//! `hcm` command line. The library computes and returns values; only the CLI
//! (`src/cli/`) prints.
//!
//! The modules are layered, each using only those of the layers below it (bottom
//! first; `tests/layers.rs` checks it):
//!
//! 1. [`numerics`], [`input`], [`output`], [`law_catalogue`], [`progress`] — generic
//!    numerics and optimisers, files read within a size limit, atomic file output,
//!    laws by name, how a stage reports progress;
//! 2. [`residual`] — the stored residual network;
//! 3. [`scenario`] — scenario files, assignments, contact geometry;
//! 4. [`dataset`] — measured data;
//! 5. [`indicators`] — the paper's indicators of contact events;
//! 6. [`simulate`] — the simulator;
//! 7. [`experiment`], [`toss`], [`figure`] — noisy experiments, toss replays, figures;
//! 8. [`identify`] — physics parameters (PM2);
//! 9. [`train`], [`evaluate`] — the residual network, held-out evaluation;
//! 10. [`export`] — the blob a controller embeds;
//! 11. [`diagnose`] — what the simulation gets wrong, and why;
//! 12. [`pipeline`] — `hcm reproduce`'s presets over the stages.

#![warn(missing_docs)]

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
pub mod residual;
pub mod scenario;
pub mod simulate;
pub mod toss;
pub mod train;

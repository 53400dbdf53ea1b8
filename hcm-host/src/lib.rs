//! hcm-host: the std side of hybrid contact modeling — the pipeline stages behind the
//! `hcm` command line. The library computes and returns values; only the CLI
//! (`src/cli/`) prints.

pub mod dataset;
pub mod diagnose;
pub mod evaluate;
pub mod experiment;
pub mod export;
pub mod figure;
pub mod identify;
pub mod indicators;
pub mod law_catalogue;
pub mod numerics;
pub mod output;
pub mod pipeline;
pub mod residual;
pub mod scenario;
pub mod simulate;
pub mod toss;
pub mod train;

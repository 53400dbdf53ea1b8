//! Puts `memory.x` (and an empty `device.x`) where cortex-m-rt's `link.x` finds it (the linker's search path).

use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("memory.x beside Cargo.toml");
    // cortex-m-rt's `device` feature includes the device's interrupt handler names;
    // the firmware handles no interrupt, so there are none.
    fs::write(out.join("device.x"), "/* no interrupt handlers */\n").expect("OUT_DIR writable");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
}

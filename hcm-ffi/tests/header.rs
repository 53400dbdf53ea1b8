//! The checked-in C header (`include/hcm.h`) is not stale: every exported function,
//! constant, struct and status code of the crate appears in it, with the same value,
//! and the header declares no function the library lacks. Where `cbindgen` is
//! installed, the header must also be exactly what it generates now.

use hcm_ffi::{hcm_status_name, HcmStatus};
use std::ffi::CStr;
use std::path::{Path, PathBuf};
use std::process::Command;

fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn header() -> String {
    let path = crate_dir().join("include/hcm.h");
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The crate's sources, concatenated.
fn sources() -> String {
    let folder = crate_dir().join("src");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "rs"))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|path| std::fs::read_to_string(path).unwrap())
        .collect()
}

/// The word after `marker` on every line that contains it (up to a non-identifier).
fn names_after<'a>(text: &'a str, marker: &str) -> Vec<&'a str> {
    text.lines()
        .filter_map(|line| line.split_once(marker).map(|(_, rest)| rest))
        .map(|rest| {
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            &rest[..end]
        })
        .collect()
}

#[test]
fn every_exported_function_is_declared_and_no_other() {
    let (sources, header) = (sources(), header());
    let mut exported = names_after(&sources, "extern \"C\" fn ");
    exported.sort();
    assert!(exported.len() >= 8, "{exported:?}");
    // Each one is `#[no_mangle]` (the line above it, or two above with `unsafe`).
    let no_mangle = sources.matches("#[no_mangle]").count();
    assert_eq!(no_mangle, exported.len(), "{exported:?}");
    // Declarations start a line with their return type: `HcmStatus hcm_…(`,
    // `const char *hcm_…(`.
    let mut declared: Vec<String> = header
        .lines()
        .filter(|line| line.starts_with("HcmStatus ") || line.starts_with("const char *"))
        .flat_map(|line| names_after(line, "hcm_").into_iter().take(1))
        .map(|name| format!("hcm_{name}"))
        .collect();
    declared.sort();
    assert_eq!(
        declared, exported,
        "regenerate include/hcm.h (see cbindgen.toml)"
    );
}

#[test]
fn every_constant_and_struct_is_in_the_header_with_its_value() {
    let (sources, header) = (sources(), header());
    for line in sources.lines().map(str::trim) {
        if let Some(rest) = line.strip_prefix("pub const HCM_") {
            let (name, value) = rest.split_once(':').unwrap();
            let value = value
                .rsplit_once('=')
                .unwrap()
                .1
                .trim()
                .trim_end_matches(';');
            let define = format!("#define HCM_{name} {value}\n");
            assert!(
                header.contains(&define),
                "{define:?} missing: regenerate include/hcm.h"
            );
        }
    }
    for name in names_after(&sources, "pub struct Hcm") {
        let typedef = format!("typedef struct Hcm{name} {{");
        let aligned = format!("Hcm{name} {{");
        assert!(
            header.contains(&typedef) || header.contains(&aligned),
            "Hcm{name} missing: regenerate include/hcm.h"
        );
    }
}

#[test]
fn every_status_code_is_in_the_header_with_its_value() {
    let header = header();
    let mut found = 0;
    for code in -1..64 {
        // SAFETY: `hcm_status_name` returns a static NUL-terminated string.
        let name = unsafe { CStr::from_ptr(hcm_status_name(code)) }
            .to_str()
            .unwrap();
        if HcmStatus::from_code(code).is_some() {
            assert!(
                header.contains(&format!("  {name} = {code},\n")),
                "{name} = {code}"
            );
            found += 1;
        }
    }
    assert_eq!(found, header.matches("  HCM_STATUS_").count());
}

/// The exact check, where the generator is at hand (developer machines); CI without
/// cbindgen relies on the checks above and on compiling the C example against it.
#[test]
fn the_header_is_what_cbindgen_generates_now() {
    let workspace = crate_dir().join("..");
    let output = std::env::temp_dir().join(format!("hcm-ffi-header-{}.h", std::process::id()));
    let run = Command::new("cbindgen")
        .current_dir(&workspace)
        .args([
            "--config",
            "hcm-ffi/cbindgen.toml",
            "--crate",
            "hcm-ffi",
            "--quiet",
        ])
        .arg("--output")
        .arg(&output)
        .output();
    let Ok(run) = run else {
        println!("cbindgen is not installed: exact header comparison skipped");
        return;
    };
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let generated = std::fs::read_to_string(&output).unwrap();
    let _ = std::fs::remove_file(Path::new(&output));
    assert!(
        generated == header(),
        "include/hcm.h is stale: cbindgen --config hcm-ffi/cbindgen.toml --crate hcm-ffi \
         --output hcm-ffi/include/hcm.h"
    );
}

//! `hcm … | head` closes the pipe before hcm is done writing: hcm ends quietly with the
//! status a shell gives a process killed by SIGPIPE (141), not with a panic report.

use hcm_tests::cli::hcm_exe;
use std::process::{Command, Stdio};

#[test]
fn a_closed_stdout_ends_hcm_quietly() {
    let mut child = Command::new(hcm_exe())
        .arg("laws")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Close the reading end before hcm writes its first line.
    drop(child.stdout.take());
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(141), "stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}

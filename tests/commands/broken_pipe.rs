//! `hcm … | head` closes the pipe before hcm is done writing: hcm ends quietly with the
//! status a shell gives a process killed by SIGPIPE (141), not with a panic report.

use hcm_tests::cli::hcm_exe;
use std::process::{Command, Stdio};

#[test]
fn a_closed_stdout_ends_hcm_quietly() {
    // The pipe's reading end is closed before hcm starts, so its first write fails
    // whatever the scheduling. (Closing it after the spawn raced hcm: on a loaded
    // machine `hcm laws` could write all of its short output into the pipe's buffer
    // first and exit 0.)
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let child = Command::new(hcm_exe())
        .arg("laws")
        .stdout(writer)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(141), "stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}

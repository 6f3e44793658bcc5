//! Running the real `bzspline` binary in the fixtures folder, shared by the
//! command's test files.
#![allow(dead_code)] // each test file uses some of these

pub mod gdal;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

pub const BIN: &str = env!("CARGO_BIN_EXE_bzspline");

pub fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

pub struct Out {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// Runs the binary in the fixtures folder (so messages name the file as given).
pub fn run(args: &[&str], stdin: Option<&[u8]>) -> Out {
    let mut cmd = Command::new(BIN);
    cmd.args(args)
        .current_dir(fixture(""))
        .stdin(if stdin.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        })
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("the binary runs");
    if let Some(bytes) = stdin {
        let mut si = child.stdin.take().expect("stdin is piped");
        // A command that refuses its arguments exits before reading.
        match si.write_all(bytes) {
            Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => panic!("writing stdin: {e}"),
            _ => {}
        }
    }
    let out = child.wait_with_output().expect("the binary finishes");
    Out {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8(out.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(out.stderr).expect("stderr is UTF-8"),
    }
}

/// Runs the command, asserts that it succeeded (notes on standard error
/// allowed), and gives its standard output.
pub fn succeeds(args: &[&str]) -> String {
    let o = run(args, None);
    assert_eq!(o.code, 0, "{args:?}: {}", o.stderr);
    o.stdout
}

pub fn ok(args: &[&str]) -> String {
    let o = run(args, None);
    assert_eq!(o.code, 0, "{args:?} failed: {}", o.stderr);
    assert!(
        o.stderr.is_empty(),
        "{args:?} wrote to stderr: {}",
        o.stderr
    );
    o.stdout
}

/// A data error: exit code 1, one line on stderr naming the place, nothing on
/// stdout, and no file created by `-o`.
pub fn assert_data_error(args: &[&str], stdin: Option<&[u8]>, wants: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.txt");
    let mut all: Vec<&str> = args.to_vec();
    let out_s = out.to_str().unwrap().to_owned();
    all.extend(["-o", &out_s]);
    let o = run(&all, stdin);
    assert_eq!(o.code, 1, "{args:?}: exit code; stderr {}", o.stderr);
    assert!(o.stdout.is_empty(), "{args:?}: stdout {}", o.stdout);
    assert_eq!(o.stderr.lines().count(), 1, "{args:?}: {}", o.stderr);
    assert!(o.stderr.starts_with("error: "), "{args:?}: {}", o.stderr);
    for w in wants {
        assert!(
            o.stderr.contains(w),
            "{args:?}: wanted {w:?} in {}",
            o.stderr
        );
    }
    assert!(!out.exists(), "{args:?}: -o file was written");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "{args:?}: a temporary file was left behind"
    );
}

/// The README and every page of the guide in `docs/`, one after another: the
/// text the tests that keep printed outputs true search.
pub fn guide() -> String {
    let top = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut text = std::fs::read_to_string(top.join("README.md")).unwrap();
    let mut pages: Vec<_> = std::fs::read_dir(top.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    pages.sort();
    for page in pages {
        text += &std::fs::read_to_string(page).unwrap();
    }
    text
}

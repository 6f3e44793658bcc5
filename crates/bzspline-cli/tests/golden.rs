//! The `fit` output of a saved corpus, reproduced bit for bit: the paper's
//! examples, random y(x) with one or per-interval alphas, open and closed
//! curves in 2D and 3D with every parametrisation, values near the ends of
//! the double range (`tests/golden/cases.txt`). A change to the construction
//! that moves any digit fails here; one that is meant to says why in its
//! commit and saves the corpus again:
//!
//! ```sh
//! cd crates/bzspline-cli/tests/golden
//! grep -v '^#' cases.txt | while IFS='|' read -r name input args; do
//!     ../../../../target/debug/bzspline fit $input $args > $(echo $name).json
//! done
//! ```

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_bzspline");

#[test]
fn fit_reproduces_the_saved_corpus_bit_for_bit() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let cases = std::fs::read_to_string(dir.join("cases.txt")).unwrap();
    let mut checked = 0;
    for line in cases
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let parts: Vec<&str> = line.split('|').map(str::trim).collect();
        let [name, input, args] = parts[..] else {
            panic!("cases.txt: {line}")
        };
        let out = Command::new(BIN)
            .arg("fit")
            .args(input.split_whitespace())
            .args(args.split_whitespace())
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let want = std::fs::read(dir.join(format!("{name}.json"))).unwrap();
        assert!(
            out.stdout == want,
            "{name}: the fit differs from the saved one:\n{}",
            String::from_utf8_lossy(&out.stdout)
        );
        checked += 1;
    }
    assert_eq!(checked, 42);
}
